#include "coordinator/jobs/job.h"

#include <algorithm>
#include <chrono>

#include <malloc.h>

#include "common/render/post_normalization.h"

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
      stage_timing(plan.stages.size()),
      delta_log_bytes(std::max(
          kDeltaLogBytes, static_cast<std::size_t>(kDeltaLogBytesPerPixel * spec.settings.width *
                                                   static_cast<double>(spec.settings.height)))),
      frame_buffer(spec.settings.width, spec.settings.height) {}

namespace {

double wall_clock_ms() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Appends one pixel's 8-bit values as differences from the previous pixel's (TileRecord).
void append_difference(std::string& out, std::uint8_t previous[3], const Rgb& value) {
  const std::uint8_t now[3] = {to_8bit(static_cast<float>(value.r)),
                               to_8bit(static_cast<float>(value.g)),
                               to_8bit(static_cast<float>(value.b))};
  for (int c = 0; c < 3; ++c) {
    out.push_back(static_cast<char>(static_cast<std::uint8_t>(now[c] - previous[c])));
    previous[c] = now[c];
  }
}

}  // namespace

void Job::apply_result(int unit_index, std::span<const float> values, std::int64_t worker) {
  const WorkUnit& unit = plan.units[unit_index];
  const Stage& stage = plan.stages[unit.stage];
  const std::vector<PixelCoord> pixels = expand(unit.pixels);
  // Normalized jobs' values change with the whole image's highest one: the page loads the PNG.
  const bool log_pixels = !spec.settings.normalize_colors;
  TileRecord record{unit.pixels.rect, unit.stage, worker, wall_clock_ms(), {}};
  if (log_pixels) record.pixels.reserve(3 * pixels.size());
  std::uint8_t previous[3] = {0, 0, 0};
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const PixelCoord p = pixels[i];
    const float* rgb = values.data() + 3 * i;
    if (!stage.preview_only) frame_buffer.add_pass(p.x, p.y, rgb);
    if (!log_pixels) continue;
    // A level's value stands for its block; a later pass shows the pixel's mean so far.
    append_difference(record.pixels, previous,
                      stage.level > 0 ? Rgb{rgb[0], rgb[1], rgb[2]} : frame_buffer.mean(p.x, p.y));
  }
  delta_bytes += record.pixels.size();
  tiles.push_back(std::move(record));
  trim_delta_log(delta_log_bytes);
  done_cost += unit.cost;
  ++version;
  if (on_changed) on_changed(*this);
}

void Job::trim_delta_log(std::size_t max_bytes) {
  while (delta_bytes > max_bytes && delta_first < tiles_next()) {
    std::string& dropped = tiles[delta_first - tiles_first].pixels;
    delta_bytes -= dropped.size();
    dropped = std::string();
    ++delta_first;
  }
}

Image Job::image() const {
  Image image = state == JobState::Done ? frame_buffer.resolve() : known_so_far();
  // Post-normalization needs the whole image (§4.6): applied here, never to units.
  const RenderSettings& s = spec.settings;
  if (s.normalize_colors) post_normalize(image, s.normalize_brightness);
  return image;
}

Image Job::known_so_far() const {
  const int w = frame_buffer.width(), h = frame_buffer.height();
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // The finest anchor merged over the pixel: the pixel itself once it has a pass, else
      // the anchor of its block at each coarser level (levels overlap across workers).
      for (int level = std::max(plan.levels, 1); level >= 1; --level) {
        const int side = plan.levels > 0 ? block_side(plan.levels, level) : 1;
        const PixelCoord a = block_of({x, y}, side);
        if (frame_buffer.passes_at(a.x, a.y) == 0) continue;
        image.set(x, y, frame_buffer.mean(a.x, a.y));
        break;
      }
    }
  return image;
}

void Job::release_buffers() {
  if (state == JobState::Done) {
    final_image = std::make_shared<const Image>(image());
    // Pages still polling get the last merges; later ones load the final image.
    const std::size_t keep = tiles_next() - delta_first;
    std::deque<TileRecord> tail(tiles.end() - static_cast<std::ptrdiff_t>(keep), tiles.end());
    const std::size_t next = tiles_next();
    frame_buffer = FrameBuffer(0, 0);
    tiles = std::move(tail);
    tiles_first = next - keep;
    malloc_trim(0);
  } else {
    free_buffers();
  }
  if (on_released) on_released(*this);
  if (on_changed) on_changed(*this);
}

void Job::free_buffers() {
  // Assigning empty containers frees their storage (clear() would keep the capacity).
  frame_buffer = FrameBuffer(0, 0);
  tiles_first = delta_first = tiles_next();
  tiles = std::deque<TileRecord>();
  delta_bytes = 0;
  malloc_trim(0);  // large frees go back to the system only when trimmed (glibc)
}

double Job::elapsed_seconds(Clock::time_point now) const {
  if (!started) return 0;
  return std::chrono::duration<double>(finished.value_or(now) - *started).count();
}

std::optional<double> Job::eta_seconds(Clock::time_point now) const {
  if (state == JobState::Done) return 0.0;
  if (state != JobState::Running || done_cost == 0) return std::nullopt;
  // The seeds' running estimate, over the whole job: remaining work at the rate so far.
  const double rate = elapsed_seconds(now) / static_cast<double>(done_cost);
  return rate * static_cast<double>(plan.total_cost - done_cost);
}

int Job::current_stage() const {
  for (std::size_t s = 0; s < plan.stages.size(); ++s)
    if (stage_timing[s].units_done < plan.stages[s].unit_count) return static_cast<int>(s);
  return static_cast<int>(plan.stages.size()) - 1;
}

}  // namespace tessera
