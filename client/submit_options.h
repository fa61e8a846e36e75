// tessera-submit's command line (CLI11): the scene, --coordinator URL, --tls-ca, -o OUT, --token,
// --root, and every setting of a job request (common/settings/settings_schema.h) as the same flag
// as tessera-render's, with the same ranges and help.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "common/protocol/tls.h"
#include "common/settings/settings_schema.h"

namespace tessera {

struct SubmitOptions {
  std::string scene_path;
  std::string coordinator;  // http://HOST:PORT or https://HOST:PORT
  ClientTlsOptions tls;     // for https: the certificates trusted (the system's by default)
  std::string output_path;  // empty: leave the image on the coordinator
  std::string token;        // the coordinator's --api-token, if it has one
  std::string root;         // non-empty: the folder the bundle's paths are relative to
  bool quiet = false;
  JobSettings settings;
};

struct SubmitHelp {};

// Parses the arguments after the program's name; an error names the bad flag and value.
std::variant<SubmitOptions, SubmitHelp, std::string> parse_submit_cli(
    const std::vector<std::string>& args);
std::string submit_cli_usage();

// The settings given on the command line as a job request's settings object: those that differ
// from the schema's defaults (the service's defaults are the same).
std::string settings_json(const JobSettings& settings);

}  // namespace tessera
