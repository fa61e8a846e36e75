#include "coordinator/scheduler/scheduler.h"

#include <algorithm>
#include <limits>

#include <spdlog/spdlog.h>

#include "coordinator/scheduler/result_check.h"

namespace tessera {

namespace {

double seconds_since(Clock::time_point t, Clock::time_point now) {
  return std::chrono::duration<double>(now - t).count();
}

}  // namespace

std::int64_t Scheduler::add_worker(WorkerHello hello, std::shared_ptr<FrameConnection> connection) {
  const std::int64_t id = next_worker_++;
  WorkerSlot& w = workers_[id];
  w.id = id;
  w.bundles = hello.cached;
  w.hello = std::move(hello);
  w.pipeline = WorkerPipeline(w.hello.threads, w.hello.handshake_round_trip);
  w.connection = std::move(connection);
  w.joined = options_.clock();
  update_load(w);
  spdlog::info("worker {} \"{}\" joined from {} with {} threads", id, w.hello.name, w.hello.address,
               w.hello.threads);
  return id;
}

void Scheduler::remove_worker(std::int64_t id) {
  auto it = workers_.find(id);
  if (it == workers_.end()) return;
  const int requeued = take_back_units(it->second, [](std::int64_t) { return true; });
  spdlog::info("worker {} \"{}\" left; {} units re-queued", id, it->second.hello.name, requeued);
  hungry_.erase(id);
  idle_threads_.erase(id);
  workers_.erase(it);
  fill_slots();
}

int Scheduler::take_back_units(WorkerSlot& w, const std::function<bool(std::int64_t)>& of_job) {
  int requeued = 0;
  for (auto entry = w.in_flight.begin(); entry != w.in_flight.end();) {
    const auto [job, unit] = entry->first;
    if (!of_job(job)) {
      ++entry;
      continue;
    }
    entry = w.in_flight.erase(entry);
    auto run = runs_.find(job);
    if (run == runs_.end()) continue;
    UnitRun& u = run->second.units[unit];
    std::erase(u.holders, w.id);
    if (u.state == UnitState::InFlight && u.holders.empty()) {
      u.state = UnitState::Pending;
      run->second.pending.push_front(unit);
      ++requeued;
    }
    update_straggler(run->second, unit);
  }
  update_load(w);
  if (options_.metrics) options_.metrics->units_requeued.add(requeued);
  return requeued;
}

void Scheduler::add_job(Job& job, const std::vector<bool>& done) {
  spdlog::info("job {} queued: {} ({}x{}, {} units)", job.id, job.bundle->main,
               job.spec.settings.width, job.spec.settings.height, job.plan.units.size());
  JobRun& run = runs_[job.id];
  run.job = &job;
  run.units.resize(job.plan.units.size());
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u)
    if (u < static_cast<int>(done.size()) && done[u])
      run.units[u].state = UnitState::Done;
    else
      run.pending.push_back(u);
  if (job.done_cost() == job.plan.total_cost) return finish(run, JobState::Done);
  // Start level with the others, so a new job neither waits for nor starves the running ones.
  double least = 0;
  bool any = false;
  for (auto& [id, other] : runs_)
    if (id != job.id) {
      least = any ? std::min(least, other.virtual_time) : other.virtual_time, any = true;
      other.job->mark_ran_beside_another();
      job.mark_ran_beside_another();
    }
  run.virtual_time = least;
  fill_slots();
}

bool Scheduler::cancel(std::int64_t job) {
  auto it = runs_.find(job);
  if (it == runs_.end()) return false;
  finish(it->second, JobState::Cancelled);
  return true;
}

bool Scheduler::fail(std::int64_t job, const std::string& error) {
  auto it = runs_.find(job);
  if (it == runs_.end()) return false;
  finish(it->second, JobState::Failed, error);
  return true;
}

void Scheduler::tick() {
  const auto now = options_.clock();
  std::vector<std::int64_t> expired;
  for (const auto& [id, run] : runs_)
    if (run.job->started() && seconds_since(*run.job->started(), now) > options_.max_job_seconds)
      expired.push_back(id);
  const std::string limit =
      "time limit of " + std::to_string(static_cast<int>(options_.max_job_seconds)) + " s";
  for (std::int64_t id : expired) {
    JobRun& run = runs_.at(id);
    // A failure one worker reported and no other confirmed (none took the job in time).
    finish(
        run, JobState::Failed,
        run.first_failure.empty()
            ? limit + " exceeded"
            : run.first_failure + " (not confirmed by a second worker within the " + limit + ")");
  }
  fill_slots();
}

