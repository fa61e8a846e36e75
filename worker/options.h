// Command line of tessera-worker (CLI11): --coordinator [tls://]HOST:PORT [--secret S]
// [--threads N] [--name NAME] [--tls-ca FILE | --tls-insecure]. The link is TLS when the address
// starts with tls:// or either TLS flag is given. The secret may come from TESSERA_SECRET instead,
// so it stays out of `ps`.
#pragma once

#include <variant>

#include "worker/session/worker_session.h"

namespace tessera {

// The configuration, or the exit status to stop with: 0 after --help, 2 after a usage error
// (both already printed).
std::variant<WorkerConfig, int> parse_worker_options(int argc, char** argv);

}  // namespace tessera
