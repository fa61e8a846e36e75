#include "coordinator/jobs/job.h"

#include <algorithm>
#include <chrono>
#include <iterator>

#include <malloc.h>

namespace tessera {

const char* to_string(JobState state) {
  switch (state) {
    case JobState::Queued:
      return "queued";
    case JobState::Running:
      return "running";
    case JobState::Done:
      return "done";
    case JobState::Failed:
      return "failed";
    case JobState::Cancelled:
      return "cancelled";
  }
  return "unknown";
}

Job::Job(std::int64_t id_, Bundle bundle_, JobSpec spec_, PlanOptions plan_options_, int priority_)
    : id(id_),
      bundle(std::make_shared<const Bundle>(std::move(bundle_))),
      hash(content_hash(*bundle)),
      spec(std::move(spec_)),
      plan_options(plan_options_),
      priority(priority_),
      plan(make_plan(plan_options)),
      delta_log_bytes(std::max(
          kDeltaLogBytes, static_cast<std::size_t>(kDeltaLogBytesPerPixel * spec.settings.width *
                                                   static_cast<double>(spec.settings.height)))),
      stage_timing_(plan.stages.size()),
      frame_buffer_(spec.settings.width, spec.settings.height) {}

namespace {

double wall_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Pixels whose values the merge converts at a time (on the stack).
constexpr std::size_t kChunk = 256;

// Writes `count` pixels' 8-bit values (3 floats a pixel at `values`, at most kChunk pixels) as
// differences from the previous pixel's (TileRecord) at `out`, which has room for them;
// `previous` carries the last pixel's values from one call to the next.
void put_differences(char* out, std::uint8_t previous[3], const float* values, std::size_t count) {
  std::uint8_t now[3 * kChunk];
  const std::size_t n = 3 * count;
  to_8bit_run(values, n, now);
  for (std::size_t j = 0; j < 3; ++j)
    out[j] = static_cast<char>(static_cast<std::uint8_t>(now[j] - previous[j]));
  for (std::size_t j = 3; j < n; ++j)
    out[j] = static_cast<char>(static_cast<std::uint8_t>(now[j] - now[j - 3]));
  for (int c = 0; c < 3; ++c) previous[c] = now[n - 3 + c];
}

}  // namespace

bool Job::record_dispatch(int stage, Clock::time_point now) {
  StageTiming& timing = stage_timing_[stage];
  if (!timing.first_dispatch) timing.first_dispatch = now;
  if (!started_) started_ = now;
  if (state_ == JobState::Running) return false;
  state_ = JobState::Running;
  return true;
}

void Job::apply_result(int unit_index, std::span<const float> values, const RenderStats& stats,
                       const std::optional<ResultSource>& from) {
  const WorkUnit& unit = plan.units[unit_index];
  const Stage& stage = plan.stages[unit.stage];
  // Normalized jobs' values change with the whole image's highest one: the page loads the PNG.
  const bool log_pixels = !spec.settings.normalize_colors;
  TileRecord record{unit.pixels.rect, unit.stage, from ? from->worker : 0, wall_clock_ms(), {}};
  // Sized once and written through a pointer, not a push_back per byte: this loop runs for
  // every pixel pass the coordinator merges.
  if (log_pixels) record.pixels.resize(3 * static_cast<std::size_t>(unit.cost));
  char* delta = record.pixels.data();
  const float* rgb = values.data();
  std::uint8_t previous[3] = {0, 0, 0};
  // A row of pixels at a time: the merge and the tile record's bytes are loops over the row.
  for_each_run(unit.pixels, [&](PixelCoord first, int count, int stride) {
    if (!stage.preview_only) frame_buffer_.add_run(first, count, stride, rgb);
    if (log_pixels) {
      for (std::size_t done = 0; done < static_cast<std::size_t>(count); done += kChunk) {
        const std::size_t n = std::min(kChunk, static_cast<std::size_t>(count) - done);
        const float* shown = rgb + 3 * done;  // a level's value stands for its block
        float mean[3 * kChunk];
        if (stage.level == 0) {
          // A later pass shows the pixel's mean so far.
          frame_buffer_.mean_run({first.x + static_cast<int>(done) * stride, first.y},
                                 static_cast<int>(n), stride, mean);
          shown = mean;
        }
        put_differences(delta + 3 * done, previous, shown, n);
      }
      delta += 3 * static_cast<std::size_t>(count);
    }
    rgb += 3 * static_cast<std::size_t>(count);
  });
  delta_bytes_ += record.pixels.size();
  tiles_.push_back(std::move(record));
  trim_delta_log(delta_log_bytes);
  done_cost_ += unit.cost;
  stats_ += stats;
  StageTiming& timing = stage_timing_[unit.stage];
  timing.units_done += 1;
  if (from) {
    WorkerShare& share = shares_[from->worker];
    share.name = from->name;
    share.units += 1;
    share.pixels += unit.cost;
    share.seconds += stats.seconds;
    timing.last_result = from->at;
  }
  ++version_;
  if (on_changed) on_changed(*this);
}

void Job::finish(JobState state, std::string error, Clock::time_point now) {
  state_ = state;
  error_ = std::move(error);
  finished_ = now;
  ++version_;
  release_buffers();
}

void Job::keep_encodings(Encodings encoded) {
  final_encoded_ = std::move(encoded);
  final_pixels_.reset();
}

void Job::fail_unstored(std::string error) {
  state_ = JobState::Failed;
  error_ = std::move(error);
  final_encoded_.clear();
  ++version_;
}

void Job::restore_finished(Clock::time_point created, JobState state, std::string error,
                           Clock::time_point finished, Encodings encoded) {
  created_ = created;
  state_ = state;
  error_ = std::move(error);
  started_ = created;
  finished_ = finished;
  free_buffers();
  final_encoded_ = std::move(encoded);
}

void Job::restore_unfinished(Clock::time_point created, std::optional<Clock::time_point> started) {
  created_ = created;
  started_ = started;
  state_ = started ? JobState::Running : JobState::Queued;
}

void Job::trim_delta_log(std::size_t max_bytes) {
  while (delta_bytes_ > max_bytes && delta_first_ < tiles_next()) {
    std::string& dropped = tiles_[delta_first_ - tiles_first_].pixels;
    delta_bytes_ -= dropped.size();
    dropped = std::string();
    ++delta_first_;
  }
}

ImageSnapshot Job::snapshot() const {
  const RenderSettings& s = spec.settings;
  ImageSnapshot snapshot{final_pixels_, state_ == JobState::Done, plan.levels, s.normalize_colors,
                         s.normalize_brightness};
  if (!snapshot.pixels) snapshot.pixels = std::make_shared<const FrameBuffer>(frame_buffer_);
  return snapshot;
}

void Job::release_buffers() {
  if (state_ == JobState::Done) {
    // Moved, not copied: the io thread makes no image (Api::on_released).
    final_pixels_ = std::make_shared<const FrameBuffer>(std::move(frame_buffer_));
    // Pages still polling get the last merges (moved, not copied: up to the log's bound of
    // pixels); later ones load the final image.
    const std::size_t keep = tiles_next() - delta_first_;
    std::deque<TileRecord> tail(
        std::make_move_iterator(tiles_.end() - static_cast<std::ptrdiff_t>(keep)),
        std::make_move_iterator(tiles_.end()));
    const std::size_t next = tiles_next();
    frame_buffer_ = FrameBuffer(0, 0);
    tiles_ = std::move(tail);
    tiles_first_ = next - keep;
    malloc_trim(0);
  } else {
    free_buffers();
  }
  if (on_released) on_released(*this);
  if (on_changed) on_changed(*this);
}

void Job::free_buffers() {
  // Assigning empty containers frees their storage (clear() would keep the capacity).
  frame_buffer_ = FrameBuffer(0, 0);
  tiles_first_ = delta_first_ = tiles_next();
  tiles_ = std::deque<TileRecord>();
  delta_bytes_ = 0;
  malloc_trim(0);  // large frees go back to the system only when trimmed (glibc)
}

double Job::elapsed_seconds(Clock::time_point now) const {
  if (!started_) return 0;
  return std::chrono::duration<double>(finished_.value_or(now) - *started_).count();
}

std::optional<double> Job::eta_seconds(Clock::time_point now) const {
  if (state_ == JobState::Done) return 0.0;
  if (state_ != JobState::Running || done_cost_ == 0) return std::nullopt;
  // The seeds' running estimate, over the whole job: remaining work at the rate so far.
  const double rate = elapsed_seconds(now) / static_cast<double>(done_cost_);
  return rate * static_cast<double>(plan.total_cost - done_cost_);
}

int Job::current_stage() const {
  for (std::size_t s = 0; s < plan.stages.size(); ++s)
    if (stage_timing_[s].units_done < plan.stages[s].unit_count) return static_cast<int>(s);
  return static_cast<int>(plan.stages.size()) - 1;
}

}  // namespace tessera
