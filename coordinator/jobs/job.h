// A job in the coordinator: what was asked (bundle, settings, plan), and what has come back
// (frame buffer, the log of merged units the page paints, per-stage timings, statistics,
// per-worker shares). What was asked is fixed before the job is queued; what has come back
// changes only through the job's methods, each called by one owner: the scheduler records
// dispatches and results and ends the job (record_dispatch, apply_result, finish), the API
// keeps the encoded final image and frees the last tile records (keep_encodings,
// free_buffers), and persistence restores jobs after a restart (apply_result replays,
// restore_finished, restore_unfinished) and fails those whose results it cannot store
// (fail_unstored). The scheduler decides what runs where.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/progressive/plan.h"
#include "common/protocol/bundle.h"
#include "common/protocol/job_spec.h"
#include "common/render/frame_buffer.h"
#include "coordinator/jobs/image_snapshot.h"

namespace tessera {

using Clock = std::chrono::steady_clock;

enum class JobState { Queued, Running, Done, Failed, Cancelled };
const char* to_string(JobState state);

struct StageTiming {
  std::optional<Clock::time_point> first_dispatch, last_result;
  int units_done = 0;
};

// One worker's part in a job, for the page's per-worker shares.
struct WorkerShare {
  std::string name;
  long long units = 0, pixels = 0;
  double seconds = 0;
};

// One merged unit, in merge order: which unit and worker, and when. What the page paints for
// it (GET /api/jobs/{id}/tiles, docs/SERVICE.md) is made when a page asks (tile_pixels.h):
// the means so far of the unit's pixels, read from the job's frame buffer; only an area
// preview's values, which no frame buffer keeps, are held here. A level's values stand for
// their blocks (the page fills them).
struct TileRecord {
  int unit = 0;
  std::int64_t worker = 0;
  double merged_at_ms = 0;     // wall clock, milliseconds since 1970: for measuring latency
  std::string preview_values;  // an area preview's bytes (append_tile_values), else empty
};

// How far behind a page may be and still get records rather than the whole image: the bytes
// of the newest merged units' pixels, 8 MiB (about 2.8 million pixels' worth) or 1.5 bytes a
// pixel of larger images (half of one pass). It bounds an answer's work and what a page
// behind downloads, and the area previews' values a job keeps.
inline constexpr std::size_t kDeltaLogBytes = 8u << 20;
inline constexpr double kDeltaLogBytesPerPixel = 1.5;

class Job {
 public:
  // The final image's encodings by format ("png", "exr").
  using Encodings = std::map<std::string, std::shared_ptr<const std::string>>;

  Job(std::int64_t id, Bundle bundle, JobSpec spec, PlanOptions plan_options, int priority);

  // What was asked: set at construction, or by JobStore::create and at admission (the
  // prediction) before the job is queued, and never changed after.
  std::int64_t id;
  // Shared and never changed: a rerender (POST /api/jobs/{id}/rerender) reads it on an intake
  // thread without copying it on the io thread, even if the job is evicted meanwhile.
  std::shared_ptr<const Bundle> bundle;
  std::string hash;
  JobSpec spec;
  PlanOptions plan_options;
  int priority;
  std::string client;  // the submitter's address, for the per-client cap on unfinished jobs
  Plan plan;
  std::vector<std::string> effects;
  std::optional<Camera> camera;  // JobRequest::camera
  std::vector<NamedCamera> viewpoints;
  // The prediction made at submission from the probe and the worker threads then connected
  // (issue 5); empty when no worker was connected.
  double seconds_per_pixel_pass = 0;
  std::optional<double> uncalibrated_prediction, predicted_seconds;
  int prediction_threads = 0;  // the worker threads the prediction was made for
  // The tile log's bound in bytes (kDeltaLogBytes; tests make it small).
  std::size_t delta_log_bytes;

  // Called by release_buffers, on the io thread: the coordinator encodes the final image.
  std::function<void(Job&)> on_released;
  // Called after every merge and when the job finishes, on the io thread: answers the long
  // polls waiting for this job's tiles.
  std::function<void(Job&)> on_changed;

  // What has come back. Changed only through the methods below, each one step of a job's life.

  // The scheduler sent a unit of `stage`: times the stage and the job from their first
  // dispatch. Returns true when this started the job (queued -> running).
  bool record_dispatch(int stage, Clock::time_point now);
  // Another job ran beside this one: its time no longer calibrates predictions (Scheduler).
  void mark_ran_beside_another() { ran_alone_ = false; }
  // A worker's failure report the job survives (the scheduler lets another worker try).
  void add_warning(std::string warning) { warnings_.push_back(std::move(warning)); }
  // Merges one unit's values (3 floats per pixel of for_each_pixel(unit), in that order, exactly
  // as many as the unit's cost in pixels: callers check), logs it as a
  // tile record and counts it in the job's progress and statistics; `from` says which worker
  // sent it and when, for the tile record, the per-worker shares and the stage's timing (none
  // for results replayed from the store). The scheduler and JobPersistence::restore call it.
  struct ResultSource {
    std::int64_t worker = 0;
    std::string name;
    Clock::time_point at;
  };
  void apply_result(int unit, std::span<const float> values, const RenderStats& stats,
                    const std::optional<ResultSource>& from = std::nullopt);
  // The job ends (Scheduler::finish): done, failed or cancelled at `now`, with the error for
  // the page; then release_buffers.
  void finish(JobState state, std::string error, Clock::time_point now);
  // The coordinator encoded the final image (after release_buffers): only the encodings stay.
  void keep_encodings(Encodings encoded);
  // A done job whose results cannot be stored fails after all, keeping no image
  // (JobPersistence::store_images).
  void fail_unstored(std::string error);
  // A job restored from the store (JobPersistence::restore), created at `created`: finished as
  // the store says, with its stored encodings and no buffers...
  void restore_finished(Clock::time_point created, JobState state, std::string error,
                        Clock::time_point finished, Encodings encoded);
  // ... or unfinished, after its stored results were replayed: running again since `started`
  // if the store held results of it, else queued.
  void restore_unfinished(Clock::time_point created, std::optional<Clock::time_point> started);
  // Frees the frame buffer and the tile records: the coordinator does once a done job's last
  // pages had time to catch up (a job restored finished has none).
  void free_buffers();

