// A job in the coordinator: what was asked (bundle, settings, plan), and what has come back
// (frame buffer, display image, per-stage timings, statistics, per-worker shares). Plain data
// plus the merge of one unit's result; the scheduler decides what runs where.
#pragma once

#include <chrono>
#include <cstdint>
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

// Which worker rendered which unit, for the page's overlay.
struct TileRecord {
  Tile rect;
  int stage = 0;
  std::int64_t worker = 0;
};

struct Job {
  Job(std::int64_t id, Bundle bundle, JobSpec spec, PlanOptions plan_options, int priority);

  std::int64_t id;
  Bundle bundle;
  std::string hash;
  JobSpec spec;
  PlanOptions plan_options;
  int priority;
  std::string client;  // the submitter's address, for the per-client cap on unfinished jobs
  Plan plan;
  std::vector<std::string> effects, warnings;
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
  std::vector<TileRecord> tiles;

  FrameBuffer frame_buffer;
  Image display;                  // what the page shows: blocks filled with their anchor's colour
  std::vector<int> display_rank;  // per pixel: how fine the value shown there is
  std::uint64_t version = 0;      // bumps whenever `display` changes

  // Once finished the buffers above are freed (release_buffers): a done job keeps only its
  // final image, as pixels until the coordinator has encoded it, then only encoded; a
  // cancelled or failed job keeps no image. So memory is bounded by the running jobs.
  std::shared_ptr<const Image> final_image;
  std::map<std::string, std::shared_ptr<const std::string>> final_encoded;  // "png", "exr"
  // Called by release_buffers, on the io thread: the coordinator encodes the final image.
  std::function<void(Job&)> on_released;

  bool finished_state() const {
    return state == JobState::Done || state == JobState::Failed || state == JobState::Cancelled;
  }
  // Merges one unit's values (3 floats per pixel of expand(unit), in that order).
  void apply_result(int unit, std::span<const float> values);
  // The final image once done (bit-identical to tessera-render), else the display image;
  // post-normalized when the settings ask for it. Only before release_buffers.
  Image image() const;
  // Called once the state is final (Scheduler::finish): keeps the final image of a done job,
  // frees the frame buffer, display, ranks and tile records, and returns the memory to the
  // system (malloc_trim).
  void release_buffers();
  // Frees the frame buffer, display, ranks and tile records (a job restored finished never
  // needs them).
  void free_buffers();
  double elapsed_seconds(Clock::time_point now) const;
  std::optional<double> eta_seconds(Clock::time_point now) const;
  // The first stage not finished: the level or pass being refined now.
  int current_stage() const;
};

}  // namespace tessera
