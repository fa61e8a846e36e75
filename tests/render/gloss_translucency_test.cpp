// Gloss and translucency by non-weighted jittered discrete cone tracing (§4.1.4, eq.
// 4.18-4.19): what they reduce to, what they cost, and values computed by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 48;

// A black mirror wall behind the origin facing the camera, and a small glowing ball between
// them, off the view axis: the wall shows the ball's reflection. `mirror` sets the wall.
Scene mirror_wall(const Material& mirror) {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, -1.1}) * Affine::scaling({10, 10, 0.1}), mirror));
  scene.objects.push_back(
      object(Sphere{}, Affine::translation({0.6, 0.3, 2}) * Affine::scaling({0.3, 0.3, 0.3}),
             glowing({1, 0.5, 0.2})));
  return scene;
}

Material mirror(double gloss) {
  Material m = black_material();
  m.reflectivity = 0.8;
  m.gloss_strength = gloss;
  return m;
}

// A pane of glass (no bending: the speed of light of air) between the camera and a glowing
// ball, which it shows through itself.
Scene glass_pane(double translucency) {
  Scene scene;
  scene.camera = camera_on_z(40);
  Material glass = black_material();
  glass.transparency = 0.8;
  glass.translucency_strength = translucency;
  glass.speed_of_light = 0.8;
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, 1.5}) * Affine::scaling({10, 10, 0.2}), glass));
  scene.objects.push_back(object(Sphere{}, Affine::scaling({0.5, 0.5, 0.5}), glowing({1, 1, 1})));
  return scene;
}

RenderSettings cones_of(int samples) {
  RenderSettings s = settings(kSize, kSize);
  s.cone_samples = samples;
  return s;
}

TEST(Gloss, StrengthZeroIsTheMirrorBitForBit) {
  const Scene sharp = mirror_wall(mirror(0));
  const PreparedScene prepared(sharp, BvhMode::Sah);
  EXPECT_FALSE(prepared.effects().has(Effect::Gloss));
  EXPECT_EQ(render(sharp, cones_of(17)), render(sharp, settings(kSize, kSize)));
}

TEST(Gloss, OneConeSampleIsNoGloss) {
  const Scene glossy = mirror_wall(mirror(0.5));
  const PreparedScene prepared(glossy, BvhMode::Sah);
  EXPECT_TRUE(prepared.effects().has(Effect::Gloss));
  EXPECT_FALSE(render_effects(prepared, cones_of(1)).has(Effect::Gloss));
  EXPECT_EQ(render(glossy, cones_of(1)), render(mirror_wall(mirror(0)), cones_of(1)));
}

TEST(Gloss, BlursTheReflectionWithAConeOfRays) {
  RenderStats sharp_stats, glossy_stats;
  const Image sharp = render(mirror_wall(mirror(0)), cones_of(9), &sharp_stats);
  const Image glossy = render(mirror_wall(mirror(0.5)), cones_of(9), &glossy_stats);
  EXPECT_NE(sharp, glossy);
  // The ball is matte: every reflected ray ends there or on the background, so each hit on
  // the wall costs one ray when sharp and a cone of nine when glossy.
  EXPECT_GT(sharp_stats.reflection_rays, 0u);
  EXPECT_EQ(glossy_stats.reflection_rays, 9 * sharp_stats.reflection_rays);
  // Blurring spreads the reflection: more pixels show some of it, the brightest shows less.
  int sharp_lit = 0, glossy_lit = 0;
  float sharp_peak = 0, glossy_peak = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = kSize / 2; x < kSize; ++x) {  // the reflection lies right of the centre
      sharp_lit += sharp.get(x, y).r > 0.01 ? 1 : 0;
      glossy_lit += glossy.get(x, y).r > 0.01 ? 1 : 0;
      sharp_peak = std::max(sharp_peak, static_cast<float>(sharp.get(x, y).r));
      glossy_peak = std::max(glossy_peak, static_cast<float>(glossy.get(x, y).r));
    }
  EXPECT_GT(glossy_lit, sharp_lit);
  EXPECT_LE(glossy_peak, sharp_peak);
}

// Inside a uniformly glowing room every ray of a cone sees the same glow: a glossy (or
// translucent) ball keeps exactly the value a mirror (or clear glass) would have.
Scene ball_in_glowing_room(const Material& ball) {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.objects.push_back(
      object(Sphere{}, Affine::scaling({50, 50, 50}), glowing({0.5, 0.5, 0.5})));
  scene.objects.push_back(object(Sphere{}, Affine::identity(), ball));
  return scene;
}

