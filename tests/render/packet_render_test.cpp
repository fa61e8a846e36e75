// At one fixed sample a pixel, camera rays walk the scene BVH four at a time
// (Tracer::find_packet_hits) and each is then shaded on from its hit: every pixel must still be
// what tracing its camera ray alone gives, bit for bit, with the same statistics, whatever the
// shading does after the hit (reflections, refraction, random normals, cones of rays).
#include <gtest/gtest.h>

#include <vector>

#include "common/render/pixel_samples.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

// A reflective floor under two mirror balls that face each other (reflections of reflections),
// a glass ball, a rough mirror ball (random normals), a glossy one (cones of rays) and a matte
// box (no reflection).
Scene mirrors_on_a_floor() {
  Scene scene;
  scene.camera.eye = {0, 2.5, 7};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 1, 0};
  scene.camera.view_angle = 45;
  scene.globals.background = {0.1, 0.2, 0.3};
  const auto add = [&](ShapeGeometry shape, const Affine& transform, const Material& m) {
    scene.objects.push_back(object(shape, transform, m));
  };
  Material floor;
  floor.diffuse = {0.5, 0.5, 0.55};
  floor.reflectivity = 0.3;
  add(Cube{}, Affine::translation({0, -1, 0}) * Affine::scaling({6, 0.05, 6}), floor);
  Material mirror;
  mirror.diffuse = {0.05, 0.05, 0.05};
  mirror.specular = {0.8, 0.8, 0.8};
  mirror.specular_exponent = 60;
  mirror.reflectivity = 0.9;
  add(Sphere{}, Affine::translation({-1.3, 0, 0}), mirror);
  add(Sphere{}, Affine::translation({1.3, 0.2, -0.6}) * Affine::scaling({0.9, 0.9, 0.9}), mirror);
  Material glass;
  glass.diffuse = {0.05, 0.06, 0.05};
  glass.transparency = 0.85;
  glass.speed_of_light = 0.67;
  glass.reflectivity = 0.1;
  add(Sphere{}, Affine::translation({0.2, -0.5, 1.8}) * Affine::scaling({0.5, 0.5, 0.5}), glass);
  Material rough = mirror;
  rough.surface_roughness = 0.05;
  add(Sphere{}, Affine::translation({-2.6, -0.3, -2.5}) * Affine::scaling({0.7, 0.7, 0.7}), rough);
  Material glossy = mirror;
  glossy.gloss_strength = 0.2;
  add(Sphere{}, Affine::translation({2.7, -0.3, -2.5}) * Affine::scaling({0.7, 0.7, 0.7}), glossy);
  Material matte;
  matte.diffuse = {0.7, 0.2, 0.1};
  add(Cube{}, Affine::translation({0, -0.5, -1.8}) * Affine::scaling({0.5, 0.5, 0.5}), matte);
  scene.lights.push_back(point_light({-4, 6, 5}, {0.9, 0.9, 0.85}));
  scene.lights.push_back(point_light({4, 5, 3}, {0.4, 0.4, 0.5}));
  return scene;
}

TEST(PacketRender, PixelsEqualTheirCameraRaysTracedAlone) {
  const Scene scene = mirrors_on_a_floor();
  RenderSettings s = settings(64, 48);
  s.cone_samples = 3;
  s.seed = 7;
  const PreparedScene prepared(scene, s.bvh);
  const EffectSet effects = render_effects(prepared, s);
  ASSERT_TRUE(effects.has(Effect::Reflection));
  ASSERT_TRUE(effects.has(Effect::Gloss));
  ASSERT_TRUE(effects.has(Effect::SurfaceRoughness));

  const int pass = 1;
  std::vector<Rgb> packed(static_cast<std::size_t>(s.width * s.height));
  RenderStats packed_stats;
  render_pass(prepared, s, {0, 0, s.width, s.height}, pass, packed, packed_stats);

  // Each camera ray traced on its own, with the random numbers its pixel's sample draws.
  RenderStats alone_stats;
  Tracer tracer(prepared, s, alone_stats);
  const ImageRays camera(prepared.camera(), s.width, s.height);
  const SampleOffset centre = regular_sample_offsets(1)[0];
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      ++alone_stats.camera_rays;  // as each sample does: its ray budget starts anew
      SampleStream rng(s.seed, static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y),
                       static_cast<std::uint32_t>(pass));
      const Ray ray = camera.through(x + centre.dx, y + centre.dy);
      const Rgb alone = tracer.trace(ray, RayKind::Camera, 0, 1.0, MediumStack{}, rng);
      ASSERT_EQ(packed[static_cast<std::size_t>(y * s.width + x)], alone) << x << "," << y;
    }
  EXPECT_EQ(packed_stats.camera_rays, alone_stats.camera_rays);
  EXPECT_EQ(packed_stats.shadow_rays, alone_stats.shadow_rays);
  EXPECT_EQ(packed_stats.reflection_rays, alone_stats.reflection_rays);
  EXPECT_EQ(packed_stats.refraction_rays, alone_stats.refraction_rays);
  EXPECT_EQ(packed_stats.intersections.shape_tests, alone_stats.intersections.shape_tests);
  EXPECT_EQ(packed_stats.intersections.bvh_nodes, alone_stats.intersections.bvh_nodes);
  // Reflections of reflections happen: some camera rays spawn more than one reflected ray.
  EXPECT_GT(alone_stats.reflection_rays, alone_stats.camera_rays);
}

// The tracer keeps the packet's eye in each instance's object space; packets from another eye
// must not use the last eye's.
TEST(PacketRender, PacketsFromAnotherEyeTakeTheirOwn) {
  const Scene scene = mirrors_on_a_floor();
  RenderSettings s = settings(16, 12);
  const PreparedScene prepared(scene, s.bvh);
  RenderStats stats;
  Tracer packets(prepared, s, stats);
  Tracer alone(prepared, s, stats);
  const Vec3 eyes[] = {{0, 2.5, 7}, {0, 0.5, 4}, {0, 2.5, 7}, {1.5, 3, 6}};
  const Vec3 directions[kPacketLanes] = {unit_or_zero({0, -0.3, -1}), unit_or_zero({0.2, -0.4, -1}),
                                         unit_or_zero({-0.3, -0.2, -1}),
                                         unit_or_zero({0.1, -0.6, -1})};
  for (const Vec3& eye : eyes) {
    packets.find_packet_hits(eye, directions, kPacketLanes);
    for (int l = 0; l < kPacketLanes; ++l) {
      SampleStream a(1, 0, 0, 0), b(1, 0, 0, 0);
      EXPECT_EQ(packets.trace_packet_ray(l, MediumStack{}, a),
                alone.trace({eye, directions[l], 0}, RayKind::Camera, 0, 1.0, MediumStack{}, b))
          << eye.y << " " << l;
    }
  }
}

}  // namespace
}  // namespace tessera::test
