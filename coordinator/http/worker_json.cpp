#include "coordinator/http/worker_json.h"

namespace tessera {

nlohmann::json workers_json(const std::vector<Scheduler::WorkerView>& workers) {
  nlohmann::json out = nlohmann::json::array();
  for (const Scheduler::WorkerView& w : workers)
    out.push_back(
        {{"id", w.id},
         {"name", w.name},
         {"address", w.address},
         {"threads", w.threads},
         {"in_flight", w.in_flight},
         {"slots", w.slots},
         {"round_trip_ms", w.round_trip_seconds * 1e3},
         {"units_done", w.units_done},
         {"dropped_results", w.dropped_results},
         {"pixels_done", w.pixels_done},
         {"busy_seconds", w.busy_seconds},
         {"connected_seconds", w.connected_seconds},
         {"pixels_per_second", w.connected_seconds > 0
                                   ? static_cast<double>(w.pixels_done) / w.connected_seconds
                                   : 0.0}});
  return out;
}

}  // namespace tessera
