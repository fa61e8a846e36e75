// The scheduler: keeps every worker's slots full (its threads plus a small prefetch, so
// network latency is hidden), shares workers between jobs by priority, re-queues a lost
// worker's units, and near the end of a stage sends a straggling unit to an idle worker too:
// the first result wins and a late duplicate is dropped. Sample passes after the first wait
// for the previous pass, so each pixel's passes reach the frame buffer in pass order.
// Workers are not believed blindly: a result must answer a unit sent to that worker and pass
// result_check.h, and a job fails only when two workers report it failing (docs/PROTOCOL.md).
// Everything runs on the coordinator's single io thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/protocol/connection.h"
#include "common/protocol/messages.h"
#include "common/render/time_prediction.h"
#include "coordinator/jobs/job_store.h"
#include "coordinator/metrics/service_metrics.h"
#include "coordinator/scheduler/prediction_calibration.h"
#include "coordinator/scheduler/worker_pipeline.h"

namespace tessera {

struct SchedulerOptions {
  double max_job_seconds = 600;
  // A unit may be duplicated once it has run this many times the job's mean unit time (and
  // at least `min_speculation`) while workers sit idle.
  double speculation_factor = 3;
  std::chrono::milliseconds min_speculation{500};
  ServiceMetrics* metrics = nullptr;  // units, pixels and rays counted here when given
  // Where the scheduler reads the time: tests step a clock of their own so deadlines do not
  // depend on how busy the machine is.
  std::function<Clock::time_point()> clock = [] { return Clock::now(); };
};

struct WorkerHello {
  std::string name, address;
  int threads = 1;
  std::set<std::string> cached;     // bundle hashes the worker already holds
  double handshake_round_trip = 0;  // seconds from the challenge to the worker's answer
};

struct Prediction {
  std::optional<double> seconds, uncalibrated;  // empty without a connected worker
  int threads = 0;
  double factor = 1;            // the calibration applied: speed factor...
  double overhead_seconds = 0;  // ...and the overhead added
};

// Told of what changes a job for good, so it can be stored (coordinator/jobs/job_persistence.h)
// without the scheduler knowing the store. Called on the io thread.
class JobObserver {
 public:
  virtual ~JobObserver() = default;
  // A unit's result was merged into the job's frame buffer (Job::apply_result): its values are
  // handed over, not copied (a result is up to 65,536 pixels' floats, kMostUnitPixels).
  virtual void merged(const Job& job, int unit, FloatValues values, const RenderStats& stats,
                      const std::string& worker) = 0;
  // The job started running or finished (its buffers are already released).
  virtual void state_changed(const Job& job) = 0;
};

class Scheduler {
 public:
  explicit Scheduler(SchedulerOptions options) : options_(options) {}

  // The caller welcomes the worker, then calls fill_slots() to give it work.
  std::int64_t add_worker(WorkerHello hello, std::shared_ptr<FrameConnection> connection);
  void fill_slots();
  void remove_worker(std::int64_t worker);
  // Throw ProtocolError for a forged message: a result for a unit or job never sent to this
  // worker, or one that fails result_check.h; a job_failed for a job never sent to it. The
  // caller drops the worker, which re-queues its units. Late duplicates and results for jobs
  // finished meanwhile are dropped silently.
  void on_result(std::int64_t worker, ResultMessage result);
  // The first worker to report a job failing loses the job (its units go to the others); the
  // job fails when a second worker reports it too, or at the time limit with the first report.
  void on_job_failed(std::int64_t worker, const JobFailedMessage& report);

  void set_observer(JobObserver* observer) { observer_ = observer; }
  // `done` (per unit, may be empty) marks units whose results the job already holds: a job
  // resumed after a restart runs only the others.
  void add_job(Job& job, const std::vector<bool>& done = {});
  // Fails a queued or running job (e.g. its results cannot be stored); false if finished.
  bool fail(std::int64_t job, const std::string& error);
  // Cancels a queued or running job and frees its workers at once; false if already finished.
  bool cancel(std::int64_t job);
  // Time limits and speculation deadlines; called periodically.
  void tick();
  // Whether any job is queued or running.
  bool has_unfinished_jobs() const { return !runs_.empty(); }

