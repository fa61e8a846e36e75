// Neighbouring pixels share the regular samples on their common corners and edges
// (render/sample_lattice.h): each is traced once, and every pixel's value stays what it is when
// the pixel traces all its own samples.
#include <gtest/gtest.h>

#include "common/render/sample_lattice.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

// Nothing drawn at random: a sample's value depends on its position alone.
Scene scene_without_randomness() { return sphere_and_glass_cube(0); }

RenderSettings grid_settings(int aa) {
  RenderSettings s = settings(48, 36);
  s.aa_samples = aa;
  return s;
}

// Every other pixel of every other row in `rect`: they fill a quarter of their bounds, too few
// to share samples, so each traces its own.
std::vector<PixelCoord> sparse_pixels(const PixelRect& rect) {
  std::vector<PixelCoord> pixels;
  for (int y = rect.y0; y < rect.y1; y += 2)
    for (int x = rect.x0; x < rect.x1; x += 2) pixels.push_back({x, y});
  return pixels;
}

class SharedSamples : public ::testing::TestWithParam<int> {};

TEST_P(SharedSamples, APixelSharingItsSamplesEqualsThePixelTracingItsOwnBitForBit) {
  const Scene scene = scene_without_randomness();
  const RenderSettings s = grid_settings(GetParam());
  const PreparedScene prepared(scene, s.bvh);
  const PixelRect rect{5, 3, 45, 33};
  std::vector<Rgb> shared(static_cast<std::size_t>(rect.area()));
  RenderStats shared_stats;
  render_pass(prepared, s, rect, 0, shared, shared_stats);

  const std::vector<PixelCoord> own = sparse_pixels(rect);
  std::vector<Rgb> traced(own.size());
  RenderStats own_stats;
  render_pixels(prepared, s, own, 0, traced, own_stats);
  ASSERT_EQ(own_stats.camera_rays, own.size() * static_cast<std::size_t>(s.aa_samples));
  for (std::size_t i = 0; i < own.size(); ++i) {
    const std::size_t at =
        static_cast<std::size_t>((own[i].y - rect.y0) * rect.width() + (own[i].x - rect.x0));
    ASSERT_EQ(shared[at], traced[i]) << own[i].x << "," << own[i].y;
  }
}

TEST_P(SharedSamples, EachLatticePointIsTracedOnce) {
  const Scene scene = scene_without_randomness();
  const RenderSettings s = grid_settings(GetParam());
  const PreparedScene prepared(scene, s.bvh);
  const int w = 10, h = 7;
  std::vector<Rgb> values(static_cast<std::size_t>(w * h));
  RenderStats stats;
  render_pass(prepared, s, {0, 0, w, h}, 0, values, stats);
  // 3x3: every point of the (2w + 1) x (2h + 1) half-pixel lattice; 5 points: the pixels'
  // corners and centres.
  const std::uint64_t points =
      GetParam() == 9 ? (2 * w + 1) * (2 * h + 1) : (w + 1) * (h + 1) + w * h;
  EXPECT_EQ(stats.camera_rays, points);
  EXPECT_EQ(stats.samples, static_cast<std::uint64_t>(w * h * GetParam()));
  EXPECT_EQ(stats.pixels, static_cast<std::uint64_t>(w * h));
}

