#include "common/progressive/unit_pixels.h"

#include <gtest/gtest.h>

#include <random>
#include <tuple>
#include <vector>

namespace tessera {
namespace {

// The pixels as unit_pixels.h defines them, one at a time: every block of side `step` in the
// rectangle gives its anchor (less the coarser level's) or its clamped centre.
std::vector<PixelCoord> by_definition(const UnitPixels& u) {
  std::vector<PixelCoord> out;
  const PixelRect& r = u.rect;
  if (u.step <= 0) return out;
  for (int by = first_multiple_at_or_after(r.y0, u.step); by < r.y1; by += u.step)
    for (int bx = first_multiple_at_or_after(r.x0, u.step); bx < r.x1; bx += u.step) {
      if (u.pattern == PixelPattern::Centres)
        out.push_back({std::min(bx + u.step / 2, r.x1 - 1), std::min(by + u.step / 2, r.y1 - 1)});
      else if (u.exclude <= 0 || bx % u.exclude != 0 || by % u.exclude != 0)
        out.push_back({bx, by});
    }
  return out;
}

TEST(UnitPixels, RunsVisitThePixelsOfTheDefinitionInOrder) {
  std::mt19937 rng(7);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  for (int trial = 0; trial < 20000; ++trial) {
    UnitPixels u;
    u.step = uniform(1, 9);
    // Rectangles aligned to the step, as the plan makes them, or clipped anywhere.
    const int x0 = uniform(0, 40), y0 = uniform(0, 40);
    u.rect = {x0, y0, x0 + uniform(0, 40), y0 + uniform(0, 40)};
    u.exclude = trial % 3 == 0 ? 0 : u.step * uniform(1, 4);
    if (trial % 7 == 0) u.exclude = uniform(1, 12);  // not a multiple of the step
    u.pattern = trial % 4 == 0 ? PixelPattern::Centres : PixelPattern::Anchors;

    std::vector<PixelCoord> visited;
    long long runs_pixels = 0;
    for_each_run(u, [&](PixelCoord first, int count, int stride) {
      ASSERT_GT(count, 0);
      // Twice the step where the coarser level's anchors are every other one (make_plan's).
      const bool every_other =
          u.pattern == PixelPattern::Anchors && u.exclude == 2 * u.step && first.y % u.exclude == 0;
      EXPECT_EQ(stride, every_other ? 2 * u.step : u.step);
      runs_pixels += count;
      for (int i = 0; i < count; ++i) visited.push_back({first.x + i * stride, first.y});
    });
    const std::vector<PixelCoord> expected = by_definition(u);
    ASSERT_EQ(visited, expected) << "step " << u.step << " exclude " << u.exclude << " rect "
                                 << u.rect.x0 << "," << u.rect.y0 << "-" << u.rect.x1 << ","
                                 << u.rect.y1
                                 << (u.pattern == PixelPattern::Centres ? " centres" : "");
    EXPECT_EQ(expand(u), expected);
    EXPECT_EQ(pixel_count(u), static_cast<long long>(expected.size()));
    EXPECT_EQ(runs_pixels, static_cast<long long>(expected.size()));
  }
}

TEST(UnitPixels, APassRowIsOneRun) {
  const UnitPixels u{.rect = {3, 5, 131, 9}, .step = 1};
  int runs = 0;
  for_each_run(u, [&](PixelCoord first, int count, int) {
    EXPECT_EQ(first.x, 3);
    EXPECT_EQ(count, 128);
    ++runs;
  });
  EXPECT_EQ(runs, 4);
}

TEST(UnitPixels, ALevelRowWithoutTheCoarserAnchorsIsOneRun) {
  // The finest level of a plan: its rows at even y leave out the even columns (level above's).
  const UnitPixels u{.rect = {0, 0, 128, 4}, .step = 1, .exclude = 2};
  std::vector<std::tuple<int, int, int, int>> runs;
  for_each_run(u, [&](PixelCoord first, int count, int stride) {
    runs.emplace_back(first.x, first.y, count, stride);
  });
  const std::vector<std::tuple<int, int, int, int>> expected = {
      {1, 0, 64, 2}, {0, 1, 128, 1}, {1, 2, 64, 2}, {0, 3, 128, 1}};
  EXPECT_EQ(runs, expected);
}

}  // namespace
}  // namespace tessera
