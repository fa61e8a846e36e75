// Shadow modes (§4.2.1): none, hard, and soft shadows from a cone of shadow feelers (eq.
// 4.25-4.26), against the analytic umbra and penumbra of a ball over a floor.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr double kBallHeight = 2, kBallRadius = 0.5, kLightHeight = 6;

// A white matte floor (its top face the plane y = 0), a black ball over the origin and a
// white point light above it.
Scene ball_over_floor() {
  Scene scene;
  scene.camera.eye = {0, 8, 6};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.view_angle = 40;
  Material floor = black_material();
  floor.diffuse = {0.5, 0.5, 0.5};
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, -1, 0}) * Affine::scaling({20, 1, 20}), floor));
  scene.objects.push_back(object(Sphere{},
                                 Affine::translation({0, kBallHeight, 0}) *
                                     Affine::scaling({kBallRadius, kBallRadius, kBallRadius}),
                                 black_material()));
  scene.lights.push_back(point_light({0, kLightHeight, 0}, {1, 1, 1}));
  return scene;
}

RenderSettings with_shadows(ShadowMode mode, double jitter = 0.2) {
  RenderSettings s = settings(32, 32);
  s.shadows = mode;
  s.shadow_jitter = jitter;
  return s;
}

// The floor's value at (x, 0, 0), seen from straight above; `key` keys its random numbers.
Rgb floor_at(const PreparedScene& prepared, const RenderSettings& s, double x, std::uint32_t key) {
  return trace_ray(prepared, {{x, 1, 0}, {0, -1, 0}, 0}, s, key);
}

// Eq. 4.8 with N = (0, 1, 0): the unshadowed value at (x, 0, 0).
double lambertian_at(double x) { return 0.5 * kLightHeight / std::hypot(x, kLightHeight); }

TEST(ShadowModes, EffectSetFollowsTheMode) {
  const Scene scene = ball_over_floor();
  const PreparedScene prepared(scene, BvhMode::Sah);
  const EffectSet hard = render_effects(prepared, with_shadows(ShadowMode::Hard));
  EXPECT_TRUE(hard.has(Effect::HardShadows));
  EXPECT_FALSE(hard.has(Effect::SoftShadows));
  const EffectSet soft = render_effects(prepared, with_shadows(ShadowMode::Soft));
  EXPECT_TRUE(soft.has(Effect::SoftShadows));
  EXPECT_FALSE(soft.has(Effect::HardShadows));
  const EffectSet none = render_effects(prepared, with_shadows(ShadowMode::None));
  EXPECT_FALSE(none.has(Effect::HardShadows) || none.has(Effect::SoftShadows));
  // A cone of radius 0 is the hard feeler.
  EXPECT_TRUE(render_effects(prepared, with_shadows(ShadowMode::Soft, 0)).has(Effect::HardShadows));
  // No lights, no shadows of any kind.
  Scene dark = scene;
  dark.lights.clear();
  const PreparedScene unlit(dark, BvhMode::Sah);
  EXPECT_TRUE(render_effects(unlit, with_shadows(ShadowMode::Soft)).names().empty());
}

TEST(ShadowModes, NoneGivesTheUnshadowedLambertianValueUnderTheBall) {
  const Scene scene = ball_over_floor();
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_EQ(floor_at(prepared, with_shadows(ShadowMode::Hard), 0, 0).g, 0.0);  // in the umbra
  EXPECT_DOUBLE_EQ(floor_at(prepared, with_shadows(ShadowMode::None), 0, 0).g, 0.5);
  EXPECT_NEAR(floor_at(prepared, with_shadows(ShadowMode::None), 0.3, 0).g, lambertian_at(0.3),
              1e-12);
  RenderStats stats;
  render(scene, with_shadows(ShadowMode::None), &stats);
  EXPECT_EQ(stats.shadow_rays, 0u);
}

TEST(SoftShadows, JitterStrengthZeroEqualsHardShadowsBitForBit) {
  const Scene scene = ball_over_floor();
  EXPECT_EQ(render(scene, with_shadows(ShadowMode::Soft, 0)),
            render(scene, with_shadows(ShadowMode::Hard)));
}

TEST(SoftShadows, EachLitPointSendsAConeOfFeelers) {
  const Scene scene = ball_over_floor();
  RenderStats hard, soft;
  const Image hard_image = render(scene, with_shadows(ShadowMode::Hard), &hard);
  const Image soft_image = render(scene, with_shadows(ShadowMode::Soft), &soft);
  EXPECT_NE(hard_image, soft_image);
  EXPECT_GT(hard.shadow_rays, 0u);
  EXPECT_EQ(soft.shadow_rays, 9 * hard.shadow_rays);  // nrOfConeSamples = 9
}

// Seen from the floor point (x, 0, 0), the ball covers the directions within asin(R / d) of
// its centre; the cone's rays lie within [theta_min, theta_max] of the direction to the light
// (its rim at r_c, jittered by up to r_c * sqrt(2) / 8 across). So the point is in full shadow
// while the light's direction is more than theta_max inside the ball's disc, and fully lit
// once it is more than theta_max outside it; in between the shadow lifts. Each point's
// feelers are jittered anew, so it lifts monotonically on average over a point's samples.
TEST(SoftShadows, PenumbraLiesBetweenTheAnalyticUmbraAndPenumbraAndIsMonotone) {
  const Scene scene = ball_over_floor();
  const PreparedScene prepared(scene, BvhMode::Sah);
  const RenderSettings s = with_shadows(ShadowMode::Soft, 0.4);
  const double r_c = s.shadow_jitter / 2;
  const double theta_max = std::atan(r_c * (1 + std::sqrt(2.0) / 8));
  const double margin = 0.002;  // radians, for the rounding of the hit and the feelers
  constexpr int kSamples = 16;
  double highest_mean = 0;
  int umbra = 0, penumbra = 0, lit = 0;
  for (int i = 0; i <= 400; ++i) {
    const double x = i * 0.005;
    const double to_centre = std::atan2(x, kBallHeight);  // from the vertical
    const double to_light = std::atan2(x, kLightHeight);
    const double offset = to_centre - to_light;  // the light's direction from the ball's centre
    const double ball = std::asin(kBallRadius / std::hypot(x, kBallHeight));
    double mean = 0;
    for (int k = 0; k < kSamples; ++k) {
      const auto key = static_cast<std::uint32_t>(i * kSamples + k);
      const double factor = floor_at(prepared, s, x, key).g / lambertian_at(x);
      SCOPED_TRACE(testing::Message() << "x = " << x << ", shadow factor " << factor);
      if (offset < ball - theta_max - margin) {
        EXPECT_EQ(factor, 0.0);
      } else if (offset > ball + theta_max + margin) {
        EXPECT_NEAR(factor, 1.0, 1e-12);
      } else {
        EXPECT_GE(factor, 0.0);
        EXPECT_LE(factor, 1.0 + 1e-12);
      }
      mean += factor / kSamples;
    }
    if (offset < ball - theta_max - margin)
      ++umbra;
    else if (offset > ball + theta_max + margin)
      ++lit;
    else
      penumbra += mean > 0 && mean < 1 ? 1 : 0;
    // Generous: the mean of 16 points' cones may dip by a little under one feeler in nine.
    EXPECT_GE(mean, highest_mean - 1.0 / s.cone_samples) << "x = " << x;
    highest_mean = std::max(highest_mean, mean);
  }
  EXPECT_GT(umbra, 5);
  EXPECT_GT(penumbra, 10);
  EXPECT_GT(lit, 5);
}

}  // namespace
}  // namespace tessera::test