bool Scheduler::dispatchable(const JobRun& run) const {
  if (run.pending.empty()) return false;
  const Job& job = *run.job;
  const int stage = job.plan.units[run.pending.front()].stage;
  if (job.plan.stages[stage].pass == 0) return true;
  // A later pass waits until every earlier stage is complete (pass order in the frame buffer).
  for (int s = 0; s < stage; ++s)
    if (job.stage_timing()[s].units_done < job.plan.stages[s].unit_count) return false;
  return true;
}

bool Scheduler::any_dispatchable() const {
  return std::any_of(runs_.begin(), runs_.end(),
                     [this](const auto& entry) { return dispatchable(entry.second); });
}

void Scheduler::fill_slots() {
  // New units first: to each worker with a free slot, in id order, while any job has some. A
  // worker visited takes at least one unit (unless it reported every such job failing).
  for (auto it = hungry_.begin(); it != hungry_.end() && any_dispatchable();) {
    WorkerSlot& w = workers_.at(*it++);  // past w first: filling w takes it out of hungry_
    while (w.connection->open() && static_cast<int>(w.in_flight.size()) < w.pipeline.slots() &&
           dispatch_one(w)) {
    }
  }
  // Then duplicates of stragglers, while any is due. Only a worker with idle threads takes one;
  // its prefetch slots are for new work.
  const auto now = options_.clock();
  for (auto it = idle_threads_.begin(); it != idle_threads_.end() && any_straggler_due(now);) {
    WorkerSlot& w = workers_.at(*it++);
    while (w.connection->open() && static_cast<int>(w.in_flight.size()) < w.hello.threads &&
           speculate(w, now)) {
    }
  }
}

void Scheduler::update_load(const WorkerSlot& w) {
  const int held = static_cast<int>(w.in_flight.size());
  if (held < w.pipeline.slots())
    hungry_.insert(w.id);
  else
    hungry_.erase(w.id);
  if (held < w.hello.threads)
    idle_threads_.insert(w.id);
  else
    idle_threads_.erase(w.id);
}

void Scheduler::update_straggler(JobRun& run, int unit) {
  const UnitRun& u = run.units[unit];
  if (u.state == UnitState::InFlight && u.holders.size() == 1)
    run.stragglers.emplace(u.dispatched, unit);
  else
    run.stragglers.erase({u.dispatched, unit});
}

bool Scheduler::dispatch_one(WorkerSlot& w) {
  JobRun* best = nullptr;
  for (auto& [id, run] : runs_)
    if (dispatchable(run) && !run.failed_on.count(w.id) &&
        (!best || run.virtual_time < best->virtual_time))
      best = &run;
  if (!best) return false;
  const int unit = best->pending.front();
  best->pending.pop_front();
  best->virtual_time += static_cast<double>(best->job->plan.units[unit].cost) / best->job->priority;
  send_unit(w, *best, unit);
  return true;
}

double Scheduler::speculation_wait(const JobRun& run) const {
  long long units_done = 0;
  for (const auto& t : run.job->stage_timing()) units_done += t.units_done;
  const double mean =
      units_done > 0 ? run.job->stats().seconds / static_cast<double>(units_done) : 0;
  return std::max(options_.speculation_factor * mean,
                  std::chrono::duration<double>(options_.min_speculation).count());
}

bool Scheduler::any_straggler_due(Clock::time_point now) const {
  return std::any_of(runs_.begin(), runs_.end(), [&](const auto& entry) {
    const JobRun& run = entry.second;
    return !run.stragglers.empty() &&
           seconds_since(run.stragglers.begin()->first, now) >= speculation_wait(run);
  });
}

bool Scheduler::speculate(WorkerSlot& w, Clock::time_point now) {
  // The oldest due straggler of any job, not the worker's own; ties go to the lower job id.
  JobRun* pick_run = nullptr;
  Clock::time_point pick_dispatched;
  int pick = -1;
  for (auto& [id, run] : runs_) {
    if (run.failed_on.count(w.id)) continue;
    const double wait = speculation_wait(run);
    for (const auto& [dispatched, unit] : run.stragglers) {
      if (seconds_since(dispatched, now) < wait) break;  // the rest are younger still
      if (run.units[unit].holders[0] == w.id) continue;  // at most the worker's slots
      if (!pick_run || dispatched < pick_dispatched)
        pick_run = &run, pick_dispatched = dispatched, pick = unit;
      break;
    }
  }
  if (!pick_run) return false;
  spdlog::debug("job {}: unit {} also sent to worker {}", pick_run->job->id, pick, w.id);
  send_unit(w, *pick_run, pick);
  return true;
}

