// Command line of tessera-worker: --coordinator HOST:PORT [--secret S] [--threads N]
// [--name NAME]. The secret may come from TESSERA_SECRET instead, so it stays out of `ps`.
#pragma once

#include "worker/session/worker_session.h"

namespace tessera {

extern const char* const kWorkerUsage;

// Throws std::invalid_argument with a usage message.
WorkerConfig parse_worker_options(int argc, char** argv);

}  // namespace tessera
