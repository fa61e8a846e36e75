#include "coordinator/jobs/job_persistence.h"

#include <fstream>
#include <sstream>

#include <spdlog/spdlog.h>

namespace tessera {

namespace {

// Stored times are wall-clock (they outlive the process); the job's are steady.
WallClock::time_point to_wall(Clock::time_point t) {
  return WallClock::now() - std::chrono::duration_cast<WallClock::duration>(Clock::now() - t);
}
Clock::time_point to_steady(WallClock::time_point t) {
  return Clock::now() - std::chrono::duration_cast<Clock::duration>(WallClock::now() - t);
}

JobState state_of(const std::string& name) {
  for (JobState s :
       {JobState::Queued, JobState::Running, JobState::Done, JobState::Failed, JobState::Cancelled})
    if (name == to_string(s)) return s;
  return JobState::Queued;
}

std::shared_ptr<const std::string> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return nullptr;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return std::make_shared<const std::string>(bytes.str());
}

}  // namespace

JobPersistence::JobPersistence(const std::filesystem::path& dir, std::chrono::seconds keep_finished,
                               std::int64_t max_disk_bytes)
    : db_(dir, max_disk_bytes), keep_finished_(keep_finished), max_disk_bytes_(max_disk_bytes) {}

std::int64_t JobPersistence::admit(const JobRequest& r) {
  StoredRequest stored;
  stored.bundle = r.bundle;
  stored.spec = r.spec;
  stored.plan = r.plan;
  stored.priority = r.priority;
  stored.effects = r.effects;
  stored.warnings = r.warnings;
  stored.seconds_per_pixel_pass = r.seconds_per_pixel_pass;
  stored.camera = r.camera;
  stored.viewpoints = r.viewpoints;
  return db_.add_job(stored, WallClock::now());
}

void JobPersistence::merged(const Job& job, int unit, FloatValues values, const RenderStats& stats,
                            const std::string& worker) {
  try {
    db_.append_result(job.id, unit, std::move(values), stats, worker);
  } catch (const StoreError& e) {
    note_failure(e);
  }
}

void JobPersistence::state_changed(const Job& job) {
  // A done job is stored as done with its images once they are encoded (store_images); until
  // then it stays "running" with all its results, and a restart finishes it again.
  if (job.state() == JobState::Done) return;
  try {
    if (job.finished_state())
      db_.finish_job(job.id, to_string(job.state()), job.error(), to_wall(*job.finished()), {});
    else
      db_.set_state(job.id, to_string(job.state()));
  } catch (const StoreError& e) {
    note_failure(e);
  }
}

JobPersistence::DoneJob::DoneJob(const Job& job)
    : id(job.id), error(job.error()), finished(job.finished().value_or(Clock::now())) {}

std::optional<StoreError> JobPersistence::store_images(const DoneJob& job,
                                                       const Job::Encodings& images) {
  std::vector<StoredImage> stored;
  for (const auto& [format, bytes] : images)
    if (bytes) stored.push_back({"image." + format, *bytes});
  try {
    db_.finish_job(job.id, to_string(JobState::Done), job.error, to_wall(job.finished), stored);
  } catch (const StoreError& e) {
    return e;
  }
  return std::nullopt;
}

void JobPersistence::fail_unstored(Job& job, const StoreError& e) {
  // Kept only in memory, the job would come back after a restart as what the store holds of
  // it: it fails now, and that (a small write, after the failed one rolled back) is kept.
  job.fail_unstored("cannot store the job's results: " + e.cause());
  spdlog::error("job {} failed: its results cannot be stored: {}", job.id, e.cause());
  try {
    db_.finish_job(job.id, to_string(job.state()), job.error(),
                   to_wall(job.finished().value_or(Clock::now())), {});
  } catch (const StoreError& again) {
    spdlog::error("job {}: its failure cannot be stored either: {}", job.id, again.cause());
  }
}

void JobPersistence::note_failure(const StoreError& e) {
  for (std::int64_t job : e.jobs()) failed_.emplace(job, e.cause());
  if (e.jobs().empty()) spdlog::error("job store: {}", e.cause());
}

void JobPersistence::tick(JobStore& jobs, Scheduler& scheduler) {
  for (const StoreError& e : db_.take_failures()) note_failure(e);
  for (const auto& [job, cause] : failed_)
    if (scheduler.fail(job, "cannot store the job's results: " + cause))
      spdlog::error("job {} failed: its progress cannot be stored: {}", job, cause);
  failed_.clear();
  try {
    for (std::int64_t gone : db_.prune(WallClock::now(), keep_finished_, max_disk_bytes_))
      jobs.forget(gone);
  } catch (const StoreError& e) {
    spdlog::error("job store retention: {}", e.cause());
  }
  // Last: retention above takes the store's connection, and would wait for this write.
  db_.flush_soon();
}

void JobPersistence::write_out() {
  try {
    db_.flush();
  } catch (const StoreError& e) {
    spdlog::error("job store: the last results cannot be stored: {}", e.cause());
  }
}

void JobPersistence::restore(JobStore& jobs, Scheduler& scheduler,
                             const std::function<void(Job&)>& prepare) {
  int resumed = 0, kept = 0;
  for (StoredJob& stored : db_.load_all()) {
    StoredRequest& r = stored.request;
    JobRequest request;
    request.bundle = std::move(r.bundle);
    request.spec = r.spec;
    request.plan = r.plan;
    request.priority = r.priority;
    request.effects = r.effects;
    request.warnings = r.warnings;
    request.seconds_per_pixel_pass = r.seconds_per_pixel_pass;
    request.camera = r.camera;
    request.viewpoints = std::move(r.viewpoints);
    Job* job = jobs.create(std::move(request), {}, [&](const JobRequest&) { return stored.id; });
    if (!job) {
      spdlog::warn("job {} not restored: more unfinished jobs than the limit", stored.id);
      continue;
    }
    job->uncalibrated_prediction = r.uncalibrated_prediction;
    job->predicted_seconds = r.predicted_seconds;
    job->prediction_threads = r.prediction_threads;
    const Clock::time_point created = to_steady(stored.created);
    prepare(*job);
    if (stored.finished) {
      Job::Encodings encoded;
      for (const std::string& name : stored.images)
        if (auto bytes = read_file(db_.image_path(stored.id, name)))
          encoded[name.substr(name.find('.') + 1)] = std::move(bytes);
      job->restore_finished(created, state_of(stored.state), stored.error,
                            to_steady(*stored.finished), std::move(encoded));
      ++kept;
      continue;
    }
    // Replayed in merge order, the frame buffer is bit-identical to the one before the crash.
    std::vector<bool> done(job->plan.units.size(), false);
    for (const StoredResult& result : stored.results) {
      if (result.unit < 0 || result.unit >= static_cast<int>(done.size()) || done[result.unit] ||
          result.values.size() != 3 * static_cast<std::size_t>(job->plan.units[result.unit].cost))
        continue;  // a store written by this code holds none of these; never trusted blindly
      done[result.unit] = true;
      job->apply_result(result.unit, result.values, result.stats);
    }
    std::optional<Clock::time_point> running_since;
    if (!stored.results.empty()) running_since = Clock::now();
    job->restore_unfinished(created, running_since);
    scheduler.add_job(*job, done);
    ++resumed;
  }
  spdlog::info("job store: {} finished jobs kept, {} unfinished jobs resumed", kept, resumed);
}

}  // namespace tessera
