// Command line of tessera-coordinator (docs/SERVICE.md):
//   --http-port P --worker-port Q [--secret S | --insecure] [--local-workers N]
//   [--local-threads T] [--scenes-dir DIR] [--web-dir DIR] [--bind ADDR]
//   [--worker-binary PATH] [--max-job-seconds S] [--max-body-bytes N] [--heartbeat-ms MS]
//   [--silence-ms MS] [--intake-threads N] [--max-intake-seconds S]
//   [--max-http-connections N] [--api-token T | --open-submit] [--allow-origin O]...
//   [--max-jobs-per-client N] [--tls-cert FILE --tls-key FILE]
#pragma once

#include <filesystem>
#include <optional>
#include <string>

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
};

extern const char* const kCoordinatorUsage;

// Throws std::invalid_argument with a usage message.
CoordinatorOptions parse_coordinator_options(int argc, char** argv);

}  // namespace tessera
