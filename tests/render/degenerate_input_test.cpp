// Degenerate input gives a clear error or a defined image, never a crash or silent NaN: the
// camera at the limits of its parameters, singular and non-finite transforms, non-finite
// material values in scenes built in code (the loader refuses them, tests/loaders/*).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Scene lit_sphere() {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.globals.background = {0.1, 0.1, 0.3};
  Material m;
  m.diffuse = {0.8, 0.3, 0.2};
  m.specular = {0.5, 0.5, 0.5};
  m.specular_exponent = 2.5;
  scene.objects.push_back(object(Sphere{}, Affine::identity(), m));
  scene.lights.push_back(point_light({3, 4, 5}, {1, 1, 1}));
  return scene;
}

bool all_finite(const Image& image) {
  for (const float v : image.rgb)
    if (!std::isfinite(v)) return false;
  return true;
}

// The loader accepts upDirection 0 1e-200 0 (its direction is clear); the renderer must too,
// although its squared length underflows. It is the same camera as up = (0, 1, 0).
TEST(DegenerateInput, TinyUpDirectionIsADirection) {
  const RenderSettings s = settings(32, 24);
  Scene tiny = lit_sphere();
  tiny.camera.up = {0, 1e-200, 0};
  Scene huge = lit_sphere();
  huge.camera.up = {0, 1e300, 0};
  const Image expected = render(lit_sphere(), s);
  EXPECT_EQ(render(tiny, s).rgb, expected.rgb);
  EXPECT_EQ(render(huge, s).rgb, expected.rgb);
}

// eyePoint and viewPoint 2e308 apart: their difference overflows, their direction does not.
TEST(DegenerateInput, EyeAndViewPointAtTheEndsOfTheDoubles) {
  Scene scene = lit_sphere();
  scene.camera.eye = {0, 0, 1e308};
  scene.camera.look_at = {0, 0, -1e308};
  RenderStats stats;
  const Image image = render(scene, settings(16, 12), &stats);
  EXPECT_TRUE(all_finite(image));
  EXPECT_EQ(stats.nan_samples, 0u);
}

TEST(DegenerateInput, UpParallelToTheViewOrCoincidentEyeIsAnError) {
  Scene parallel = lit_sphere();
  parallel.camera.up = {0, 0, -3};
  EXPECT_THROW(PreparedScene(parallel, BvhMode::Sah), SceneError);
  Scene nearly = lit_sphere();
  nearly.camera.up = {0, 1e-12, 1};
  EXPECT_THROW(PreparedScene(nearly, BvhMode::Sah), SceneError);
  Scene zero = lit_sphere();
  zero.camera.up = {};
  EXPECT_THROW(PreparedScene(zero, BvhMode::Sah), SceneError);
  Scene nan_up = lit_sphere();
  nan_up.camera.up = {std::nan(""), 1, 0};
  EXPECT_THROW(PreparedScene(nan_up, BvhMode::Sah), SceneError);
  Scene same = lit_sphere();
  same.camera.look_at = same.camera.eye;
  EXPECT_THROW(PreparedScene(same, BvhMode::Sah), SceneError);
  Scene nan_eye = lit_sphere();
  nan_eye.camera.eye.x = std::numeric_limits<double>::infinity();
  EXPECT_THROW(PreparedScene(nan_eye, BvhMode::Sah), SceneError);
}

// viewAngle just above 0 sees one point, just below 180 nearly a half-space: both are
// defined images. 0, 180 and beyond are errors (the loader reports them located,
// SdlGlobals.RangeErrors).
TEST(DegenerateInput, ViewAnglesNearZeroAndNearAHundredAndEighty) {
  for (double angle : {1e-300, 1e-9, 179.999999, std::nextafter(180.0, 0.0)}) {
    SCOPED_TRACE(angle);
    Scene scene = lit_sphere();
    scene.camera.view_angle = angle;
    RenderStats stats;
    const Image image = render(scene, settings(16, 12), &stats);
    EXPECT_TRUE(all_finite(image));
    EXPECT_EQ(stats.nan_samples, 0u);
    if (angle < 1) {
      // Every pixel looks at the sphere's centre point.
      const Rgb centre = image.get(8, 6);
      EXPECT_GT(centre.r, 0.1);
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) ASSERT_NEAR(image.get(x, y).r, centre.r, 1e-6);
    }
  }
  for (double angle : {0.0, 180.0, -5.0, std::nan("")}) {
    Scene scene = lit_sphere();
    scene.camera.view_angle = angle;
    EXPECT_THROW(PreparedScene(scene, BvhMode::Sah), SceneError) << angle;
  }
}

TEST(DegenerateInput, ZeroScaleAndNonFiniteTransformsAreLocatedErrors) {
  for (const Affine& t :
       {Affine::scaling({1, 0, 1}), Affine::scaling({1e-200, 1e-200, 1e-200}),
        Affine::translation({std::nan(""), 0, 0}), Affine::scaling({1e308, 1e308, 1e308})}) {
    Scene scene = lit_sphere();
    scene.objects[0].transform = t;
    scene.objects[0].where = {"scene.sdl", 7, 3};
    try {
      PreparedScene prepared(scene, BvhMode::Sah);
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.where().line, 7);
      EXPECT_EQ(e.where().column, 3);
    }
  }
}

// A NaN in a material built in code (the loader cannot make one) is counted, reported and
// written as black: never a NaN pixel.
TEST(DegenerateInput, NonFiniteMaterialsAreCountedNotWritten) {
  Scene scene = lit_sphere();
  scene.objects[0].material.diffuse.g = std::nan("");
  RenderStats stats;
  const Image image = render(scene, settings(16, 12), &stats);
  EXPECT_TRUE(all_finite(image));
  EXPECT_GT(stats.nan_samples, 0u);
  EXPECT_EQ(image.get(8, 6), Rgb{});
}

}  // namespace
}  // namespace tessera::test
