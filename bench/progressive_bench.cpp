// The price of progressive refinement (issue 4): the whole progressive plan — every level's
// anchors, unit by unit, through render_pixels, merged into a frame buffer as the coordinator
// does — against one direct render_pass of the image, both on one thread, same pixels, same
// samples. The ratio of the two is the overhead; the target is at most 1.05.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

#include "common/loaders/sdl_loader.h"
#include "common/progressive/plan.h"
#include "common/render/frame_buffer.h"
#include "common/render/render.h"

namespace tessera {
namespace {

constexpr int kWidth = 320, kHeight = 240;

RenderSettings demo_settings(int aa) {
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.aa_samples = aa;
  return settings;
}

const PreparedScene& demo_scene() {
  static const Scene scene = load_sdl_file(std::string(TESSERA_SOURCE_DIR) + "/scenes/demo.sdl");
  static const PreparedScene prepared(scene, BvhMode::Sah);
  return prepared;
}

void merge(FrameBuffer& frame, int x, int y, const Rgb& c) {
  const float rgb[3] = {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
  frame.add_pass(x, y, rgb);
}

void BM_Direct(benchmark::State& state) {
  const RenderSettings settings = demo_settings(static_cast<int>(state.range(0)));
  std::vector<Rgb> out(static_cast<std::size_t>(kWidth) * kHeight);
  RenderStats stats;
  for (auto _ : state) {
    FrameBuffer frame(kWidth, kHeight);
    render_pass(demo_scene(), settings, {0, 0, kWidth, kHeight}, 0, out, stats);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) merge(frame, x, y, out[y * kWidth + x]);
    benchmark::DoNotOptimize(frame);
  }
}

void BM_Progressive(benchmark::State& state) {
  const RenderSettings settings = demo_settings(static_cast<int>(state.range(0)));
  const Plan plan = make_plan({.width = kWidth, .height = kHeight});
  RenderStats stats;
  for (auto _ : state) {
    FrameBuffer frame(kWidth, kHeight);
    for (const WorkUnit& unit : plan.units) {
      const std::vector<PixelCoord> coords = expand(unit.pixels);
      std::vector<Rgb> out(coords.size());
      render_pixels(demo_scene(), settings, coords, plan.stages[unit.stage].pass, out, stats);
      for (std::size_t i = 0; i < coords.size(); ++i)
        merge(frame, coords[i].x, coords[i].y, out[i]);
    }
    benchmark::DoNotOptimize(frame);
  }
  state.counters["units"] = static_cast<double>(plan.units.size());
}

// The floor of the coordinator's merge (issue 22 §3: 200 M pixel passes a second on one core):
// a 2048x2048 job's plan at 4 passes, in the capacity benchmark's units of 16,132 pixels (its
// units before `units64k`, kept so that the figures compare), added into a new frame buffer
// as Job::apply_result does, with nothing else (no socket, no store, no checks). Items are
// pixel passes.
struct MergedJob {
  Plan plan;
  long long pixel_passes = 0;
  std::vector<float> values;  // enough for its largest unit
};
MergedJob merged_job(int side) {
  MergedJob job;
  job.plan = make_plan({.width = side, .height = side, .passes = 4, .unit_pixels = 16132});
  long long largest = 0;
  for (const WorkUnit& unit : job.plan.units) {
    largest = std::max(largest, unit.cost);
    job.pixel_passes += unit.cost;
  }
  job.values.assign(3 * static_cast<std::size_t>(largest), 0.25f);
  return job;
}

void BM_MergeRuns(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const MergedJob job = merged_job(side);
  for (auto _ : state) {
    FrameBuffer frame(side, side);
    frame.count_by_units(job.plan);
    for (const WorkUnit& unit : job.plan.units) frame.add_unit(unit.pixels, job.values.data());
    benchmark::DoNotOptimize(frame);
  }
  state.SetItemsProcessed(state.iterations() * job.pixel_passes);
}
BENCHMARK(BM_MergeRuns)->Arg(2048)->Arg(256)->Unit(benchmark::kMillisecond);

// The same into one frame buffer cleared between rounds, as a job's memory comes from the
// pool already mapped (mapping_pool.h): MergeRuns' new buffer faults its pages in during pass 0,
// which hides what the merge itself costs. The second argument 0 counts pass 0 over the levels
// by pixel, as before branch merge8, 1 by level tile (docs/SCALING.md).
void BM_MergeRunsReused(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const MergedJob job = merged_job(side);
  Plan counted = job.plan;
  if (state.range(1) == 0)
    std::erase_if(counted.stages, [](const Stage& s) { return s.level > 0; });
  FrameBuffer frame(side, side);
  frame.count_by_units(counted);
  for (auto _ : state) {
    state.PauseTiming();
    frame.clear();
    state.ResumeTiming();
    for (const WorkUnit& unit : job.plan.units) frame.add_unit(unit.pixels, job.values.data());
    benchmark::DoNotOptimize(frame);
  }
  state.SetItemsProcessed(state.iterations() * job.pixel_passes);
}
BENCHMARK(BM_MergeRunsReused)
    ->Args({2048, 0})
    ->Args({2048, 1})
    ->Args({256, 0})
    ->Args({256, 1})
    ->Unit(benchmark::kMillisecond);

// Interleaved so that the machine's load drifts across both alike.
BENCHMARK(BM_Direct)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Progressive)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Direct)->Arg(9)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Progressive)->Arg(9)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tessera
