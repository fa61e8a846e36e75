// The lighting model against values computed by hand from eq. 4.1-4.17 and 4.24. The image is
// 65x65 so that pixel (32, 32) looks exactly along the view axis at the sphere's front point
// (0, 0, 1), whose normal is (0, 0, 1).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 65;
constexpr int kCentre = 32;

Scene sphere_scene(const Material& m) {
  Scene scene;
  scene.camera = camera_on_z();
  scene.globals.global_ambient = {0.1, 0.1, 0.1};
  scene.objects.push_back(object(Sphere{}, Affine::identity(), m));
  return scene;
}

Rgb centre_pixel(const Scene& scene) {
  return render(scene, settings(kSize, kSize)).get(kCentre, kCentre);
}

TEST(Lighting, EmissivePlusAmbientTimesGlobalAmbient) {
  Material m = black_material();
  m.emissive = {0.2, 0.0, 0.1};
  m.ambient = {0.5, 1.0, 0.0};
  const Rgb c = centre_pixel(sphere_scene(m));  // eq. 4.4 + 4.5, no lights
  EXPECT_NEAR(c.r, 0.2 + 0.05, 1e-7);
  EXPECT_NEAR(c.g, 0.1, 1e-7);
  EXPECT_NEAR(c.b, 0.1, 1e-7);
}

TEST(Lighting, LambertianPixelFacingTheLight) {
  Material m;  // ambient 0.1, diffuse 0.8
  Scene scene = sphere_scene(m);
  scene.lights.push_back(point_light({0, 0, 10}, {1, 1, 1}));
  // 0.1 * 0.1 + 0.8 * (N.L = 1)
  EXPECT_NEAR(centre_pixel(scene).g, 0.81, 1e-6);
}

TEST(Lighting, LambertianCosineAtAnAngle) {
  Material m = black_material();
  m.diffuse = {1, 1, 1};
  Scene scene = sphere_scene(m);
  // Light at 60 degrees from the normal (0,0,1) of the front point, far enough to be a direction.
  const double far = 1e6;
  scene.lights.push_back(
      point_light({far * std::sin(M_PI / 3), 0, 1 + far * std::cos(M_PI / 3)}, {1, 1, 1}));
  EXPECT_NEAR(centre_pixel(scene).r, 0.5, 1e-6);
}

TEST(Lighting, BlinnSpecularWithHalfwayVector) {
  Material m = black_material();
  m.specular = {1, 1, 1};
  m.specular_exponent = 4;
  Scene scene = sphere_scene(m);
  // Light along +x far away: L = (1,0,0), V = (0,0,-1), H = normalize(L - V) = (1,0,1)/sqrt2.
  scene.lights.push_back(point_light({1e7, 0, 1}, {1, 1, 1}));
  EXPECT_NEAR(centre_pixel(scene).r, std::pow(std::sqrt(0.5), 4), 1e-6);  // (N.H)^4 = 0.25
}

TEST(Lighting, LightAttenuationEq412) {
  Material m = black_material();
  m.diffuse = {1, 1, 1};
  Scene scene = sphere_scene(m);
  scene.lights.push_back(point_light({0, 0, 3}, {1, 1, 1}));  // distance 2 from (0,0,1)
  scene.globals.light_attenuation = {1, 0.5, 0.25};           // 1 + 1 + 1 = 3
  EXPECT_NEAR(centre_pixel(scene).r, 1.0 / 3.0, 1e-6);
  scene.globals.light_attenuation = {0.1, 0, 0};  // min(1, 10) = 1
  EXPECT_NEAR(centre_pixel(scene).r, 1.0, 1e-6);
}

TEST(Lighting, SpotlightCutoffAndExponent) {
  Material m = black_material();
  m.diffuse = {1, 1, 1};
  Scene scene = sphere_scene(m);
  Light spot = spot_light({0, 0, 10}, {1, 1, 1});
  // The spot points 30 degrees away from the lit point; cos(30)^2 = 0.75.
  spot.spot.direction = {std::sin(M_PI / 6), 0, -std::cos(M_PI / 6)};
  spot.spot.exponent = 2;
  spot.spot.cutoff_degrees = 40;
  scene.lights = {spot};
  EXPECT_NEAR(centre_pixel(scene).r, 0.75, 1e-6);
  scene.lights[0].spot.cutoff_degrees = 20;  // outside the cone
  EXPECT_EQ(centre_pixel(scene).r, 0.0);
}

