// Interrupting a render (issue 16 §3) and the ray budget of a pixel sample, on the runaway
// scene of the issue: a pixel in progress stops soon after its cancel flag or its deadline,
// and without either its cost is bounded by the budget, its value the same every time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <map>
#include <string>
#include <thread>

#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"
#include "common/render/interrupt.h"
#include "common/render/render.h"
#include "common/render/time_prediction.h"
#include "common/render/tracer.h"

namespace tessera::test {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// The glossy mirror hall: the eye inside a mirror sphere with no weight cut-off, so that every
// hit branches into 64 rays, 16 deep: 64^16 rays a sample without the budget.
constexpr const char* kMirrorHall =
    "eyePoint 0 0 0\nviewPoint 0 0 -1\nupDirection 0 1 0\nlight 0 0.5 0  1 1 1\n"
    "maxRecursionDepth 16\nminReflectivity 0\n"
    "push scale 10 10 10 reflectivity 0.95 glossStrength 0.5 sphere pop\n";

class MirrorHall : public ::testing::Test {
 protected:
  MirrorHall()
      : scene_(load_sdl(MemorySource(std::map<std::string, std::string>{{"hall.sdl", kMirrorHall}}),
                        "hall.sdl")),
        prepared_(scene_, BvhMode::Sah) {
    settings_.width = 8;
    settings_.height = 8;
    settings_.cone_samples = 64;
  }

  // Traces pixel (4, 4) of pass 0.
  Rgb pixel(const RenderSettings& s, RenderStats& stats, const RenderInterrupt& interrupt = {}) {
    const PixelCoord p{4, 4};
    Rgb value;
    render_pixels(prepared_, s, {&p, 1}, 0, {&value, 1}, stats, interrupt);
    return value;
  }

  Scene scene_;
  PreparedScene prepared_;
  RenderSettings settings_;
};

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

TEST_F(MirrorHall, CancelFlagStopsAPixelInProgressWithin100Ms) {
  // Nine samples each at the ray budget: seconds of work, far past the 50 ms.
  RenderSettings s = settings_;
  s.aa_samples = 9;
  std::atomic<bool> cancel{false};
  Clock::time_point cancelled_at;
  std::thread canceller([&] {
    std::this_thread::sleep_for(milliseconds(50));
    cancelled_at = Clock::now();
    cancel = true;
  });
  RenderStats stats;
  EXPECT_THROW(pixel(s, stats, {.cancel = &cancel}), RenderInterrupted);
  canceller.join();
  EXPECT_LT(ms_since(cancelled_at), 100);
  EXPECT_EQ(stats.pixels, 0u);  // the pixel did not finish
  EXPECT_GT(stats.reflection_rays, 0u);
}

TEST_F(MirrorHall, DeadlineStopsAPixelInProgressWithin100Ms) {
  RenderSettings s = settings_;
  s.aa_samples = 9;
  const auto start = Clock::now();
  RenderStats stats;
  EXPECT_THROW(pixel(s, stats, {.deadline = start + milliseconds(50)}), RenderInterrupted);
  EXPECT_GE(ms_since(start), 50);
  EXPECT_LT(ms_since(start), 150);
  EXPECT_EQ(stats.pixels, 0u);
}

TEST_F(MirrorHall, CancelFlagStopsEveryThreadOfAWholeImage) {
  std::atomic<bool> cancel{false};
  std::thread canceller([&] {
    std::this_thread::sleep_for(milliseconds(50));
    cancel = true;
  });
  const auto start = Clock::now();
  RenderStats stats;
  EXPECT_THROW(render_image(prepared_, settings_, 2, stats, {}, {.cancel = &cancel}),
               RenderInterrupted);
  canceller.join();
  EXPECT_LT(ms_since(start), 150);
}

TEST_F(MirrorHall, RayBudgetBoundsAPixelSampleAndItsValueIsFinite) {
  RenderStats stats;
  const Rgb value = pixel(settings_, stats);
  EXPECT_EQ(stats.samples, 1u);
  EXPECT_EQ(stats.ray_budget_pixels, 1u);
  const std::uint64_t rays = stats.shadow_rays + stats.reflection_rays + stats.refraction_rays;
  EXPECT_GE(rays, Tracer::kMaxRaysPerSample);
  // Past the budget, each of the at most 63 rays still due in each of the 16 open cones is
  // traced as a single path: at most 16 reflections, each with its shadow feeler.
  EXPECT_LE(rays, Tracer::kMaxRaysPerSample + 63 * 16 * 2 * 16);
  EXPECT_TRUE(is_finite(value));
  EXPECT_GT(value.r, 0);
}

TEST_F(MirrorHall, ABudgetedPixelIsTheSameTwiceAndOnAnotherThread) {
  RenderStats here, there;
  const Rgb a = pixel(settings_, here);
  Rgb b;
  std::thread([&] { b = pixel(settings_, there); }).join();
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
  EXPECT_EQ(here.ray_budget_pixels, 1u);
  EXPECT_EQ(here.reflection_rays, there.reflection_rays);
  EXPECT_EQ(here.shadow_rays, there.shadow_rays);
}

TEST_F(MirrorHall, ProbeIsCutShortInsideAPixelAndBoundsTheCostFromBelow) {
  const auto start = Clock::now();
  const CostProbe probe = probe_render_cost(prepared_, settings_, {.max_total_seconds = 0.1});
  const double elapsed_ms = ms_since(start);
  EXPECT_GE(elapsed_ms, 100);
  EXPECT_LT(elapsed_ms, 200);
  EXPECT_TRUE(probe.cut_short);
  // The probe counts its thread's CPU time, at most the wall time to the deadline.
  EXPECT_GT(probe.seconds, 0);
  EXPECT_LE(probe.seconds, elapsed_ms / 1000);
  // The time went on the pixels finished and the unfinished one.
  EXPECT_DOUBLE_EQ(probe.seconds_per_pixel_pass(), probe.seconds / double(probe.pixels + 1));
}

}  // namespace
}  // namespace tessera::test
