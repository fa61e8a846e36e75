#include "coordinator/jobs/job.h"

#include <algorithm>

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
      bundle(std::move(bundle_)),
      hash(content_hash(bundle)),
      spec(std::move(spec_)),
      plan_options(plan_options_),
      priority(priority_),
      plan(make_plan(plan_options)),
      stage_timing(plan.stages.size()),
      frame_buffer(spec.settings.width, spec.settings.height),
      display(spec.settings.width, spec.settings.height),
      display_rank(static_cast<std::size_t>(spec.settings.width) * spec.settings.height, 0) {}

void Job::apply_result(int unit_index, std::span<const float> values) {
  const WorkUnit& unit = plan.units[unit_index];
  const Stage& stage = plan.stages[unit.stage];
  const std::vector<Pixel> pixels = expand(unit.pixels);
  const int w = display.width, h = display.height;
  // Ranks: level l fills blocks with rank l; whole-image passes rank above every level.
  const int rank = stage.level > 0 ? stage.level : plan.levels + 1 + stage.pass;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const Pixel p = pixels[i];
    const float* rgb = values.data() + 3 * i;
    if (!stage.preview_only) frame_buffer.add_pass(p.x, p.y, rgb);
    if (stage.level > 0) {
      // A coarse block takes its sample's colour wherever nothing finer has arrived yet.
      const Pixel b = block_of(p, stage.block);
      for (int y = b.y; y < std::min(b.y + stage.block, h); ++y)
        for (int x = b.x; x < std::min(b.x + stage.block, w); ++x) {
          int& shown = display_rank[static_cast<std::size_t>(y) * w + x];
          if (shown >= rank) continue;
          shown = rank;
          display.set(x, y, {rgb[0], rgb[1], rgb[2]});
        }
    } else {
      display_rank[static_cast<std::size_t>(p.y) * w + p.x] = rank;
      display.set(p.x, p.y, frame_buffer.mean(p.x, p.y));
    }
  }
  done_cost += unit.cost;
  ++version;
}

Image Job::image() const {
  Image image = state == JobState::Done ? frame_buffer.resolve() : display;
  // Post-normalization needs the whole image (§4.6): applied here, never to units.
  const RenderSettings& s = spec.settings;
  if (s.normalize_colors) post_normalize(image, s.normalize_brightness);
  return image;
}

void Job::release_buffers() {
  if (state == JobState::Done) final_image = std::make_shared<const Image>(image());
  free_buffers();
  if (on_released) on_released(*this);
}

void Job::free_buffers() {
  // Assigning empty containers frees their storage (clear() would keep the capacity).
  frame_buffer = FrameBuffer(0, 0);
  display = Image();
  display_rank = std::vector<int>();
  tiles = std::vector<TileRecord>();
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
