// Command line of tessera-coordinator (CLI11; docs/SERVICE.md lists the options):
//   --http-port P --worker-port Q [--secret S | --insecure] [--local-workers N]
//   [--local-threads T] [--scenes-dir DIR] [--web-dir DIR] [--bind ADDR]
//   [--worker-binary PATH] [--max-job-seconds S] [--max-body-bytes N] [--heartbeat-ms MS]
//   [--silence-ms MS] [--intake-threads N] [--max-intake-seconds S]
//   [--max-http-connections N] [--api-token T | --open-submit] [--allow-origin O]...
//   [--max-jobs-per-client N] [--tls-cert FILE --tls-key FILE] [--data-dir DIR]
//   [--keep-finished DURATION] [--max-disk BYTES]
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/protocol/connection.h"
#include "coordinator/http/submit_policy.h"
#include "coordinator/jobs/limits.h"

namespace tessera {

struct CoordinatorOptions {
  std::string bind = "0.0.0.0";
  unsigned short http_port = 8080;
  unsigned short worker_port = 7701;
  std::string secret;  // from --secret or TESSERA_SECRET
  bool insecure = false;
  int local_workers = 0;
  int local_threads = 0;  // per local worker; 0: the cores shared out
  std::optional<std::filesystem::path> scenes_dir;
  std::filesystem::path web_dir;
  std::filesystem::path worker_binary;
  // Written once both ports listen: {"http_port": P, "worker_port": Q}. With ports 0 (the
  // system picks free ones) it is how tests and scripts learn them without racing for ports.
  std::optional<std::filesystem::path> port_file;
  ServiceLimits limits;
  ConnectionTiming timing;
  int intake_threads = 2;       // scene loading, probes and encodings, off the io thread
  int max_intake_seconds = 10;  // wall time of one submission or prediction
  int max_http_connections = 256;
  SubmitPolicy submit;          // --api-token (TESSERA_API_TOKEN), --open-submit, --allow-origin
  int max_jobs_per_client = 8;  // unfinished jobs per peer address
  // Both or neither: HTTPS and TLS on the worker port (PEM files).
  std::optional<std::filesystem::path> tls_cert, tls_key;
  // The durable job store (docs/SERVICE.md "Data directory"): finished jobs are kept for
  // keep_finished and, oldest first, within max_disk_bytes.
  std::filesystem::path data_dir = "tessera-data";
  std::chrono::seconds keep_finished = std::chrono::hours(24 * 7);
  std::int64_t max_disk_bytes = std::numeric_limits<std::int64_t>::max();
};

struct CoordinatorHelp {};  // --help was asked for

// Parses the arguments after the program's name; returns the options, CoordinatorHelp, or an
// error message naming the bad flag and value. TESSERA_SECRET and TESSERA_API_TOKEN stand in for
// --secret and --api-token.
std::variant<CoordinatorOptions, CoordinatorHelp, std::string> parse_coordinator_options(
    const std::vector<std::string>& args);
std::string coordinator_usage();
// "3600s", "90m", "12h", "7d" (a bare number is seconds); throws std::invalid_argument.
std::chrono::seconds parse_duration(const std::string& flag, const std::string& text);
// "1048576", "512K", "512M", "2G" (powers of 1024); throws std::invalid_argument.
std::int64_t parse_bytes(const std::string& flag, const std::string& text);

}  // namespace tessera
