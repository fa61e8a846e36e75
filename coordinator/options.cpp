#include "coordinator/options.h"

#include <cstdlib>
#include <stdexcept>

#include "coordinator/workers/local_workers.h"

namespace tessera {

namespace {}  // namespace

const char* const kCoordinatorUsage =
    "usage: tessera-coordinator --http-port P --worker-port Q [--secret S | --insecure]\n"
    "       [--local-workers N] [--local-threads T] [--scenes-dir DIR] [--web-dir DIR]\n"
    "       [--bind ADDR] [--worker-binary PATH] [--max-job-seconds S] [--max-body-bytes N]\n"
    "       [--heartbeat-ms MS] [--silence-ms MS] [--port-file PATH] [--intake-threads N]\n"
    "       [--max-intake-seconds S] [--max-http-connections N] [--api-token T | --open-submit]\n"
    "       [--allow-origin ORIGIN]... [--max-jobs-per-client N]\n"
    "       [--tls-cert FILE --tls-key FILE]";

namespace {

long parse_number(const std::string& flag, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < lo || v > hi)
    throw std::invalid_argument(flag + " takes a number in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]\n" + kCoordinatorUsage);
  return v;
}

}  // namespace

CoordinatorOptions parse_coordinator_options(int argc, char** argv) {
  CoordinatorOptions o;
  if (const char* s = std::getenv("TESSERA_SECRET")) o.secret = s;
  if (const char* t = std::getenv("TESSERA_API_TOKEN")) o.submit.api_token = t;
  o.web_dir = TESSERA_WEB_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value\n" + kCoordinatorUsage);
      return argv[++i];
    };
    if (arg == "--http-port")
      o.http_port = static_cast<unsigned short>(parse_number(arg, value(), 0, 65535));
    else if (arg == "--worker-port")
      o.worker_port = static_cast<unsigned short>(parse_number(arg, value(), 0, 65535));
    else if (arg == "--secret")
      o.secret = value();
    else if (arg == "--insecure")
      o.insecure = true;
    else if (arg == "--local-workers")
      o.local_workers = static_cast<int>(parse_number(arg, value(), 0, 64));
    else if (arg == "--local-threads")
      o.local_threads = static_cast<int>(parse_number(arg, value(), 1, 1024));
    else if (arg == "--scenes-dir")
      o.scenes_dir = value();
    else if (arg == "--web-dir")
      o.web_dir = value();
    else if (arg == "--bind")
      o.bind = value();
    else if (arg == "--port-file")
      o.port_file = value();
    else if (arg == "--worker-binary")
      o.worker_binary = value();
    else if (arg == "--max-job-seconds")
      o.limits.max_job_seconds = static_cast<double>(parse_number(arg, value(), 1, 86400));
    else if (arg == "--max-body-bytes")
      o.limits.max_body_bytes =
          static_cast<std::size_t>(parse_number(arg, value(), 1024, 1L << 30));
    else if (arg == "--heartbeat-ms")
      o.timing.heartbeat = std::chrono::milliseconds(parse_number(arg, value(), 10, 60000));
    else if (arg == "--silence-ms")
      o.timing.silence = std::chrono::milliseconds(parse_number(arg, value(), 50, 600000));
    else if (arg == "--intake-threads")
      o.intake_threads = static_cast<int>(parse_number(arg, value(), 1, 64));
    else if (arg == "--max-intake-seconds")
      o.max_intake_seconds = static_cast<int>(parse_number(arg, value(), 1, 3600));
    else if (arg == "--max-http-connections")
      o.max_http_connections = static_cast<int>(parse_number(arg, value(), 1, 65536));
    else if (arg == "--api-token")
      o.submit.api_token = value();
    else if (arg == "--open-submit")
      o.submit.open_submit = true;
    else if (arg == "--allow-origin")
      o.submit.allowed_origins.push_back(value());
    else if (arg == "--max-jobs-per-client")
      o.max_jobs_per_client = static_cast<int>(parse_number(arg, value(), 1, 1024));
    else if (arg == "--tls-cert")
      o.tls_cert = value();
    else if (arg == "--tls-key")
      o.tls_key = value();
    else
      throw std::invalid_argument("unknown argument " + arg + "\n" + kCoordinatorUsage);
  }
  if (o.insecure && !o.secret.empty())
    throw std::invalid_argument(std::string("--secret and --insecure exclude each other\n") +
                                kCoordinatorUsage);
  if (o.tls_cert.has_value() != o.tls_key.has_value())
    throw std::invalid_argument(std::string("--tls-cert and --tls-key go together\n") +
                                kCoordinatorUsage);
  if (o.timing.silence <= o.timing.heartbeat)
    throw std::invalid_argument("--silence-ms must exceed --heartbeat-ms");
  if (o.worker_binary.empty()) o.worker_binary = default_worker_binary();
  return o;
}

}  // namespace tessera
