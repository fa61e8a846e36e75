#include "common/progressive/plan.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <vector>

namespace tessera {
namespace {

// How many times each pixel is traced for pass 0 by units that are accumulated.
std::vector<int> pass0_counts(const Plan& plan) {
  std::vector<int> counts(static_cast<std::size_t>(plan.width) * plan.height, 0);
  for (const WorkUnit& u : plan.units) {
    const Stage& s = plan.stages[u.stage];
    if (s.pass != 0 || s.preview_only) continue;
    for (PixelCoord p : expand(u.pixels))
      ++counts[static_cast<std::size_t>(p.y) * plan.width + p.x];
  }
  return counts;
}

TEST(LevelCount, IsCeilLog2OfTheLargerSide) {
  EXPECT_EQ(level_count(1, 1), 1);
  EXPECT_EQ(level_count(2, 2), 1);
  EXPECT_EQ(level_count(3, 2), 2);
  EXPECT_EQ(level_count(256, 256), 8);
  EXPECT_EQ(level_count(257, 10), 9);
  EXPECT_EQ(level_count(640, 480), 10);
}

TEST(Plan, EveryPixelIsTracedExactlyOnceOverTheLevels) {
  for (auto [w, h] :
       {std::pair{1, 1}, {2, 2}, {7, 5}, {64, 64}, {100, 37}, {640, 480}, {33, 129}}) {
    const Plan plan = make_plan({.width = w, .height = h});
    for (int c : pass0_counts(plan)) ASSERT_EQ(c, 1) << w << "x" << h;
    EXPECT_EQ(plan.total_cost, static_cast<long long>(w) * h);
  }
}

TEST(Plan, LevelOneIsTwoByTwoBlocks) {
  const Plan plan = make_plan({.width = 256, .height = 256});
  ASSERT_EQ(plan.levels, 8);
  const Stage& first = plan.stages[0];
  EXPECT_EQ(first.level, 1);
  EXPECT_EQ(first.block, 128);
  EXPECT_EQ(first.blocks, 4);
  EXPECT_EQ(first.traced, 4);
  std::set<std::pair<int, int>> anchors;
  for (int i = 0; i < first.unit_count; ++i)
    for (PixelCoord p : expand(plan.units[first.first_unit + i].pixels)) anchors.insert({p.x, p.y});
  EXPECT_EQ(anchors, (std::set<std::pair<int, int>>{{0, 0}, {128, 0}, {0, 128}, {128, 128}}));
}

TEST(Plan, AnchorCountsPerLevelMatchFigure511) {
  const Plan plan = make_plan({.width = 256, .height = 256});
  long long previous = 0;
  for (int l = 1; l <= plan.levels; ++l) {
    const Stage& s = plan.stages[l - 1];
    const long long side = 1LL << l;  // blocks across at level l
    EXPECT_EQ(s.block, 256 >> l);
    EXPECT_EQ(s.blocks, side * side);
    EXPECT_EQ(s.traced, side * side - previous);
    previous = side * side;
  }
}

TEST(Plan, NonPowerOfTwoSizesKeepPartialBlocks) {
  const Plan plan = make_plan({.width = 5, .height = 3});  // L = 3, sides 4, 2, 1
  ASSERT_EQ(plan.levels, 3);
  EXPECT_EQ(plan.stages[0].blocks, 2);  // 2 x 1 blocks of side 4
  EXPECT_EQ(plan.stages[0].traced, 2);
  EXPECT_EQ(plan.stages[1].blocks, 6);  // 3 x 2 of side 2
  EXPECT_EQ(plan.stages[1].traced, 4);
  EXPECT_EQ(plan.stages[2].traced, 15 - 6);
}

TEST(Plan, PassesAfterTheLevelsCoverTheWholeImage) {
  const Plan plan = make_plan({.width = 40, .height = 30, .passes = 3});
  ASSERT_EQ(plan.stages.size(), static_cast<std::size_t>(plan.levels + 2));
  for (int p = 1; p <= 2; ++p) {
    const Stage& s = plan.stages[plan.levels + p - 1];
    EXPECT_EQ(s.pass, p);
    EXPECT_EQ(s.level, 0);
    EXPECT_EQ(s.traced, 1200);
  }
  EXPECT_EQ(plan.total_cost, 3 * 1200);
}

TEST(Plan, DirectModeHasNoLevels) {
  const Plan plan = make_plan({.width = 40, .height = 30, .passes = 2, .progressive = false});
  EXPECT_EQ(plan.levels, 0);
  ASSERT_EQ(plan.stages.size(), 2u);
  for (int c : pass0_counts(plan)) ASSERT_EQ(c, 1);
}

TEST(Plan, UnitsHaveRoughlyEqualCost) {
  const Plan plan = make_plan({.width = 640, .height = 480, .unit_pixels = 1024});
  for (const WorkUnit& u : plan.units) {
    EXPECT_LE(u.cost, 2 * 1024);
    EXPECT_EQ(u.cost, pixel_count(u.pixels));
  }
  const Stage& last = plan.stages[plan.levels - 1];
  EXPECT_GT(last.unit_count, 100);
}

TEST(Plan, CentreOrderStartsInTheMiddleScanlineAtTheTopLeft) {
  const Plan centre = make_plan({.width = 512, .height = 512, .unit_pixels = 256});
  const Plan scan =
      make_plan({.width = 512, .height = 512, .order = UnitOrder::Scanline, .unit_pixels = 256});
  const Stage& s = centre.stages[centre.levels - 1];
  const PixelRect first = centre.units[s.first_unit].pixels.rect;
  const int side = first.width();
  EXPECT_LE(std::abs((first.x0 + first.x1) / 2 - 256), side);
  EXPECT_LE(std::abs((first.y0 + first.y1) / 2 - 256), side);
  const PixelRect last = centre.units[s.first_unit + s.unit_count - 1].pixels.rect;
  EXPECT_TRUE(last.x0 == 0 || last.y0 == 0 || last.x1 == 512 || last.y1 == 512);
  const Stage& t = scan.stages[scan.levels - 1];
  EXPECT_EQ(scan.units[t.first_unit].pixels.rect.x0, 0);
  EXPECT_EQ(scan.units[t.first_unit].pixels.rect.y0, 0);
  for (int i = 1; i < t.unit_count; ++i) {
    const PixelRect a = scan.units[t.first_unit + i - 1].pixels.rect;
    const PixelRect b = scan.units[t.first_unit + i].pixels.rect;
    EXPECT_TRUE(b.y0 > a.y0 || (b.y0 == a.y0 && b.x0 > a.x0));
  }
}

TEST(Plan, AreaPreviewTracesEveryBlockCentreAndCostsAboutAThirdMore) {
  const Plan plan = make_plan({.width = 256, .height = 256, .preview = PreviewMode::Area});
  for (int c : pass0_counts(plan)) ASSERT_EQ(c, 1);
  for (int l = 1; l < plan.levels; ++l) {
    const Stage& s = plan.stages[l - 1];
    EXPECT_TRUE(s.preview_only);
    EXPECT_EQ(s.traced, s.blocks);
    for (int i = 0; i < s.unit_count; ++i)
      for (PixelCoord p : expand(plan.units[s.first_unit + i].pixels)) {
        EXPECT_EQ(p.x % s.block, s.block / 2);
        EXPECT_EQ(p.y % s.block, s.block / 2);
      }
  }
  const double ratio = static_cast<double>(plan.total_cost) / (256.0 * 256.0);
  EXPECT_NEAR(ratio, 4.0 / 3.0, 0.01);
}

// A region's plan (issue 21 §4) traces pass 0 of each of its pixels once and nothing outside
// it, at the whole image's levels: its cost is the region's.
TEST(Plan, ARegionCoversItsPixelsOnly) {
  const PixelRect regions[] = {{0, 0, 640, 480},   {100, 50, 260, 170}, {333, 77, 334, 78},
                               {5, 400, 639, 403}, {0, 0, 1, 480},      {601, 17, 640, 480}};
  for (const PixelRect& r : regions)
    for (const PreviewMode preview : {PreviewMode::Anchor, PreviewMode::Area})
      for (const bool progressive : {true, false}) {
        const Plan plan = make_plan({.width = 640,
                                     .height = 480,
                                     .passes = 2,
                                     .progressive = progressive,
                                     .preview = preview,
                                     .unit_pixels = 256,
                                     .region = r});
        const std::string name = std::to_string(r.x0) + "," + std::to_string(r.y0) + "," +
                                 std::to_string(r.x1) + "," + std::to_string(r.y1);
        const std::vector<int> counts = pass0_counts(plan);
        for (int y = 0; y < 480; ++y)
          for (int x = 0; x < 640; ++x) {
            const bool inside = x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
            ASSERT_EQ(counts[static_cast<std::size_t>(y) * 640 + x], inside ? 1 : 0)
                << name << " at " << x << "," << y;
          }
        for (const WorkUnit& u : plan.units) {
          ASSERT_GT(u.cost, 0) << name;
          for (PixelCoord p : expand(u.pixels))
            ASSERT_TRUE(p.x >= r.x0 && p.x < r.x1 && p.y >= r.y0 && p.y < r.y1) << name;
        }
        if (preview == PreviewMode::Anchor) {
          EXPECT_EQ(plan.total_cost, 2LL * r.width() * r.height()) << name;
        }
        EXPECT_EQ(plan.levels, progressive ? 10 : 0);  // the whole image's
        EXPECT_EQ(plan.area, r);
      }
}

TEST(Plan, ARegionStartsAtTheFirstLevelWhoseBlocksFitIt) {
  const Plan whole = make_plan({.width = 640, .height = 480});
  EXPECT_EQ(whole.stages.front().level, 1);
  const Plan part = make_plan({.width = 640, .height = 480, .region = PixelRect{100, 50, 140, 70}});
  // 40 pixels across: blocks of 32 (level 5 of 10) are the first to fit.
  EXPECT_EQ(part.stages.front().level, 5);
  EXPECT_EQ(part.stages.front().block, 32);
  EXPECT_EQ(part.stages.front().traced, 1);  // (128, 64), its one pixel at multiples of 32
  EXPECT_EQ(part.stages.back().level, 10);
  EXPECT_THROW(make_plan({.width = 64, .height = 64, .region = PixelRect{0, 0, 65, 1}}),
               std::invalid_argument);
  EXPECT_THROW(make_plan({.width = 64, .height = 64, .region = PixelRect{3, 3, 3, 9}}),
               std::invalid_argument);
}

TEST(UnitPixels, CentresAreClampedIntoPartialBlocks) {
  UnitPixels u{.rect = {0, 0, 5, 3}, .step = 4, .pattern = PixelPattern::Centres};
  const auto pixels = expand(u);
  ASSERT_EQ(pixels.size(), 2u);
  EXPECT_EQ(pixels[0].x, 2);
  EXPECT_EQ(pixels[0].y, 2);
  EXPECT_EQ(pixels[1].x, 4);
  EXPECT_EQ(pixels[1].y, 2);
  EXPECT_EQ(block_of(pixels[1], 4).x, 4);
}

TEST(PlanNames, ParseAndPrint) {
  EXPECT_EQ(parse_unit_order("center"), UnitOrder::Centre);
  EXPECT_EQ(parse_unit_order("scanline"), UnitOrder::Scanline);
  EXPECT_THROW(parse_unit_order("spiral"), std::invalid_argument);
  EXPECT_EQ(parse_preview_mode(to_string(PreviewMode::Area)), PreviewMode::Area);
  EXPECT_THROW(make_plan({.width = 0, .height = 4}), std::invalid_argument);
}

TEST(UnitPixelsForCost, AUnitRendersInAbout20Milliseconds) {
  EXPECT_EQ(unit_pixels_for_cost(10e-6), 2000);            // 10 µs a pixel: 2000 pixels
  EXPECT_EQ(unit_pixels_for_cost(1e-3), 256);              // expensive pixels: no fewer than 256
  EXPECT_EQ(unit_pixels_for_cost(0.5e-6), 40000);          // cheap pixels still get about 20 ms...
  EXPECT_EQ(unit_pixels_for_cost(1e-9), kMostUnitPixels);  // ...up to 65,536 pixels
  EXPECT_EQ(unit_pixels_for_cost(0), 1024);                // unknown cost
}

TEST(UnitPixelsForThreads, APassKeepsTwoUnitsForEachThreadTheCoordinatorFeeds) {
  const double cheap = 0.3e-6;  // 0.3 µs a pixel pass: kMostUnitPixels a unit, 50 threads fed
  const PlanOptions small{.width = 512, .height = 512, .unit_pixels = unit_pixels_for_cost(cheap)};
  EXPECT_EQ(small.unit_pixels, kMostUnitPixels);
  EXPECT_EQ(unit_pixels_for_threads(small, 8, cheap), 512 * 512 / 16);
  EXPECT_EQ(unit_pixels_for_threads(small, 1, cheap), kMostUnitPixels);  // 4 units a pass
  EXPECT_EQ(unit_pixels_for_threads(small, 0, cheap), kMostUnitPixels);  // no thread known
  // Never smaller than the former cap, whatever the threads.
  EXPECT_EQ(unit_pixels_for_threads(small, 1000, cheap), 16384);
  // Threads beyond those the coordinator carries add no units: 2 x 50 a pass, not 2 x 128.
  const PlanOptions large{.width = 2048, .height = 2048, .unit_pixels = kMostUnitPixels};
  EXPECT_EQ(unit_pixels_for_threads(large, 128, cheap), 2048 * 2048 / 100);
  EXPECT_EQ(unit_pixels_for_threads(large, 16, cheap), kMostUnitPixels);
  // A region's pass is the region's pixels.
  const PlanOptions region{.width = 4096,
                           .height = 4096,
                           .unit_pixels = kMostUnitPixels,
                           .region = PixelRect{1024, 1024, 1536, 1536}};
  EXPECT_EQ(unit_pixels_for_threads(region, 8, cheap), 512 * 512 / 16);
  // Units sized by their cost below the former cap are left alone.
  const PlanOptions costly{.width = 512, .height = 512, .unit_pixels = 2000};
  EXPECT_EQ(unit_pixels_for_threads(costly, 64, 10e-6), 2000);
}

}  // namespace
}  // namespace tessera
