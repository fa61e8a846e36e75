// A job in the coordinator: what was asked (bundle, settings, plan), and what has come back
// (frame buffer, the log of merged units the page paints, per-stage timings, statistics,
// per-worker shares). Plain data plus the merge of one unit's result; the scheduler decides
// what runs where.
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

#include "common/image/to_8bit.h"  // the tile records' values
#include "common/progressive/plan.h"
#include "common/protocol/bundle.h"
#include "common/protocol/job_spec.h"
#include "common/render/frame_buffer.h"

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

// One merged unit, in merge order: where it is, which stage and worker, and what the page
// paints for it (GET /api/jobs/{id}/tiles, docs/SERVICE.md): one 8-bit RGB value per traced
// pixel, in expand() order, each byte the difference from the same channel of the pixel before
// (mod 256, the first pixel as it is), so that smooth images compress well. A level's values
// stand for their blocks (the page fills them); a whole-image pass's are the pixels' means so
// far. Emptied once the log holds more than kDeltaLogBytes of newer values.
struct TileRecord {
  PixelRect rect;
  int stage = 0;
  std::int64_t worker = 0;
  double merged_at_ms = 0;  // wall clock, milliseconds since 1970: for measuring latency
  std::string pixels;
};

// The newest pixels of merged units a job keeps for pages that poll: older records keep their
// place (for the worker overlay) but not their pixels, and a page further behind loads the
// whole image instead. 8 MiB (about 2.8 million pixels' worth), or 1.5 bytes a pixel of larger
// images (half of one pass), which keeps a running job within 15.5 bytes a pixel.
inline constexpr std::size_t kDeltaLogBytes = 8u << 20;
inline constexpr double kDeltaLogBytesPerPixel = 1.5;

struct Job {
  Job(std::int64_t id, Bundle bundle, JobSpec spec, PlanOptions plan_options, int priority);

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
  std::vector<std::string> effects, warnings;
  std::optional<Camera> camera;  // JobRequest::camera
  std::vector<NamedCamera> viewpoints;
  // The prediction made at submission from the probe and the worker threads then connected
  // (issue 5); empty when no worker was connected.
  double seconds_per_pixel_pass = 0;
  std::optional<double> uncalibrated_prediction, predicted_seconds;
  int prediction_threads = 0;  // the worker threads the prediction was made for
  bool ran_alone = true;       // no other job ran beside it: its time can calibrate predictions

  JobState state = JobState::Queued;
  std::string error;
  Clock::time_point created = Clock::now();
  std::optional<Clock::time_point> started, finished;

  std::vector<StageTiming> stage_timing;
  long long done_cost = 0;
  RenderStats stats;
  std::map<std::int64_t, WorkerShare> shares;  // by worker id
  // Merged units from sequence number tiles_first on (tiles[i] is number tiles_first + i); the
  // pixels of those before delta_first are dropped (kDeltaLogBytes).
  std::deque<TileRecord> tiles;
  std::size_t tiles_first = 0, delta_first = 0, delta_bytes = 0;
  std::size_t delta_log_bytes;  // the log's bound (tests make it small)
  std::size_t tiles_next() const { return tiles_first + tiles.size(); }

  // 14 bytes a pixel: the whole of a running job's memory per pixel. What the page shows is
  // painted by the page itself from the tile records; image() derives it when asked.
  FrameBuffer frame_buffer;
  std::uint64_t version = 0;  // bumps with every merged unit and state change

  // Once finished the buffers above are freed (release_buffers): a done job keeps only its
  // final image, as pixels until the coordinator has encoded it, then only encoded; a
  // cancelled or failed job keeps no image. So memory is bounded by the running jobs.
  std::shared_ptr<const Image> final_image;
  std::map<std::string, std::shared_ptr<const std::string>> final_encoded;  // "png", "exr"
  // Called by release_buffers, on the io thread: the coordinator encodes the final image.
  std::function<void(Job&)> on_released;
  // Called after every merge and when the job finishes, on the io thread: answers the long
  // polls waiting for this job's tiles.
  std::function<void(Job&)> on_changed;

  bool finished_state() const {
    return state == JobState::Done || state == JobState::Failed || state == JobState::Cancelled;
  }
  // Merges one unit's values (3 floats per pixel of expand(unit), in that order) rendered by
  // `worker`, and logs it as a tile record.
  void apply_result(int unit, std::span<const float> values, std::int64_t worker = 0);
  // The final image once done (bit-identical to tessera-render), else what is known so far:
  // each pixel shows the finest anchor merged over it (area previews are only in the tile
  // records); post-normalized when the settings ask for it. Only before release_buffers.
  Image image() const;
  // Called once the state is final (Scheduler::finish): keeps the final image of a done job
  // and the tile records that still have pixels (for pages catching up with the last merges;
  // the coordinator frees them a little later with free_buffers), frees the frame buffer and
  // the rest, and returns the memory to the system (malloc_trim).
  void release_buffers();
  // Frees the frame buffer and the tile records (a job restored finished never needs them).
  void free_buffers();
  double elapsed_seconds(Clock::time_point now) const;
  std::optional<double> eta_seconds(Clock::time_point now) const;
  // The first stage not finished: the level or pass being refined now.
  int current_stage() const;

 private:
  // Drops the pixels of the oldest tile records until those kept hold at most max_bytes.
  void trim_delta_log(std::size_t max_bytes);
  Image known_so_far() const;
};

}  // namespace tessera