TEST(Lighting, TransparencyScalesAmbientDiffuseSpecularUnlessRetained) {
  Material m;
  m.ambient = {1, 1, 1};
  m.diffuse = {0, 0, 0};
  m.transparency = 0.25;
  Scene scene = sphere_scene(m);
  scene.globals.max_recursion_depth = 0;                 // no refraction ray: the local terms alone
  EXPECT_NEAR(centre_pixel(scene).r, 0.1 * 0.75, 1e-6);  // eq. 4.6
  scene.objects[0].material.retain_ambient_color = true;
  EXPECT_NEAR(centre_pixel(scene).r, 0.1, 1e-6);
}

TEST(Lighting, BackFacesAreDarkUnlessLit) {
  Material m = black_material();
  m.diffuse = {1, 1, 1};
  Scene scene = sphere_scene(m);
  // A light inside the sphere: the front point (0,0,1) sees it from behind, N.L = -1.
  scene.lights.push_back(point_light({0, 0, 0.5}, {1, 1, 1}));
  EXPECT_EQ(centre_pixel(scene).r, 0.0);
  scene.objects[0].material.light_back_faces = true;  // |N.L| = 1
  EXPECT_NEAR(centre_pixel(scene).r, 1.0, 1e-6);
}

// A light inside the sphere on the view axis: at the front point L = V, so the halfway vector
// L - V vanishes and there is no highlight (normalizing it would give NaN). Around it, N.L and
// N.H are negative or tiny, which with non-integer exponents is where pow() gives NaN.
TEST(Lighting, HalfwayVectorVanishingAndNonIntegerExponentsStayFinite) {
  for (double exponent : {0.0, 0.5, 2.5, 1e-9, 1e6}) {
    for (bool back_faces : {false, true}) {
      SCOPED_TRACE(::testing::Message() << "exponent " << exponent << " back " << back_faces);
      Material m = black_material();
      m.specular = {1, 1, 1};
      m.specular_exponent = exponent;
      m.light_back_faces = back_faces;
      Scene scene = sphere_scene(m);
      scene.globals.global_ambient = {};
      scene.lights.push_back(point_light({0, 0, 0.5}, {1, 1, 1}));
      RenderStats stats;
      const Image image = render(scene, settings(kSize, kSize), &stats);
      EXPECT_EQ(stats.nan_samples, 0u);
      for (const float v : image.rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0);
      EXPECT_EQ(image.get(kCentre, kCentre), Rgb{});
    }
  }
}

TEST(Lighting, ShadowScaledByOccluderTransparency) {
  // A big flat box as the floor facing the camera, a small sphere between it and the light.
  Scene scene;
  scene.camera = camera_on_z();
  scene.globals.global_ambient = {0, 0, 0};
  Material floor = black_material();
  floor.diffuse = {1, 1, 1};
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, -1}) * Affine::scaling({10, 10, 1}), floor));
  Material blocker = black_material();
  blocker.transparency = 0.4;
  scene.objects.push_back(
      object(Sphere{}, Affine::translation({0, 0, 2}) * Affine::scaling({0.1, 0.1, 0.1}), blocker));
  scene.lights.push_back(point_light({0, 0, 4}, {1, 1, 1}));
  scene.globals.max_recursion_depth = 0;
  RenderSettings s = settings(kSize, kSize);
  // The centre pixel sees the blocker itself; look at the floor just beside it... instead,
  // render from an eye off-axis is more work: check the floor point straight below through
  // a camera that looks past the small sphere.
  scene.camera.eye = {0.5, 0, 5};
  scene.camera.look_at = {0.5, 0, 0};
  // Floor point (0.5, 0, 0): light at (0,0,4), feeler passes the blocker at z=2 at x = 0.25,
  // outside the sphere of radius 0.1: fully lit, N.L = 4 / sqrt(16.25).
  EXPECT_NEAR(render(scene, s).get(kCentre, kCentre).r, 4 / std::sqrt(16.25), 1e-6);
  // Move the blocker onto the feeler: the floor gets transparency 0.4 of the light.
  scene.objects[1].transform = Affine::translation({0.25, 0, 2}) * Affine::scaling({0.1, 0.1, 0.1});
  EXPECT_NEAR(render(scene, s).get(kCentre, kCentre).r, 0.4 * 4 / std::sqrt(16.25), 1e-6);
}

}  // namespace
}  // namespace tessera::test
