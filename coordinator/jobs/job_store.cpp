#include "coordinator/jobs/job_store.h"

#include <algorithm>

namespace tessera {

Job* JobStore::create(JobRequest request, std::string client,
                      const std::function<std::int64_t(const JobRequest&)>& assign_id) {
  for (auto it = jobs_.begin(); static_cast<int>(jobs_.size()) >= max_jobs_ && it != jobs_.end();)
    it = it->second->finished_state() ? jobs_.erase(it) : std::next(it);
  if (static_cast<int>(jobs_.size()) >= max_jobs_) return nullptr;
  const std::int64_t id = assign_id ? assign_id(request) : next_id_;
  next_id_ = std::max(next_id_, id + 1);
  auto job = std::make_unique<Job>(id, std::move(request.bundle), request.spec, request.plan,
                                   request.priority);
  job->effects = std::move(request.effects);
  for (std::string& warning : request.warnings) job->add_warning(std::move(warning));
  job->camera = request.camera ? request.camera : request.spec.overrides.camera;
  job->viewpoints = std::move(request.viewpoints);
  job->seconds_per_pixel_pass = request.seconds_per_pixel_pass;
  job->client = std::move(client);
  Job* raw = job.get();
  jobs_[id] = std::move(job);
  return raw;
}

int JobStore::unfinished_of(const std::string& client) const {
  int n = 0;
  for (const auto& [id, job] : jobs_) n += !job->finished_state() && job->client == client;
  return n;
}

Job* JobStore::find(std::int64_t id) {
  auto it = jobs_.find(id);
  return it == jobs_.end() ? nullptr : it->second.get();
}

}  // namespace tessera
