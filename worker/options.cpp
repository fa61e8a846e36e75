#include "worker/options.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <string_view>
#include <thread>

#include <CLI/CLI.hpp>

namespace tessera {

namespace {
constexpr std::string_view kTlsScheme = "tls://";
}  // namespace

std::variant<WorkerConfig, int> parse_worker_options(int argc, char** argv) {
  WorkerConfig config;
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string coordinator;
  ClientTlsOptions tls;
  std::string ca;
  CLI::App app("tessera-worker: renders work units for a coordinator (docs/SERVICE.md)",
               "tessera-worker");
  app.add_option("--coordinator", coordinator, "the coordinator's worker port")
      ->option_text("[tls://]HOST:PORT")
      ->required()
      ->check([](std::string s) -> std::string {
        if (s.starts_with(kTlsScheme)) s.erase(0, kTlsScheme.size());
        const auto colon = s.rfind(':');
        if (colon == std::string::npos || colon == 0 || colon + 1 == s.size())
          return "expected HOST:PORT";
        return {};
      });
  app.add_option("--secret", config.secret, "the secret shared with the coordinator")
      ->envname("TESSERA_SECRET");
  app.add_option("--threads", config.threads, "render threads (default: every core)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--name", config.name, "the name the coordinator shows (default: host:pid)");
  // TLS is on when any of these three asks for it (docs/SERVICE.md).
  auto* ca_option =
      app.add_option("--tls-ca", ca, "connect with TLS, trusting these certificates (PEM)")
          ->check(CLI::ExistingFile);
  app.add_flag("--tls-insecure", tls.insecure,
               "connect with TLS without verifying the coordinator's certificate")
      ->excludes(ca_option);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help, or a usage error (printed)
  }
  const bool tls_scheme = coordinator.starts_with(kTlsScheme);
  if (tls_scheme) coordinator.erase(0, kTlsScheme.size());
  if (!ca.empty()) tls.ca = ca;
  if (tls_scheme || tls.ca || tls.insecure) {
    try {
      config.tls = make_client_tls(tls);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    }
  }
  const auto colon = coordinator.rfind(':');
  config.host = coordinator.substr(0, colon);
  config.port = coordinator.substr(colon + 1);
  if (config.name.empty()) {
    char host[256] = {};
    gethostname(host, sizeof host - 1);
    config.name = std::string(host) + ":" + std::to_string(getpid());
  }
  return config;
}

}  // namespace tessera