void Scheduler::send_unit(WorkerSlot& w, JobRun& run, int unit) {
  Job& job = *run.job;
  const auto now = options_.clock();
  if (!w.open_jobs.count(job.id)) {
    JobMessage open{.job = job.id, .hash = job.hash, .spec = job.spec, .bundle = std::nullopt};
    if (!w.bundles.count(job.hash)) {
      open.bundle = *job.bundle;
      w.bundles.insert(job.hash);
    }
    w.connection->send(encode(open));
    w.open_jobs.insert(job.id);
    w.jobs_sent.insert(job.id);
  }
  const WorkUnit& wu = job.plan.units[unit];
  w.connection->send_encoded(MessageType::Unit,
                             encode_unit_frame(UnitMessage{.job = job.id,
                                                           .unit = unit,
                                                           .pass = job.plan.stages[wu.stage].pass,
                                                           .pixels = wu.pixels}));
  if (options_.metrics) options_.metrics->units_dispatched.add();
  UnitRun& r = run.units[unit];
  if (r.holders.empty()) r.dispatched = now;
  r.holders.push_back(w.id);
  r.state = UnitState::InFlight;
  update_straggler(run, unit);
  w.in_flight.emplace(std::pair{job.id, unit}, now);
  update_load(w);
  if (!job.record_dispatch(wu.stage, now)) return;
  spdlog::info("job {} running", job.id);
  if (observer_) observer_->state_changed(job);
}

void Scheduler::on_result(std::int64_t worker, ResultMessage result) {
  WorkerSlot& w = workers_.at(worker);
  // Everything is checked before anything changes: a result that breaks a rule costs the worker
  // its connection, and remove_worker() then re-queues all of its units, this one included.
  const std::int64_t job_id = result.job;
  if (!w.jobs_sent.count(job_id))
    throw ProtocolError("result for job " + std::to_string(job_id) +
                        ", which was never sent to this worker");
  auto it = runs_.find(job_id);
  if (it == runs_.end()) {  // finished or cancelled meanwhile
    if (result.unit >= 0 && result.unit <= std::numeric_limits<int>::max())
      w.in_flight.erase({job_id, static_cast<int>(result.unit)});
    update_load(w);
    return fill_slots();
  }
  JobRun& run = it->second;
  Job& job = *run.job;
  if (run.failed_on.count(worker)) {
    ++w.dropped_results;  // rendered before the job was taken from it after its failure report
    return;
  }
  if (result.unit < 0 || result.unit >= static_cast<std::int64_t>(run.units.size()))
    throw ProtocolError("result for unknown unit " + std::to_string(result.unit));
  const int unit = static_cast<int>(result.unit);
  const auto sent = w.in_flight.find({job_id, unit});
  if (sent == w.in_flight.end())
    throw ProtocolError("result for unit " + std::to_string(unit) + " of job " +
                        std::to_string(job_id) + ", which this worker does not hold");
  const WorkUnit& wu = job.plan.units[unit];
  const auto now = options_.clock();
  check_result(result, wu.cost, seconds_since(sent->second, now));
  const RenderStats& stats = result.stats;
  const Clock::time_point sent_at = sent->second;
  // Units of at least half the size the job's units are cut to count as full-sized.
  w.pipeline.observe(seconds_since(sent_at, now), stats.seconds,
                     2 * wu.cost >= job.plan_options.unit_pixels);
  w.in_flight.erase(sent);
  update_load(w);
  UnitRun& r = run.units[unit];
  std::erase(r.holders, worker);
  if (r.state == UnitState::Done) {
    ++w.dropped_results;  // a speculative copy lost the race
    return fill_slots();
  }
  run.stragglers.erase({r.dispatched, unit});
  r.state = UnitState::Done;
  job.apply_result(unit, result.values, stats, Job::ResultSource{worker, w.hello.name, now});
  if (observer_) observer_->merged(job, unit, std::move(result.values), stats, w.hello.name);
  if (ServiceMetrics* m = options_.metrics) {
    m->units_finished.add();
    m->unit_latency.observe(seconds_since(sent_at, now));
    m->unit_render.observe(stats.seconds);
    m->pixels.add(static_cast<double>(wu.cost));
    m->rays.add(static_cast<double>(stats.camera_rays + stats.shadow_rays + stats.reflection_rays +
                                    stats.refraction_rays));
  }
  w.units_done += 1;
  w.pixels_done += wu.cost;
  w.busy_seconds += stats.seconds;
  if (job.done_cost() == job.plan.total_cost) finish(run, JobState::Done);
  fill_slots();
}

