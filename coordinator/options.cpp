#include "coordinator/options.h"

#include <cctype>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "coordinator/workers/local_workers.h"

namespace tessera {

namespace {

// A number with a unit suffix: "90m" -> 90 * units.at('m'); no suffix multiplies by 1.
std::int64_t parse_scaled(const std::string& flag, const std::string& text,
                          const std::map<char, std::int64_t>& units, const char* what) {
  const auto fail = [&] {
    return std::invalid_argument(flag + " takes " + what + ", not \"" + text + "\"");
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

namespace {

// A flag whose value parse(flag, text) reads, or refuses with a message naming both.
template <typename T>
void add_parsed(CLI::App& app, const std::string& flag, T& value, const std::string& help,
                T (*parse)(const std::string&, const std::string&)) {
  app.add_option_function<std::string>(
         flag, [&value, flag, parse](const std::string& text) { value = parse(flag, text); }, help)
      ->check(CLI::Validator(
          [flag, parse](std::string& text) -> std::string {
            try {
              parse(flag, text);
              return {};
            } catch (const std::invalid_argument& e) {
              return e.what();
            }
          },
          ""));
}

// Values whose flags read another type than CoordinatorOptions holds (paths that may be left
// unset, milliseconds), moved into it after parsing.
struct Flags {
  std::string scenes_dir, port_file, tls_cert, tls_key, worker_binary;
  std::string web_dir = TESSERA_WEB_DIR, data_dir = CoordinatorOptions().data_dir.string();
  int max_job_seconds = 0, heartbeat_ms = 0, silence_ms = 0;
  std::size_t max_body_bytes = 0;
};

std::unique_ptr<CLI::App> make_app(CoordinatorOptions& o, Flags& f) {
  auto app = std::make_unique<CLI::App>(
      "tessera-coordinator: the HTTP API and page, the job store and the scheduler, and the "
      "port workers connect to (docs/SERVICE.md)",
      "tessera-coordinator");
  app->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app->add_option("--http-port", o.http_port, "the page and the API (0 picks a free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app->add_option("--worker-port", o.worker_port, "where workers connect (0 picks a free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  app->add_option("--secret", o.secret, "shared secret workers must prove")
      ->envname("TESSERA_SECRET");
  app->add_flag("--insecure", o.insecure, "no authentication at all (trusted networks, tests)");
  app->add_option("--local-workers", o.local_workers, "start N workers on this machine")
      ->check(CLI::Range(0, 64));
  app->add_option("--local-threads", o.local_threads,
                  "threads per local worker (default: cores / N)")
      ->check(CLI::Range(1, 1024));
  app->add_option("--scenes-dir", f.scenes_dir,
                  "scenes may include files from DIR; {\"scene_file\": PATH} renders DIR/PATH");
  app->add_option("--web-dir", f.web_dir, "where the page's files are")->capture_default_str();
  app->add_option("--bind", o.bind, "listen address for both ports")->capture_default_str();
  app->add_option("--port-file", f.port_file,
                  "once both ports listen, write {\"http_port\": P, \"worker_port\": Q} here");
  app->add_option("--worker-binary", f.worker_binary,
                  "the worker for --local-workers (default: next to the coordinator)");
  app->add_option("--max-job-seconds", f.max_job_seconds, "a job running longer fails (600)")
      ->check(CLI::Range(1, 86400));
  app->add_option("--max-body-bytes", f.max_body_bytes, "request bodies over N get 413 (32 MiB)")
      ->check(CLI::Range(std::size_t{1024}, std::size_t{1} << 30));
  app->add_option("--max-pixels", o.limits.max_pixels,
                  "a job's width x height at most (7680 x 4320)")
      ->check(CLI::Range(1LL, 16384LL * 16384))
      ->capture_default_str();
  app->add_option("--heartbeat-ms", f.heartbeat_ms, "heartbeat interval (2000)")
      ->check(CLI::Range(10, 60000));
  app->add_option("--silence-ms", f.silence_ms, "silence after which a peer is dropped (10000)")
      ->check(CLI::Range(50, 600000));
  app->add_option("--intake-threads", o.intake_threads,
                  "threads that load, prepare and probe scenes and encode images")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app->add_option("--max-intake-seconds", o.max_intake_seconds,
                  "wall time of one submission or prediction")
      ->check(CLI::Range(1, 3600))
      ->capture_default_str();
  app->add_option("--max-http-connections", o.max_http_connections, "open HTTP connections")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  app->add_option("--api-token", o.submit.api_token,
                  "POST and DELETE need Authorization: Bearer TOKEN, from every address")
      ->envname("TESSERA_API_TOKEN");
  app->add_flag("--open-submit", o.submit.open_submit,
                "without a token, any address may POST and DELETE (default: only loopback)");
  app->add_option("--allow-origin", o.submit.allowed_origins,
                  "a page at ORIGIN may POST and DELETE too; repeatable")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app->add_option("--max-jobs-per-client", o.max_jobs_per_client,
                  "unfinished jobs per client address")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app->add_option("--tls-cert", f.tls_cert, "HTTPS and TLS on the worker port: certificate (PEM)");
  app->add_option("--tls-key", f.tls_key, "and its key (PEM); both or neither");
  app->add_option("--data-dir", f.data_dir, "where jobs are kept across restarts")
      ->capture_default_str();
  add_parsed(*app, "--keep-finished", o.keep_finished,
             "how long finished jobs are kept: 3600s, 90m, 12h, 7d (default 7d)", parse_duration);
  add_parsed(*app, "--max-disk", o.max_disk_bytes,
             "the data directory's budget: 512M, 2G (default unlimited)", parse_bytes);
  return app;
}

}  // namespace

std::variant<CoordinatorOptions, CoordinatorHelp, std::string> parse_coordinator_options(
    const std::vector<std::string>& args) {
  CoordinatorOptions o;
  Flags f;
  const std::unique_ptr<CLI::App> app = make_app(o, f);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // as CLI11 reads them
  try {
    app->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return CoordinatorHelp{};
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  const auto given = [&](const char* flag) { return app->count(flag) > 0; };
  o.web_dir = f.web_dir;
  o.data_dir = f.data_dir;
  if (given("--scenes-dir")) o.scenes_dir = f.scenes_dir;
  if (given("--port-file")) o.port_file = f.port_file;
  if (given("--tls-cert")) o.tls_cert = f.tls_cert;
  if (given("--tls-key")) o.tls_key = f.tls_key;
  if (given("--max-job-seconds")) o.limits.max_job_seconds = f.max_job_seconds;
  if (given("--max-body-bytes")) o.limits.max_body_bytes = f.max_body_bytes;
  if (given("--heartbeat-ms")) o.timing.heartbeat = std::chrono::milliseconds(f.heartbeat_ms);
  if (given("--silence-ms")) o.timing.silence = std::chrono::milliseconds(f.silence_ms);
  if (o.insecure && !o.secret.empty())
    return std::string("--secret and --insecure exclude each other");
  if (o.tls_cert.has_value() != o.tls_key.has_value())
    return std::string("--tls-cert and --tls-key go together");
  if (o.timing.silence <= o.timing.heartbeat)
    return std::string("--silence-ms must exceed --heartbeat-ms");
  o.worker_binary =
      f.worker_binary.empty() ? default_worker_binary() : std::filesystem::path(f.worker_binary);
  return o;
}

std::string coordinator_usage() {
  CoordinatorOptions o;
  Flags f;
  return make_app(o, f)->help();
}

}  // namespace tessera
