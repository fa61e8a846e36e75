// Command line of tessera-worker (CLI11): --coordinator HOST:PORT [--secret S] [--threads N]
// [--name NAME]. The secret may come from TESSERA_SECRET instead, so it stays out of `ps`.
#pragma once

#include <variant>

#include "worker/session/worker_session.h"

namespace tessera {

// The configuration, or the exit status to stop with: 0 after --help, 2 after a usage error
// (both already printed).
std::variant<WorkerConfig, int> parse_worker_options(int argc, char** argv);

}  // namespace tessera
