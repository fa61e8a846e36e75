#include "worker/options.h"

#include <unistd.h>

#include <algorithm>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>

namespace tessera {

std::variant<WorkerConfig, int> parse_worker_options(int argc, char** argv) {
  WorkerConfig config;
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string coordinator;
  CLI::App app("tessera-worker: renders work units for a coordinator (docs/SERVICE.md)",
               "tessera-worker");
  app.add_option("--coordinator", coordinator, "the coordinator's worker port")
      ->option_text("HOST:PORT")
      ->required()
      ->check([](const std::string& s) -> std::string {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help, or a usage error (printed)
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
