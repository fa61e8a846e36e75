#include "coordinator/options.h"

#include <cctype>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>

#include "coordinator/workers/local_workers.h"

namespace tessera {

const char* const kCoordinatorUsage =
    "usage: tessera-coordinator --http-port P --worker-port Q [--secret S | --insecure]\n"
    "       [--local-workers N] [--local-threads T] [--scenes-dir DIR] [--web-dir DIR]\n"
    "       [--bind ADDR] [--worker-binary PATH] [--max-job-seconds S] [--max-body-bytes N]\n"
    "       [--heartbeat-ms MS] [--silence-ms MS] [--port-file PATH] [--intake-threads N]\n"
    "       [--max-intake-seconds S] [--max-http-connections N] [--api-token T | --open-submit]\n"
    "       [--allow-origin ORIGIN]... [--max-jobs-per-client N]\n"
    "       [--tls-cert FILE --tls-key FILE] [--data-dir DIR]\n"
    "       [--keep-finished DURATION] [--max-disk BYTES] [--max-pixels N]\n"
    "  --data-dir DIR            where jobs are kept across restarts (default ./tessera-data)\n"
    "  --keep-finished DURATION  how long finished jobs are kept: 3600s, 90m, 12h, 7d (default "
    "7d)\n"
    "  --max-disk BYTES          the data directory's budget: 512M, 2G (default unlimited)\n"
    "  --max-pixels N            a job's width x height at most (default 33177600, 7680x4320)";

namespace {

long parse_number(const std::string& flag, const std::string& text, long lo, long hi) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < lo || v > hi)
    throw std::invalid_argument(flag + " takes a number in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]\n" + kCoordinatorUsage);
  return v;
}

// A number with a unit suffix: "90m" -> 90 * units.at('m'); no suffix multiplies by 1.
std::int64_t parse_scaled(const std::string& flag, const std::string& text,
                          const std::map<char, std::int64_t>& units, const char* what) {
  const auto fail = [&] {
    return std::invalid_argument(flag + " takes " + what + ", not \"" + text + "\"\n" +
                                 kCoordinatorUsage);
  };
  std::size_t digits = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
  if (digits == 0 || digits > 15 || text.size() > digits + 1) throw fail();
  std::int64_t scale = 1;
  if (text.size() == digits + 1) {
    const auto unit = units.find(text.back());
    if (unit == units.end()) throw fail();
    scale = unit->second;
  }
  const std::int64_t value = std::stoll(text.substr(0, digits));
  if (value <= 0 || value > std::numeric_limits<std::int64_t>::max() / scale) throw fail();
  return value * scale;
}

}  // namespace

std::chrono::seconds parse_duration(const std::string& flag, const std::string& text) {
  return std::chrono::seconds(parse_scaled(flag, text,
                                           {{'s', 1}, {'m', 60}, {'h', 3600}, {'d', 86400}},
                                           "a duration like 3600s, 90m, 12h or 7d"));
}

std::int64_t parse_bytes(const std::string& flag, const std::string& text) {
  return parse_scaled(flag, text, {{'K', 1LL << 10}, {'M', 1LL << 20}, {'G', 1LL << 30}},
                      "a size like 1048576, 512K, 512M or 2G");
}

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
    else if (arg == "--max-pixels")
      o.limits.max_pixels = parse_number(arg, value(), 1, 16384LL * 16384);
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
    else if (arg == "--data-dir")
      o.data_dir = value();
    else if (arg == "--keep-finished")
      o.keep_finished = parse_duration(arg, value());
    else if (arg == "--max-disk")
      o.max_disk_bytes = parse_bytes(arg, value());
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