// The coordinator predicts a unit's rays without tracing it (shared_unit_rays): they are the
// rays render_pixels traces, exactly for a whole rectangle and a unit of sparse anchors, and
// for the finest level's units (every pixel but the coarser anchors) up to the skipped
// anchors on the unit's border, whose outer corners and edges no traced pixel needs.
TEST_P(SharedSamples, AUnitsPredictedRaysAreTheRaysItTraces) {
  const Scene scene = scene_without_randomness();
  const RenderSettings s = grid_settings(GetParam());
  const PreparedScene prepared(scene, s.bvh);
  const auto traced = [&](const UnitPixels& unit) {
    const std::vector<PixelCoord> pixels = expand(unit);
    std::vector<Rgb> values(pixels.size());
    RenderStats stats;
    render_pixels(prepared, s, pixels, 0, values, stats);
    return static_cast<long long>(stats.camera_rays);
  };
  const PixelRect rect{4, 2, 24, 14};
  const UnitPixels whole{.rect = rect};
  EXPECT_EQ(shared_unit_rays(whole, GetParam()), traced(whole));
  const UnitPixels sparse{.rect = rect, .step = 2, .exclude = 4};
  EXPECT_EQ(shared_unit_rays(sparse, GetParam()), traced(sparse));
  EXPECT_EQ(shared_unit_rays(sparse, GetParam()), GetParam() * pixel_count(sparse));
  const UnitPixels finest{.rect = rect, .step = 1, .exclude = 2};
  const long long predicted = shared_unit_rays(finest, GetParam());
  EXPECT_LE(traced(finest), predicted);
  EXPECT_GE(traced(finest), predicted - (rect.width() + rect.height()));
}

INSTANTIATE_TEST_SUITE_P(Grids, SharedSamples, ::testing::Values(5, 9));

// Jitter moves each sample of each pixel on its own, and a random number drawn during a sample
// is keyed by its pixel: such samples are never shared.
TEST(SharedSamples, SamplesThatDrawRandomNumbersAreNotShared) {
  Scene scene = scene_without_randomness();
  const int w = 6, h = 5;
  const auto camera_rays = [&](const Scene& sc, const RenderSettings& s) {
    const PreparedScene prepared(sc, s.bvh);
    std::vector<Rgb> values(static_cast<std::size_t>(w * h));
    RenderStats stats;
    render_pass(prepared, s, {0, 0, w, h}, 0, values, stats);
    return stats.camera_rays;
  };
  RenderSettings jittered = grid_settings(9);
  jittered.stochastic = true;
  EXPECT_EQ(camera_rays(scene, jittered), 9u * w * h);

  scene.objects[0].material.surface_roughness = 0.05;  // perturbs normals at random
  EXPECT_EQ(camera_rays(scene, grid_settings(9)), 9u * w * h);
}

TEST(SharedSamples, OnlyRendersWithoutJitterOrRandomEffectsQualify) {
  RenderSettings s = grid_settings(9);
  EffectSet effects;
  effects.add(Effect::HardShadows);
  effects.add(Effect::Reflection);
  EXPECT_TRUE(samples_depend_on_position_only(effects, s));
  for (Effect random : {Effect::MotionBlur, Effect::SurfaceRoughness, Effect::Gloss,
                        Effect::Translucency, Effect::SoftShadows}) {
    EffectSet with = effects;
    with.add(random);
    EXPECT_FALSE(samples_depend_on_position_only(with, s)) << static_cast<int>(random);
  }
  s.stochastic = true;
  EXPECT_FALSE(samples_depend_on_position_only(effects, s));
}

// A plan's share: a pass after the first covers whole rectangles, so with many passes the share
// tends to theirs; the first pass's coarse levels share nothing and raise it.
TEST(SharedSamples, APlansShareWeighsItsPassesByTheirLayout) {
  PlanOptions options{.width = 64, .height = 48, .passes = 2, .unit_pixels = 256};
  const Plan first_two = make_plan(options);
  long long later_rays = 0, later_pixels = 0;
  for (const WorkUnit& unit : first_two.units)
    if (first_two.stages[static_cast<std::size_t>(unit.stage)].pass == 1) {
      later_rays += shared_unit_rays(unit.pixels, 9);
      later_pixels += unit.cost;
    }
  const double later_share =
      static_cast<double>(later_rays) / (9.0 * static_cast<double>(later_pixels));
  EXPECT_GT(later_share, 4.0 / 9);  // each unit traces its own edges
  EXPECT_LT(later_share, 5.0 / 9);
  EXPECT_GT(traced_share(first_two, 1, 9), traced_share(first_two, 2, 9));
  EXPECT_NEAR(traced_share(first_two, 100000, 9), later_share, 1e-4);
  EXPECT_EQ(traced_share(first_two, 3, 1), 1);  // one sample a pixel: nothing to share
}

}  // namespace
}  // namespace tessera::test
