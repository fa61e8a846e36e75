// Predicting a render's time: the probe's pixels and the estimator's arithmetic.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <set>
#include <thread>

#include "common/render/time_prediction.h"
#include "common/stats/thread_cpu_clock.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

TEST(TimePrediction, ScalesTheProbeCostToTheJobAndItsThreads) {
  // 2 µs a pixel pass, 640x480 at 4 passes, on 3 threads: 2e-6 * 1228800 / 3 = 0.8192 s.
  EXPECT_DOUBLE_EQ(*predict_render_seconds(2e-6, 640LL * 480 * 4, 3), 0.8192);
  EXPECT_FALSE(predict_render_seconds(2e-6, 1000, 0).has_value());  // no workers yet
  const CostProbe probe{.pixels = 200, .seconds = 0.01};
  EXPECT_DOUBLE_EQ(probe.seconds_per_pixel_pass(), 5e-5);
  EXPECT_EQ(CostProbe{}.seconds_per_pixel_pass(), 0);
}

TEST(TimePrediction, ProbePixelsAreDistinctAndEveryPrefixSpreadsOverTheImage) {
  const std::vector<PixelCoord> order = probe_pixel_order(640, 480, 256);
  ASSERT_EQ(order.size(), 256u);
  std::set<std::pair<int, int>> distinct;
  for (const PixelCoord& p : order) {
    EXPECT_TRUE(p.x >= 0 && p.x < 640 && p.y >= 0 && p.y < 480);
    distinct.insert({p.x, p.y});
  }
  EXPECT_EQ(distinct.size(), 256u);
  // The first 16 pixels already reach all four quadrants.
  std::set<int> quadrants;
  for (int k = 0; k < 16; ++k) quadrants.insert((order[k].x >= 320) + 2 * (order[k].y >= 240));
  EXPECT_EQ(quadrants.size(), 4u);
}

TEST(TimePrediction, ProbeStopsAtItsTimeBudget) {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Sphere{}, Affine::identity(), Material{}));
  const PreparedScene prepared(scene, BvhMode::Sah);
  const RenderSettings s = settings(64, 48);
  EXPECT_EQ(probe_render_cost(prepared, s, {.max_pixels = 64, .max_seconds = 10}).pixels, 64);
  EXPECT_EQ(probe_render_cost(prepared, s, {.max_pixels = 64, .max_seconds = 0}).pixels, 1);
}

TEST(TimePrediction, TheProbesClockCountsWorkNotTimeOffTheCpu) {
  // The probe times itself by ThreadCpuClock, so that time its thread spends preempted on a
  // shared machine does not count: here, a sleep stands for it.
  const auto asleep = ThreadCpuClock::now();
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_LT(ThreadCpuClock::now() - asleep, std::chrono::milliseconds(10));

  const auto working = ThreadCpuClock::now();
  volatile double sink = 0;
  while (ThreadCpuClock::now() - working < std::chrono::milliseconds(5)) sink = sink + 1;
  EXPECT_GT(sink, 0);  // the loop ended, so the clock advanced while the thread worked
}

}  // namespace
}  // namespace tessera::test
