// The coordinator's jobs kept across restarts (issue 17 §1-2): converts between the in-memory
// Job and the durable store's records (coordinator/store/job_record.h) in one place. A job is
// stored at admission, each merged result is queued as it merges and written every tick (by
// the store's thread), a state change is stored, and a done job's encoded images are kept as
// files. At start,
// restore() rebuilds every stored job under its old id: finished ones with their images,
// unfinished ones by replaying their results into a fresh Job, which the scheduler resumes.
// A write that fails fails the jobs it concerned; the coordinator goes on. On the io thread
// (store_images excepted).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "coordinator/jobs/job_store.h"
#include "coordinator/scheduler/scheduler.h"
#include "coordinator/store/job_database.h"

namespace tessera {

class JobPersistence : public JobObserver {
 public:
  // Throws StoreError when the directory or its database cannot be opened.
  JobPersistence(const std::filesystem::path& dir, std::chrono::seconds keep_finished,
                 std::int64_t max_disk_bytes);

  // Stores a new job and returns its id; throws StoreError (nothing is stored then).
  std::int64_t admit(const JobRequest& request);
  void merged(const Job& job, int unit, FloatValues values, const RenderStats& stats,
              const std::string& worker) override;
  void state_changed(const Job& job) override;
  // What store_images writes of a done job besides its images, taken on the io thread.
  struct DoneJob {
    std::int64_t id;
    std::string error;
    Clock::time_point finished;
    explicit DoneJob(const Job& job);
  };
  // A done job's final images, just encoded, stored with its state. Thread-safe, unlike the
  // rest: called on the thread that encoded them, since the write (the images' files and the
  // results queued since the last tick) took 5-7 % of the io thread's time while the next job
  // merged (docs/SCALING.md). Returns the store's error when it failed (nothing stored).
  std::optional<StoreError> store_images(const DoneJob& job, const Job::Encodings& images);
  // On the io thread after store_images failed: the job fails, its images dropped, with the
  // store's error, and that is stored.
  void fail_unstored(Job& job, const StoreError& e);
  // Every tick: fails in the scheduler the jobs whose write failed (in earlier ticks' writes),
  // applies retention (jobs it deleted leave `jobs`), then has the store's thread write the
  // queued results.
  void tick(JobStore& jobs, Scheduler& scheduler);
  // At a graceful stop: writes the queued results before returning.
  void write_out();
  // At start: every stored job into `jobs` (`prepare` is called on each, e.g. to set its
  // on_released), unfinished ones handed to the scheduler to resume.
  void restore(JobStore& jobs, Scheduler& scheduler, const std::function<void(Job&)>& prepare);
  // The store's size as --max-disk counts it; throws StoreError.
  std::int64_t size_bytes() { return db_.size_bytes(); }

 private:
  // Notes the jobs a failed write concerned: tick() fails them (not at once: a write may fail
  // inside the scheduler's own calls).
  void note_failure(const StoreError& e);

  JobDatabase db_;
  std::chrono::seconds keep_finished_;
  std::int64_t max_disk_bytes_;
  std::map<std::int64_t, std::string> failed_;  // job -> why its write failed
};

}  // namespace tessera