  JobState state() const { return state_; }
  bool finished_state() const {
    return state_ == JobState::Done || state_ == JobState::Failed || state_ == JobState::Cancelled;
  }
  const std::string& error() const { return error_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  bool ran_alone() const { return ran_alone_; }  // its time can calibrate predictions
  Clock::time_point created() const { return created_; }
  std::optional<Clock::time_point> started() const { return started_; }
  std::optional<Clock::time_point> finished() const { return finished_; }
  const std::vector<StageTiming>& stage_timing() const { return stage_timing_; }
  long long done_cost() const { return done_cost_; }
  const RenderStats& stats() const { return stats_; }
  const std::map<std::int64_t, WorkerShare>& shares() const { return shares_; }  // by worker id
  // Merged units from sequence number tiles_first on (tiles()[i] is number tiles_first + i);
  // those before delta_first no longer give their pixels (kDeltaLogBytes): a page that far
  // behind loads the whole image. delta_bytes: the pixel bytes of those from delta_first on.
  const std::deque<TileRecord>& tiles() const { return tiles_; }
  std::size_t tiles_first() const { return tiles_first_; }
  std::size_t delta_first() const { return delta_first_; }
  std::size_t delta_bytes() const { return delta_bytes_; }
  std::size_t tiles_next() const { return tiles_first_ + tiles_.size(); }
  const FrameBuffer& frame_buffer() const { return frame_buffer_; }
  // What the tile records from delta_first on read their values from: the frame buffer, or a
  // done job's final pixels until its image is encoded (then no record gives pixels).
  const FrameBuffer& tile_pixels() const { return final_pixels_ ? *final_pixels_ : frame_buffer_; }
  // Bumps with every merged unit and when the job ends: what its image depends on (ETags).
  std::uint64_t version() const { return version_; }
  const Encodings& final_encoded() const { return final_encoded_; }

  // What the job's image is made of, for an intake thread to make it (ImageSnapshot::image):
  // the final image once done (bit-identical to tessera-render), else what is known so far;
  // post-normalized when the settings ask for it. On the io thread this costs no pass over the
  // pixels: a done job's frame buffer is shared until its final image is encoded
  // (keep_encodings), a running job's is copied (12-14 bytes a pixel).
  ImageSnapshot snapshot() const;
  double elapsed_seconds(Clock::time_point now) const;
  std::optional<double> eta_seconds(Clock::time_point now) const;
  // The first stage not finished: the level or pass being refined now.
  int current_stage() const;

 private:
  // Once the state is final (finish): keeps a done job's frame buffer, shared, for its final
  // image (made and encoded off the io thread, Api::on_released), and the tile records
  // that still have pixels (for pages catching up with the last merges; the coordinator frees
  // them a little later with free_buffers); frees the rest (the memory goes back to the
  // system once the coordinator is idle, idle_memory.h).
  void release_buffers();
  // Moves delta_first past the oldest tile records until those after it give at most
  // max_bytes of pixels.
  void trim_delta_log(std::size_t max_bytes);

  std::vector<std::string> warnings_;
  bool ran_alone_ = true;  // no other job ran beside it
  JobState state_ = JobState::Queued;
  std::string error_;
  Clock::time_point created_ = Clock::now();
  std::optional<Clock::time_point> started_, finished_;
  std::vector<StageTiming> stage_timing_;
  long long done_cost_ = 0;
  RenderStats stats_;
  std::map<std::int64_t, WorkerShare> shares_;
  std::deque<TileRecord> tiles_;
  std::size_t tiles_first_ = 0, delta_first_ = 0, delta_bytes_ = 0;
  // At most 14 bytes a pixel (12 while every pass merged was counted by tile, a whole-image
  // job's): the whole of a running job's memory per pixel. What the page shows is
  // painted by the page itself from the tile records; snapshot() derives it when asked.
  FrameBuffer frame_buffer_;
  std::uint64_t version_ = 0;
  // Once finished the buffers above are freed (release_buffers): a done job keeps only its
  // final image, as its frame buffer until the coordinator has encoded it, then only encoded;
  // a cancelled or failed job keeps no image. So memory is bounded by the running jobs.
  std::shared_ptr<const FrameBuffer> final_pixels_;
  Encodings final_encoded_;
};

}  // namespace tessera
