// The coordinator's jobs by id, oldest first. Finished jobs are evicted, oldest first, when
// more than ServiceLimits::max_jobs are held.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>

#include "coordinator/jobs/job.h"
#include "coordinator/jobs/job_request.h"

namespace tessera {

class JobStore {
 public:
  explicit JobStore(int max_jobs) : max_jobs_(max_jobs) {}
  // Returns nullptr when the store is full of unfinished jobs. `assign_id`, when given, picks
  // the id (the durable store's); it may throw, and then nothing is created.
  Job* create(JobRequest request, std::string client = {},
              const std::function<std::int64_t(const JobRequest&)>& assign_id = {});
  // Drops a job retention deleted from the durable store.
  void forget(std::int64_t id) { jobs_.erase(id); }
  // Queued and running jobs submitted from `client`.
  int unfinished_of(const std::string& client) const;
  Job* find(std::int64_t id);
  const std::map<std::int64_t, std::unique_ptr<Job>>& all() const { return jobs_; }

 private:
  int max_jobs_;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, std::unique_ptr<Job>> jobs_;
};

}  // namespace tessera
