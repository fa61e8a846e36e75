// Builds small scenes in code for render tests, so that expectations can be computed by hand.
#pragma once

#include <gtest/gtest.h>

#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/render/tracer.h"
#include "common/scene/scene.h"

namespace tessera::test {

// A material that reflects nothing unless a test sets it: no ambient, no diffuse.
inline Material black_material() {
  Material m;
  m.ambient = {};
  m.diffuse = {};
  return m;
}

// A material that only glows: emissive `colour`, nothing else.
inline Material glowing(const Rgb& colour) {
  Material m = black_material();
  m.emissive = colour;
  return m;
}

inline SceneObject object(ShapeGeometry geometry, const Affine& transform, const Material& m) {
  return SceneObject{geometry, transform, m, {"test.sdl", 1, 1}, std::nullopt};
}

inline Light point_light(const Vec3& position, const Rgb& color) {
  Light light;
  light.position = position;
  light.color = color;
  return light;
}

inline Light spot_light(const Vec3& position, const Rgb& color) {
  Light light = point_light(position, color);
  light.is_spot = true;
  return light;
}

// The camera at (0, 0, 5) looking at the origin, y up, the given vertical field of view.
inline Camera camera_on_z(double view_angle = 30) {
  Camera c;
  c.eye = {0, 0, 5};
  c.look_at = {0, 0, 0};
  c.up = {0, 1, 0};
  c.view_angle = view_angle;
  return c;
}

inline RenderSettings settings(int width, int height) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  return s;
}

// The intensity arriving along one camera ray (unit direction), with the random numbers of
// sample 0 of pixel (key, 0) under the settings' seed.
inline Rgb trace_ray(const PreparedScene& prepared, const Ray& ray, const RenderSettings& s = {},
                     std::uint32_t key = 0) {
  RenderStats stats;
  Tracer tracer(prepared, s, stats);
  SampleStream rng(s.seed, key, 0, 0);
  return tracer.trace(ray, RayKind::Camera, 0, 1, MediumStack{}, rng);
}

inline void expect_rgb(const Rgb& got, const Rgb& expected, double tolerance = 1e-6) {
  EXPECT_NEAR(got.r, expected.r, tolerance);
  EXPECT_NEAR(got.g, expected.g, tolerance);
  EXPECT_NEAR(got.b, expected.b, tolerance);
}

inline Image render(const Scene& scene, const RenderSettings& s, RenderStats* stats = nullptr,
                    int threads = 1) {
  const PreparedScene prepared(scene, s.bvh);
  RenderStats local;
  Image image = render_image(prepared, s, threads, stats ? *stats : local);
  return image;
}

// A shiny sphere (specular, reflective, and rough when `surface_roughness` > 0) and a glass
// cube under one point light: reflection, refraction, shadows and a highlight in a few pixels.
inline Scene sphere_and_glass_cube(double surface_roughness) {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.globals.background = {0.1, 0.2, 0.3};
  Material shiny;
  shiny.specular = {0.6, 0.6, 0.6};
  shiny.specular_exponent = 20;
  shiny.reflectivity = 0.4;
  shiny.surface_roughness = surface_roughness;
  scene.objects.push_back(object(Sphere{}, Affine::translation({-0.8, 0, 0}), shiny));
  Material glass;
  glass.transparency = 0.7;
  glass.speed_of_light = 0.7;
  scene.objects.push_back(
      object(Cube{}, Affine::translation({1, 0.3, 0}) * Affine::scaling({0.6, 0.6, 0.6}), glass));
  scene.lights.push_back(point_light({3, 4, 5}, {1, 1, 1}));
  return scene;
}

}  // namespace tessera::test
