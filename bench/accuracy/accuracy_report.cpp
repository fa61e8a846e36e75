#include "bench/accuracy/accuracy_report.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include "common/progressive/plan.h"
#include "common/render/frame_buffer.h"
#include "common/render/render.h"

namespace tessera {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Scene with_depth(const Scene& scene, int depth) {
  Scene copy = scene;
  copy.globals.max_recursion_depth = depth;
  return copy;
}

// Renders once untimed-for-choice: returns the image of the last repeat and the median time.
Image render_timed(const Scene& scene, const Variant& v, int repeats, int threads,
                   double& median_seconds) {
  const Scene depth_scene = with_depth(scene, v.max_depth);
  const PreparedScene prepared(depth_scene, v.settings.bvh);
  std::vector<double> times;
  Image image;
  for (int r = 0; r < repeats; ++r) {
    RenderStats stats;
    const auto start = Clock::now();
    image = render_image(prepared, v.settings, threads, stats);
    times.push_back(since(start));
  }
  std::sort(times.begin(), times.end());
  median_seconds = times[times.size() / 2];
  return image;
}

// Traces the progressive levels of pass 0 at the base settings, one level at a time, and
// compares the preview shown after each level (every pixel shows its block's anchor).
std::vector<LevelRow> measure_levels(const Scene& scene, const RenderSettings& base,
                                     const Image& reference) {
  const PreparedScene prepared(scene, base.bvh);
  const Plan plan = make_plan({.width = base.width, .height = base.height});
  Image anchors(base.width, base.height);
  std::vector<LevelRow> rows;
  double cumulative = 0;
  for (const Stage& stage : plan.stages) {
    if (stage.level == 0) continue;  // whole-image passes: not part of the refinement
    RenderStats stats;
    const auto start = Clock::now();
    for (int u = stage.first_unit; u < stage.first_unit + stage.unit_count; ++u) {
      const std::vector<PixelCoord> coords = expand(plan.units[u].pixels);
      std::vector<Rgb> values(coords.size());
      render_pixels(prepared, base, coords, stage.pass, values, stats);
      for (std::size_t i = 0; i < coords.size(); ++i)
        anchors.set(coords[i].x, coords[i].y, values[i]);
    }
    const double seconds = since(start);
    cumulative += seconds;
    Image preview(base.width, base.height);
    for (int y = 0; y < base.height; ++y)
      for (int x = 0; x < base.width; ++x) {
        const PixelCoord a = block_of({x, y}, stage.block);
        preview.set(x, y, anchors.get(a.x, a.y));
      }
    rows.push_back({stage.level, stage.block, stage.blocks, stage.traced, seconds, cumulative,
                    compare_images(preview, reference)});
  }
  return rows;
}

}  // namespace

void mark_pareto_front(std::vector<Measured>& measured) {
  for (Measured& m : measured) {
    m.pareto = std::none_of(measured.begin(), measured.end(), [&](const Measured& o) {
      const bool no_worse = o.seconds <= m.seconds && o.error.rmse <= m.error.rmse;
      const bool better = o.seconds < m.seconds || o.error.rmse < m.error.rmse;
      return &o != &m && no_worse && better;
    });
  }
}

AccuracyReport measure_accuracy(const Scene& scene, const std::string& scene_name,
                                const AccuracyOptions& options) {
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const Sweep sweep = make_sweep(scene, options.base);
  AccuracyReport report;
  report.scene_name = scene_name;
  report.effects = PreparedScene(scene, BvhMode::Sah).effects().names();
  report.width = options.base.width;
  report.height = options.base.height;
  report.threads = options.threads > 0
                       ? options.threads
                       : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  report.repeats = options.repeats;
  report.reference = sweep.reference;
  report.not_swept = sweep.not_swept;

  say("reference: " + sweep.reference.label);
  const Image reference =
      render_timed(scene, sweep.reference, 1, report.threads, report.reference_seconds);
  for (const Variant& v : sweep.variants) {
    say(v.knob + ": " + v.label);
    Measured m;
    m.variant = v;
    const Image image = render_timed(scene, v, options.repeats, report.threads, m.seconds);
    m.error = compare_images(image, reference);
    report.measured.push_back(m);
  }
  const double cheapest =
      std::min_element(report.measured.begin(), report.measured.end(),
                       [](const Measured& a, const Measured& b) { return a.seconds < b.seconds; })
          ->seconds;
  for (Measured& m : report.measured) m.time_ratio = cheapest > 0 ? m.seconds / cheapest : 1;
  mark_pareto_front(report.measured);
  say("progressive levels");
  report.levels = measure_levels(scene, options.base, reference);
  return report;
}

}  // namespace tessera
