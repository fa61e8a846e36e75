// The JSON view of the connected workers for GET /api/workers.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "coordinator/scheduler/scheduler.h"

namespace tessera {

// One object a worker: its name, address and threads, what it holds and has done, its round
// trip, and its whole-life pixels per second (the page shows a recent rate of its own).
nlohmann::json workers_json(const std::vector<Scheduler::WorkerView>& workers);

}  // namespace tessera
