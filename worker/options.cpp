#include "worker/options.h"

#include <unistd.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

namespace tessera {

const char* const kWorkerUsage =
    "usage: tessera-worker --coordinator HOST:PORT [--secret S] [--threads N] [--name NAME]";

namespace {

int parse_threads(const std::string& s) {
  char* end = nullptr;
  const long n = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || n < 1 || n > 1024)
    throw std::invalid_argument("--threads takes a number in [1, 1024]\n" +
                                std::string(kWorkerUsage));
  return static_cast<int>(n);
}
}  // namespace

WorkerConfig parse_worker_options(int argc, char** argv) {
  WorkerConfig config;
  config.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (const char* s = std::getenv("TESSERA_SECRET")) config.secret = s;
  std::string coordinator;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value\n" + kWorkerUsage);
      return argv[++i];
    };
    if (arg == "--coordinator")
      coordinator = value();
    else if (arg == "--secret")
      config.secret = value();
    else if (arg == "--threads")
      config.threads = parse_threads(value());
    else if (arg == "--name")
      config.name = value();
    else
      throw std::invalid_argument("unknown argument " + arg + "\n" + kWorkerUsage);
  }
  const auto colon = coordinator.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == coordinator.size())
    throw std::invalid_argument(std::string("--coordinator HOST:PORT is required\n") +
                                kWorkerUsage);
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
