// Rays leave surfaces from origins offset by a bound on the hit point's rounding error, not by
// a fixed epsilon: the same scene translated far away and scaled down renders the same, with
// no acne (docs/ARCHITECTURE.md, "Numerical robustness"; issue 2, item 7).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/loaders/sdl_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Scene acne_prone_scene() {
  Scene scene;
  scene.camera.eye = {0.3, 2.5, 6};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.view_angle = 40;
  scene.globals.background = {0.1, 0.1, 0.2};
  Material floor;
  floor.diffuse = {0.7, 0.7, 0.7};
  floor.reflectivity = 0.3;
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, -2, 0}) * Affine::scaling({6, 1, 6}), floor));
  Material ball;
  ball.diffuse = {0.8, 0.2, 0.2};
  ball.specular = {0.5, 0.5, 0.5};
  ball.specular_exponent = 30;
  scene.objects.push_back(object(Sphere{}, Affine::identity(), ball));
  Material glass;
  glass.transparency = 0.8;
  glass.speed_of_light = 0.67;
  glass.diffuse = {0.1, 0.1, 0.1};
  // The base stands 0.01 above the floor: coincident surfaces are the stability suite's case.
  scene.objects.push_back(object(
      TaperedCylinder{0.5, false},
      Affine::translation({1.8, -0.99, 0.5}) * Affine::rotation(-90, {1, 0, 0}).value(), glass));
  // A light grazing the floor makes shadow feelers nearly tangent: acne shows there first.
  scene.lights.push_back(point_light({-8, 0.5, 3}, {1, 1, 1}));
  scene.lights.push_back(point_light({2, 6, 4}, {0.6, 0.6, 0.6}));
  return scene;
}

// Tori, whose hits come from a quartic: a ring torus lying on a reflective floor and a horn
// torus standing up, lit by a light grazing the floor.
Scene torus_scene() {
  Scene scene;
  scene.camera.eye = {0.5, 3, 6};
  scene.camera.look_at = {0, -0.5, 0};
  scene.camera.view_angle = 40;
  scene.globals.background = {0.1, 0.1, 0.2};
  Material floor;
  floor.diffuse = {0.7, 0.7, 0.7};
  floor.reflectivity = 0.3;
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, -2, 0}) * Affine::scaling({6, 1, 6}), floor));
  Material ring;
  ring.diffuse = {0.8, 0.4, 0.2};
  ring.specular = {0.5, 0.5, 0.5};
  ring.specular_exponent = 30;
  scene.objects.push_back(
      object(Torus{0.4, 1.2},
             Affine::translation({-1, -0.6, 0}) * Affine::rotation(-90, {1, 0, 0}).value(), ring));
  scene.objects.push_back(object(Torus{0.7, 0.7}, Affine::translation({1.6, -0.3, -0.5}), ring));
  scene.lights.push_back(point_light({-8, -0.5, 3}, {1, 1, 1}));
  scene.lights.push_back(point_light({2, 6, 4}, {0.6, 0.6, 0.6}));
  return scene;
}

// The scene moved by p -> scale * p + offset: objects, lights and camera alike.
Scene moved(Scene scene, double scale, const Vec3& offset) {
  const Affine t = Affine::translation(offset) * Affine::scaling({scale, scale, scale});
  for (SceneObject& o : scene.objects) o.transform = t * o.transform;
  for (Light& l : scene.lights) l.position = t.apply_point(l.position);
  scene.camera.eye = t.apply_point(scene.camera.eye);
  scene.camera.look_at = t.apply_point(scene.camera.look_at);
  // Light attenuation and fog are distance-based: none here.
  return scene;
}

TEST(Robustness, TranslatedAndScaledSceneMatchesTheOriginal) {
  const RenderSettings s = settings(160, 120);
  const Image original = render(acne_prone_scene(), s);
  const Image far_small = render(moved(acne_prone_scene(), 1e-3, {1e5, -1e5, 1e5}), s);
  int differing = 0;
  double worst = 0;
  for (std::size_t i = 0; i < original.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(far_small.rgb[i]));
    const double d = std::fabs(double(original.rgb[i]) - far_small.rgb[i]);
    worst = std::max(worst, d);
    differing += d > 1e-3 ? 1 : 0;
  }
  // Pixels may differ only where a ray passes within rounding distance of an edge.
  EXPECT_LE(differing, 3) << "worst difference " << worst;
}

TEST(Robustness, TorusSceneTranslatedAndScaledMatchesTheOriginal) {
  const RenderSettings s = settings(160, 120);
  const Image original = render(torus_scene(), s);
  const Image far_small = render(moved(torus_scene(), 1e-3, {1e5, -1e5, 1e5}), s);
  int differing = 0;
  double worst = 0;
  for (std::size_t i = 0; i < original.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(original.rgb[i]) && std::isfinite(far_small.rgb[i]));
    const double d = std::fabs(double(original.rgb[i]) - far_small.rgb[i]);
    worst = std::max(worst, d);
    differing += d > 1e-3 ? 1 : 0;
  }
  EXPECT_LE(differing, 3) << "worst difference " << worst;
}

// Acne shows as pixels much darker than all their neighbours on a smooth lit surface.
int speckles(const Image& image) {
  int count = 0;
  for (int y = 1; y < image.height - 1; ++y)
    for (int x = 1; x < image.width - 1; ++x) {
      const double c = image.get(x, y).r;
      double lowest_neighbour = 1e9;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx || dy) lowest_neighbour = std::min(lowest_neighbour, image.get(x + dx, y + dy).r);
      count += c < lowest_neighbour - 0.2 ? 1 : 0;
    }
  return count;
}

TEST(Robustness, NoIsolatedDarkPixelsOnALitSphere) {
  EXPECT_EQ(speckles(render(moved(acne_prone_scene(), 1e-3, {1e5, -1e5, 1e5}), settings(160, 120))),
            0);
}

TEST(Robustness, NoIsolatedDarkPixelsOnLitTori) {
  EXPECT_EQ(speckles(render(moved(torus_scene(), 1e-3, {1e5, -1e5, 1e5}), settings(160, 120))), 0);
}

// The sample scene of hard cases a million units away (scenes/features/stability_far.sdl)
// renders as it does moved back to the origin, without speckles.
TEST(Robustness, FarSampleSceneMatchesItselfAtTheOrigin) {
  const Scene far = load_sdl_file(std::filesystem::path(TESSERA_SOURCE_DIR) /
                                  "scenes/features/stability_far.sdl");
  const RenderSettings s = settings(160, 120);
  RenderStats stats;
  const Image image = render(far, s, &stats);
  const Image at_origin = render(moved(far, 1, {-1e6, -1e6, 1e6}), s);
  EXPECT_EQ(stats.nan_samples, 0u);
  int differing = 0;
  double worst = 0;
  for (std::size_t i = 0; i < image.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(image.rgb[i]) && std::isfinite(at_origin.rgb[i]));
    const double d = std::fabs(double(image.rgb[i]) - at_origin.rgb[i]);
    worst = std::max(worst, d);
    differing += d > 1e-3 ? 1 : 0;
  }
  EXPECT_LE(differing, 3) << "worst difference " << worst;
  EXPECT_EQ(speckles(image), 0);
}

}  // namespace
}  // namespace tessera::test
