// tessera-worker: renders work units for a coordinator (docs/SERVICE.md).
#include <boost/asio/io_context.hpp>

#include "worker/options.h"
#include "worker/session/worker_session.h"

int main(int argc, char** argv) {
  auto parsed = tessera::parse_worker_options(argc, argv);
  if (const int* exit_status = std::get_if<int>(&parsed)) return *exit_status;
  boost::asio::io_context io;
  tessera::WorkerSession session(io, std::get<tessera::WorkerConfig>(parsed));
  session.start();
  io.run();
  return session.fatal_error().empty() ? 0 : 1;
}
