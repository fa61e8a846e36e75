// tessera-worker: renders work units for a coordinator (docs/SERVICE.md).
#include <spdlog/spdlog.h>
#include <boost/asio/io_context.hpp>
#include <cstdio>
#include <string_view>

#include "worker/options.h"
#include "worker/session/worker_session.h"

int main(int argc, char** argv) {
  tessera::WorkerConfig config;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--help" || std::string_view(argv[i]) == "-h") {
      std::puts(tessera::kWorkerUsage);
      return 0;
    }
  try {
    config = tessera::parse_worker_options(argc, argv);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  boost::asio::io_context io;
  tessera::WorkerSession session(io, config);
  session.start();
  io.run();
  return session.fatal_error().empty() ? 0 : 1;
}
