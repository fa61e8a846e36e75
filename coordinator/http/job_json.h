// The JSON views of a job for GET /api/jobs and GET /api/jobs/{id}.
#pragma once

#include <nlohmann/json.hpp>

#include "coordinator/jobs/job.h"

namespace tessera {

nlohmann::json job_summary_json(const Job& job, Clock::time_point now);
// Everything the page shows: state, level, pass, progress, estimate, the per-level table
// (Figure 5.1.1 of the seeds), effects, statistics and per-worker shares.
nlohmann::json job_status_json(const Job& job, Clock::time_point now);
// The job's settings as POST /api/jobs takes them: parse_settings of this gives the job's spec,
// plan options and priority again, which a rerender builds on (tests/service/coordinator_test).
nlohmann::json job_settings_json(const Job& job);

}  // namespace tessera
