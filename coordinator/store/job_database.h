// The coordinator's durable job store (issue 17 §1-2): one SQLite database DIR/tessera.db in
// WAL mode for jobs, states and merged unit results, with bundles as content-addressed files
// under DIR/bundles/<hash>, final images under DIR/images/<id>/ and the results' pixel values
// appended to DIR/results/<id> (result_files.h). Every write is one
// transaction, so a failed write (disk full, over the byte budget, I/O error) leaves the store
// as it was before it; a crash loses only results not yet flushed.
//
// Results are batched: append_result queues in memory, flush writes the queue in one
// transaction; flush_soon has the store's own thread do it (the coordinator asks every tick),
// so that the writes do not hold up the caller. Destroying the store without flush drops the
// queue, exactly as a crash would. All members are safe to call from several threads;
// append_result waits for a flush under way only for a job's first result.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/protocol/payload.h"
#include "coordinator/store/job_record.h"

namespace tessera {

namespace sqlite {
class Connection;
}
class FlushThread;

// A store that cannot be opened or written. `jobs` names the jobs whose write failed (empty
// when the failure is the store's own, e.g. at open); `cause` says why.
class StoreError : public std::runtime_error {
 public:
  StoreError(std::vector<std::int64_t> jobs, const std::string& cause);
  const std::vector<std::int64_t>& jobs() const { return jobs_; }
  const std::string& cause() const { return cause_; }

 private:
  std::vector<std::int64_t> jobs_;
  std::string cause_;
};

class JobDatabase {
 public:
  // 2: jobs keep their scene's camera and Viewpoints. 3: results' payloads in files.
  static constexpr std::int64_t kSchemaVersion = 3;
  static constexpr std::int64_t kUnlimited = std::numeric_limits<std::int64_t>::max();

  // Opens DIR (created if missing) and its database, migrating a store of an older schema
  // version (a crash mid-way leaves it at a whole version); refuses a newer schema version or
  // another application's database. A write that would take size_bytes() above
  // max_disk_bytes fails with StoreError. Throws StoreError.
  explicit JobDatabase(const std::filesystem::path& dir, std::int64_t max_disk_bytes = kUnlimited);
  ~JobDatabase();
  JobDatabase(const JobDatabase&) = delete;
  JobDatabase& operator=(const JobDatabase&) = delete;

  // Stores a new job in state "queued" and returns its id. Ids grow and are never reused,
  // across restarts and after jobs are deleted.
  std::int64_t add_job(const StoredRequest& request, WallClock::time_point created);
  void set_state(std::int64_t job, const std::string& state, const std::string& error = {});
  // Queues a merged unit result; returns its sequence number within the job.
  std::int64_t append_result(std::int64_t job, int unit, FloatValues values,
                             const RenderStats& stats, const std::string& worker);
  // Writes every queued result in one transaction. On failure the failed jobs' queued results
  // are dropped, the store keeps each job's results up to its last successful flush, and
  // StoreError names the jobs.
  void flush();
  // Has the store's thread flush soon; returns at once. Its failures wait in take_failures().
  void flush_soon();
  std::vector<StoreError> take_failures();
  // Flushes the store's thread has finished since open (for tests).
  long long background_flushes() const;
  std::size_t queued() const;
  // Drops the job's queued results (a finished job is restored from its state and images,
  // never from its results; a job failed because its results could not be stored would fail
  // again writing them), flushes the other jobs', then records the final state, finish time
  // and images (written as files).
  void finish_job(std::int64_t job, const std::string& state, const std::string& error,
                  WallClock::time_point finished, const std::vector<StoredImage>& images);

  // Every job with its request, flushed results and image names, by id.
  std::vector<StoredJob> load_all();
  // Up to `limit` jobs with ids above `after_id`, by id.
  std::vector<JobListing> list(int limit, std::int64_t after_id = 0);
  std::filesystem::path image_path(std::int64_t job, const std::string& name) const;

  // Retention: deletes finished jobs that finished before now - keep_finished, then the
  // oldest finished jobs while size_bytes() > max_disk_bytes. Unfinished jobs are never
  // deleted. Returns the deleted ids.
  std::vector<std::int64_t> prune(WallClock::time_point now, std::chrono::seconds keep_finished,
                                  std::int64_t max_disk_bytes);
  // The database's used pages plus every bundle, image and result file.
  std::int64_t size_bytes();

 private:
  struct QueuedResult {
    std::int64_t job, sequence;
    int unit;
    FloatValues payload;  // the result's values, taken over from the message
    RenderStats stats;    // turned into JSON by the flush, off the io thread that appends
    std::string worker;
  };

  void open();  // the constructor's work, before its errors are given the directory's name
  std::int64_t size_locked();
  void check_budget(const std::vector<std::int64_t>& jobs);
  void flush_locked();
  // Forgets the job's queued results and next sequence number.
  void drop_queued(std::int64_t job);
  void delete_job_locked(std::int64_t job);
  void sweep_orphans();
  std::filesystem::path bundle_path(const std::string& hash) const;
  // The job's results' payloads, DIR/results/<job> (result_files.h).
  std::filesystem::path result_file(std::int64_t job) const;

  std::filesystem::path dir_;
  std::int64_t max_disk_bytes_;
  // Whoever holds both takes mutex_ (the connection's) first.
  std::unique_ptr<sqlite::Connection> db_;
  mutable std::mutex mutex_;
  mutable std::mutex queue_mutex_;  // the three below
  std::vector<QueuedResult> queue_;
  std::map<std::int64_t, std::int64_t> next_sequence_;  // by job, once known
  std::vector<StoreError> failures_;                    // of background flushes
  // Last: stopped (a flush under way finished) before anything it uses goes.
  std::unique_ptr<FlushThread> flush_thread_;
};

}  // namespace tessera