void Scheduler::on_job_failed(std::int64_t worker, const JobFailedMessage& report) {
  WorkerSlot& w = workers_.at(worker);
  const std::int64_t job_id = report.job;
  if (!w.jobs_sent.count(job_id))
    throw ProtocolError("job_failed for job " + std::to_string(job_id) +
                        ", which was never sent to this worker");
  auto it = runs_.find(job_id);
  if (it == runs_.end()) return;
  JobRun& run = it->second;
  if (report.missing_bundle) {
    // The worker evicted the bundle since it last announced it: it dropped the job and the
    // units sent with it. Take them back and open the job again, this time with the bundle.
    w.bundles.erase(run.job->hash);
    w.open_jobs.erase(job_id);
    const int requeued = take_back_units(w, [&](std::int64_t job) { return job == job_id; });
    spdlog::info("worker {} no longer holds the bundle of job {}; {} units re-queued", worker,
                 job_id, requeued);
    return fill_slots();
  }
  const std::string failure = "worker " + w.hello.name + ": " + report.error;
  if (!run.failed_on.insert(worker).second) return;  // it said so already
  if (run.failed_on.size() == 1) {
    // A scene that crashes one worker is not one worker's word: let another try.
    run.first_failure = failure;
    run.job->add_warning(failure + " (the job goes on with the other workers)");
    spdlog::warn("job {}: {}; its units go to other workers", job_id, failure);
    withdraw(w, run);
    return fill_slots();
  }
  finish(run, JobState::Failed, run.first_failure + "; also " + failure);
}

void Scheduler::withdraw(WorkerSlot& w, JobRun& run) {
  const std::int64_t job_id = run.job->id;
  if (w.open_jobs.erase(job_id)) w.connection->send(encode(CancelMessage{.job = job_id}));
  take_back_units(w, [&](std::int64_t job) { return job == job_id; });
}

void Scheduler::finish(JobRun& run, JobState state, const std::string& error) {
  Job& job = *run.job;
  // Free the workers at once: they drop the job's queued units and its prepared scene.
  for (auto& [id, w] : workers_) {
    if (!w.open_jobs.erase(job.id)) continue;
    w.connection->send(encode(CancelMessage{.job = job.id}));
    std::erase_if(w.in_flight, [&](const auto& entry) { return entry.first.first == job.id; });
    update_load(w);
  }
  spdlog::info("job {} {}{}{}", job.id, to_string(state), error.empty() ? "" : ": ", error);
  job.finish(state, error, options_.clock());
  if (state == JobState::Done && job.ran_alone() && job.uncalibrated_prediction &&
      job.prediction_threads > 0)
    calibration_.observe(*job.uncalibrated_prediction, job.stats().seconds / job.prediction_threads,
                         job.elapsed_seconds(*job.finished()));
  if (observer_) observer_->state_changed(job);
  runs_.erase(job.id);  // `run` and `job` references end here
  fill_slots();
}

Scheduler::WorkerTotals Scheduler::worker_totals() const {
  WorkerTotals t;
  for (const auto& [id, w] : workers_) {
    t.workers += 1;
    t.threads += w.hello.threads;
  }
  return t;
}

Prediction Scheduler::predict(double seconds_per_pixel_pass, long long pixel_passes) const {
  Prediction p;
  p.threads = worker_totals().threads;
  p.factor = calibration_.factor();
  p.overhead_seconds = calibration_.overhead_seconds();
  p.uncalibrated = predict_render_seconds(seconds_per_pixel_pass, pixel_passes, p.threads);
  if (p.uncalibrated) p.seconds = calibration_.apply(*p.uncalibrated);
  return p;
}

std::vector<Scheduler::WorkerView> Scheduler::workers() const {
  const auto now = options_.clock();
  std::vector<WorkerView> out;
  out.reserve(workers_.size());
  for (const auto& [id, w] : workers_)
    out.push_back({.id = id,
                   .name = w.hello.name,
                   .address = w.hello.address,
                   .threads = w.hello.threads,
                   .in_flight = w.in_flight.size(),
                   .slots = w.pipeline.slots(),
                   .round_trip_seconds = w.pipeline.round_trip_seconds(),
                   .units_done = w.units_done,
                   .dropped_results = w.dropped_results,
                   .pixels_done = w.pixels_done,
                   .busy_seconds = w.busy_seconds,
                   .connected_seconds = seconds_since(w.joined, now)});
  return out;
}

}  // namespace tessera
