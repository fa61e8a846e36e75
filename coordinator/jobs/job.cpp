#include "coordinator/jobs/job.h"

#include "coordinator/jobs/tile_pixels.h"

#include <algorithm>
#include <chrono>
#include <iterator>

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
      frame_buffer_(FrameBuffer::deferred(spec.settings.width, spec.settings.height)) {
  frame_buffer_.count_by_units(plan);
}

namespace {

double wall_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
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
  TileRecord record{unit_index, from ? from->worker : 0, wall_clock_ms(), {}};
  // A row of pixels at a time; the page's bytes of this unit are made when a page asks
  // (encode_tiles), except an area preview's, whose values the frame buffer does not keep.
  if (stage.preview_only) {
    if (!spec.settings.normalize_colors) append_tile_values(record.preview_values, values);
  } else {
    if (!frame_buffer_.has_memory()) frame_buffer_.take_memory();
    frame_buffer_.add_unit(unit.pixels, values.data());
  }
  // Normalized jobs' values change with the whole image's highest one: the page loads the PNG.
  if (!spec.settings.normalize_colors) delta_bytes_ += 3 * static_cast<std::size_t>(unit.cost);
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
  // The records' values were read from those pixels: pages still behind load the final image.
  trim_delta_log(0);
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
    TileRecord& dropped = tiles_[delta_first_ - tiles_first_];
    delta_bytes_ -= 3 * static_cast<std::size_t>(plan.units[dropped.unit].cost);
    dropped.preview_values = std::string();
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
    // Pages still polling get the last merges, their values read from those pixels until the
    // final image is encoded (keep_encodings); later ones load the final image.
    const std::size_t keep = tiles_next() - delta_first_;
    std::deque<TileRecord> tail(
        std::make_move_iterator(tiles_.end() - static_cast<std::ptrdiff_t>(keep)),
        std::make_move_iterator(tiles_.end()));
    const std::size_t next = tiles_next();
    frame_buffer_ = FrameBuffer(0, 0);
    tiles_ = std::move(tail);
    tiles_first_ = next - keep;
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
