// Effects on demand: an effect the scene does not call for costs nothing (docs/ARCHITECTURE.md).
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Scene plain_scene() {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Sphere{}, Affine::identity(), Material{}));
  return scene;
}

RenderStats stats_of(const Scene& scene, const RenderSettings& s) {
  RenderStats stats;
  render(scene, s, &stats);
  return stats;
}

bool has_name(const EffectSet& effects, const std::string& name) {
  const auto names = effects.names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Keywords that change nothing here are reported, never silently dropped.
TEST(Effects, KeywordsWithoutEffectAreReported) {
  Scene scene = plain_scene();
  EXPECT_TRUE(PreparedScene(scene, BvhMode::Sah).unsupported().empty());
  scene.globals.adapted_shadow_computation = true;
  const PreparedScene prepared(scene, BvhMode::Sah);
  ASSERT_EQ(prepared.unsupported().size(), 1u);
  EXPECT_EQ(prepared.unsupported()[0].rfind("scene: adaptedShadowComputation changes nothing", 0),
            0u);
}

// Gloss and translucency are effects only where they would show: on a surface that reflects
// (refracts) at all.
TEST(Effects, GlossAndTranslucencyOnlyOnReflectiveAndTransparentSurfaces) {
  Scene scene = plain_scene();
  scene.objects[0].material.gloss_strength = 0.5;
  scene.objects[0].material.translucency_strength = 0.5;
  EXPECT_TRUE(PreparedScene(scene, BvhMode::Sah).effects().names().empty());
  scene.objects[0].material.reflectivity = 0.5;
  EXPECT_EQ(PreparedScene(scene, BvhMode::Sah).effects().names(),
            (std::vector<std::string>{"reflection", "gloss"}));
  scene.objects[0].material.transparency = 0.5;
  EXPECT_EQ(PreparedScene(scene, BvhMode::Sah).effects().names(),
            (std::vector<std::string>{"reflection", "refraction", "gloss", "translucency"}));
}

TEST(Effects, PlainSceneNeedsNothing) {
  const Scene scene = plain_scene();
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_TRUE(prepared.effects().names().empty());
  const RenderStats stats = stats_of(scene, settings(32, 24));
  EXPECT_EQ(stats.camera_rays, 32u * 24u);  // one sample per pixel
  EXPECT_EQ(stats.samples, stats.pixels);
  EXPECT_EQ(stats.shadow_rays, 0u);
  EXPECT_EQ(stats.reflection_rays, 0u);
  EXPECT_EQ(stats.refraction_rays, 0u);
}

TEST(Effects, LightsBringShadowRaysOnly) {
  Scene scene = plain_scene();
  scene.lights.push_back(point_light({0, 0, 10}, {1, 1, 1}));
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_TRUE(has_name(prepared.effects(), "hard_shadows"));
  EXPECT_FALSE(has_name(prepared.effects(), "light_attenuation"));
  const RenderStats stats = stats_of(scene, settings(32, 24));
  EXPECT_GT(stats.shadow_rays, 0u);
  EXPECT_EQ(stats.reflection_rays + stats.refraction_rays, 0u);
}

TEST(Effects, ReflectionAndRefractionOnlyWhenAboveTheirMinimum) {
  Scene scene = plain_scene();
  scene.objects[0].material.reflectivity = 0.005;  // below minReflectivity 0.01
  EXPECT_EQ(stats_of(scene, settings(16, 16)).reflection_rays, 0u);
  scene.objects[0].material.reflectivity = 0.5;
  EXPECT_GT(stats_of(scene, settings(16, 16)).reflection_rays, 0u);
  EXPECT_EQ(stats_of(scene, settings(16, 16)).refraction_rays, 0u);
  scene.objects[0].material.transparency = 0.5;
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_TRUE(has_name(prepared.effects(), "refraction"));
  EXPECT_GT(stats_of(scene, settings(16, 16)).refraction_rays, 0u);
}

TEST(Effects, MaxRecursionDepthZeroSpawnsNoSecondaryRays) {
  Scene scene = plain_scene();
  scene.objects[0].material.reflectivity = 0.5;
  scene.objects[0].material.transparency = 0.5;
  scene.globals.max_recursion_depth = 0;
  const RenderStats stats = stats_of(scene, settings(16, 16));
  EXPECT_EQ(stats.reflection_rays + stats.refraction_rays, 0u);
}

TEST(Effects, AntiAliasingOnlyWhenAsked) {
  const Scene scene = plain_scene();
  const PreparedScene prepared(scene, BvhMode::Sah);
  RenderSettings s = settings(10, 10);
  EXPECT_FALSE(render_effects(prepared, s).has(Effect::AntiAliasing));
  s.aa_samples = 9;
  EXPECT_TRUE(render_effects(prepared, s).has(Effect::AntiAliasing));
  // 900 samples; the pixels share those on their common corners and edges (sample_lattice.h).
  const RenderStats stats = stats_of(scene, s);
  EXPECT_EQ(stats.samples, 900u);
  EXPECT_EQ(stats.camera_rays, 21u * 21u);
}

TEST(Effects, RecursionStopsAtMaxDepth) {
  // Two facing mirrors: a camera ray between them bounces until maxRecursionDepth.
  Scene scene;
  scene.camera = camera_on_z(1);
  Material mirror = black_material();
  mirror.reflectivity = 0.9;
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, -3}) * Affine::scaling({10, 10, 1}), mirror));
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, 8}) * Affine::scaling({10, 10, 1}), mirror));
  scene.camera.eye = {0, 0, 6};
  scene.globals.max_recursion_depth = 3;
  scene.globals.min_reflectivity = 0;
  EXPECT_EQ(stats_of(scene, settings(1, 1)).reflection_rays, 3u);
  scene.globals.min_reflectivity = 0.85;  // weight 0.9 passes, 0.81 does not
  EXPECT_EQ(stats_of(scene, settings(1, 1)).reflection_rays, 1u);
}

TEST(Effects, SpotlightsAttenuationFogAreReported) {
  Scene scene = plain_scene();
  scene.lights.push_back(spot_light({0, 0, 10}, {1, 1, 1}));
  scene.globals.light_attenuation = {1, 0.1, 0};
  scene.globals.fog = Fog{1, 10, {0.5, 0.5, 0.5}};
  const PreparedScene prepared(scene, BvhMode::Sah);
  for (const char* name : {"spotlights", "light_attenuation", "fog", "hard_shadows"})
    EXPECT_TRUE(has_name(prepared.effects(), name)) << name;
}

}  // namespace
}  // namespace tessera::test