// The distance from the origin to the camera ray of pixel (x, y).
double miss_distance(const PreparedScene& prepared, int x, int y) {
  const Ray ray = prepared.camera().ray_through(x + 0.5, y + 0.5, kSize, kSize);
  return length(cross(ray.direction, ray.origin));
}

void expect_ball_and_room(const Scene& scene, double ball_value) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  RenderStats stats;
  const Image image = render_image(prepared, cones_of(9), 1, stats);
  int ball_pixels = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double d = miss_distance(prepared, x, y);
      if (d < 0.8) {  // well inside the silhouette
        EXPECT_NEAR(image.get(x, y).g, ball_value, 1e-6) << x << "," << y;
        ++ball_pixels;
      } else if (d > 1.2) {
        EXPECT_NEAR(image.get(x, y).g, 0.5, 1e-6) << x << "," << y;
      }
    }
  EXPECT_GT(ball_pixels, 50);
}

TEST(Gloss, GlossyBallInAUniformRoomKeepsTheMirrorValue) {
  expect_ball_and_room(ball_in_glowing_room(mirror(1.0)), 0.8 * 0.5);  // eq. 4.14
}

TEST(Translucency, TranslucentBallInAUniformRoomKeepsTheGlassValue) {
  Material glass = black_material();
  glass.transparency = 0.8;
  glass.translucency_strength = 1.0;  // the speed of air: no total internal reflection
  // Through two surfaces, each passing 0.8 of what lies behind it (eq. 4.17).
  expect_ball_and_room(ball_in_glowing_room(glass), 0.8 * 0.8 * 0.5);
}

TEST(Translucency, StrengthZeroIsSharpRefractionBitForBit) {
  const Scene sharp = glass_pane(0);
  EXPECT_FALSE(PreparedScene(sharp, BvhMode::Sah).effects().has(Effect::Translucency));
  EXPECT_EQ(render(sharp, cones_of(17)), render(sharp, settings(kSize, kSize)));
}

TEST(Translucency, OneConeSampleIsNoTranslucency) {
  const Scene blurred = glass_pane(0.5);
  const PreparedScene prepared(blurred, BvhMode::Sah);
  EXPECT_TRUE(prepared.effects().has(Effect::Translucency));
  EXPECT_FALSE(render_effects(prepared, cones_of(1)).has(Effect::Translucency));
  EXPECT_EQ(render(blurred, cones_of(1)), render(glass_pane(0), cones_of(1)));
}

TEST(Translucency, BlursWhatLiesBehindWithAConeOfRays) {
  RenderStats sharp_stats, blurred_stats;
  const Image sharp = render(glass_pane(0), cones_of(5), &sharp_stats);
  const Image blurred = render(glass_pane(0.5), cones_of(5), &blurred_stats);
  EXPECT_NE(sharp, blurred);
  // Entering the pane spreads a cone of five; each of those spreads five more leaving it.
  EXPECT_EQ(blurred_stats.refraction_rays, 5 * 6 * sharp_stats.refraction_rays / 2);
}

TEST(ConeTracing, SameSettingsSameBitsOnAnyNumberOfThreads) {
  // The ball's glossy reflection, its soft shadow on the wall, and a translucent post.
  Scene scene = mirror_wall(mirror(0.4));
  scene.objects[0].material.diffuse = {0.5, 0.5, 0.5};
  SceneObject post = glass_pane(0.3).objects[0];
  post.transform = Affine::translation({-0.8, 0, 1.5}) * Affine::scaling({0.4, 2, 0.2});
  scene.objects.push_back(post);
  scene.lights.push_back(point_light({1, 1, 6}, {1, 1, 1}));
  RenderSettings s = cones_of(5);  // one sample per pixel: only the cones draw numbers
  s.shadows = ShadowMode::Soft;
  s.seed = 7;
  const Image once = render(scene, s, nullptr, 1);
  EXPECT_EQ(once, render(scene, s, nullptr, 3));
  EXPECT_EQ(once, render(scene, s, nullptr, 1));
  s.seed = 8;  // the cones' jitter follows the seed
  EXPECT_NE(once, render(scene, s, nullptr, 1));
}

}  // namespace
}  // namespace tessera::test