  // What GET /api/workers shows of each connected worker (coordinator/http/worker_json.h),
  // in order of id.
  struct WorkerView {
    std::int64_t id = 0;
    std::string name, address;
    int threads = 0;
    std::size_t in_flight = 0;
    int slots = 0;
    double round_trip_seconds = 0;
    long long units_done = 0, dropped_results = 0, pixels_done = 0;
    double busy_seconds = 0, connected_seconds = 0;
  };
  std::vector<WorkerView> workers() const;
  struct WorkerTotals {
    int workers = 0, threads = 0;
  };
  WorkerTotals worker_totals() const;
  // A job's time from its probe, the threads of the connected workers and what finished
  // jobs taught (issue 5).
  Prediction predict(double seconds_per_pixel_pass, long long pixel_passes) const;

 private:
  enum class UnitState { Pending, InFlight, Done };
  struct UnitRun {
    UnitState state = UnitState::Pending;
    std::vector<std::int64_t> holders;
    Clock::time_point dispatched;
  };
  struct JobRun {
    Job* job = nullptr;
    std::deque<int> pending;  // dispatch order; re-queued units go to the front
    std::vector<UnitRun> units;
    // The speculation candidates (units in flight on exactly one worker) by (first dispatch,
    // unit), oldest first: a look for a straggler stops at the first one too young.
    std::set<std::pair<Clock::time_point, int>> stragglers;
    double virtual_time = 0;  // fair share: advances by cost / priority per dispatch
    // Workers (connections) that reported the job failing, and the first one's message: one
    // worker's word does not fail a job, and the job is not sent to them again.
    std::set<std::int64_t> failed_on;
    std::string first_failure;
  };
  struct WorkerSlot {
    std::int64_t id = 0;
    WorkerHello hello;
    std::shared_ptr<FrameConnection> connection;
    std::set<std::string> bundles;
    std::set<std::int64_t> open_jobs;
    std::set<std::int64_t> jobs_sent;  // every job opened on this connection, finished or not
    std::map<std::pair<std::int64_t, int>, Clock::time_point> in_flight;  // (job, unit): sent
    WorkerPipeline pipeline{1};
    long long units_done = 0, pixels_done = 0;
    long long dropped_results = 0;  // late duplicates and results of earlier connections
    double busy_seconds = 0;
    Clock::time_point joined;
  };

  bool dispatch_one(WorkerSlot& worker);
  bool dispatchable(const JobRun& run) const;
  bool any_dispatchable() const;
  // How long a unit of the run must have been out before it may be duplicated.
  double speculation_wait(const JobRun& run) const;
  bool any_straggler_due(Clock::time_point now) const;
  bool speculate(WorkerSlot& worker, Clock::time_point now);
  // Keeps the unit's place among the run's stragglers in step with its state and holders;
  // called after either changes.
  static void update_straggler(JobRun& run, int unit);
  // Keeps the worker's place in hungry_ and idle_threads_ in step with its units in flight and
  // slots; called after either changes.
  void update_load(const WorkerSlot& worker);
  void send_unit(WorkerSlot& worker, JobRun& run, int unit);
  // Puts the worker's units in flight of the jobs `of_job` selects back at the front of their
  // queues (unless another worker holds them too); returns how many.
  int take_back_units(WorkerSlot& worker, const std::function<bool(std::int64_t)>& of_job);
  void finish(JobRun& run, JobState state, const std::string& error = {});
  // Takes the job away from a worker that reported it failing: cancels it there and re-queues
  // the units it held.
  void withdraw(WorkerSlot& worker, JobRun& run);

  SchedulerOptions options_;
  std::map<std::int64_t, JobRun> runs_;
  std::map<std::int64_t, WorkerSlot> workers_;
  // Workers with a free slot, and those with an idle thread (which may take a duplicate), by
  // id: filling slots looks only at these, so a result costs the same with 10 workers or 1,000.
  std::set<std::int64_t> hungry_, idle_threads_;
  PredictionCalibration calibration_;
  std::int64_t next_worker_ = 1;
  JobObserver* observer_ = nullptr;
};

}  // namespace tessera
