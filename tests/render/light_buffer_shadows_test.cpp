// Hard shadows through the light buffer (common/render/light_buffer.h): feelers that skip the
// BVH walk still find every blocker, their own object's included where it can block them.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

RenderSettings hard_shadows() {
  RenderSettings s = settings(8, 8);
  s.shadows = ShadowMode::Hard;
  return s;
}

// A white matte material: diffuse 0.5, nothing else.
const Material kMatte = [] {
  Material m = black_material();
  m.diffuse = {0.5, 0.5, 0.5};
  return m;
}();

// What the ray's hard shadow feelers cost: the intersection counts of a trace with them less
// those of one without; `value` is the green intensity it returns with them.
IntersectionCounters feeler_work(const PreparedScene& prepared, const Ray& ray, double& value) {
  const auto counts = [&](ShadowMode mode, double& g) {
    RenderSettings s = hard_shadows();
    s.shadows = mode;
    RenderStats stats;
    Tracer tracer(prepared, s, stats);
    SampleStream rng(s.seed, 0, 0, 0);
    g = tracer.trace(ray, RayKind::Camera, 0, 1, MediumStack{}, rng).g;
    return stats.intersections;
  };
  double unshadowed = 0;
  const IntersectionCounters with = counts(ShadowMode::Hard, value);
  const IntersectionCounters without = counts(ShadowMode::None, unshadowed);
  return {with.shape_tests - without.shape_tests, with.triangle_tests - without.triangle_tests,
          with.bvh_nodes - without.bvh_nodes};
}

// A torus in the XY plane (R = 1, r = 0.4) lit from (-5, 0, 0): seen from its centre along +x,
// the inner side of the tube at (0.6, 0, 0) faces the light, but the far side of the tube
// stands between. The feeler leaves its own surface outward, yet where the surface is not the
// convex hull's the torus itself blocks it.
TEST(LightBufferShadows, TheInnerSideOfATorusIsShadowedByItself) {
  Scene scene;
  scene.camera = camera_on_z();
  scene.objects.push_back(object(Torus{0.4, 1}, Affine::identity(), kMatte));
  scene.lights.push_back(point_light({-5, 0, 0}, {1, 1, 1}));
  const PreparedScene prepared(scene, BvhMode::Sah);
  ASSERT_NE(prepared.light_buffer(0), nullptr);
  const Ray inward{{0, 0, 0}, {1, 0, 0}, 0};
  EXPECT_EQ(trace_ray(prepared, inward, hard_shadows()).g, 0.0);
  RenderSettings unshadowed = hard_shadows();
  unshadowed.shadows = ShadowMode::None;
  EXPECT_NEAR(trace_ray(prepared, inward, unshadowed).g, 0.5, 1e-9);
  // The outer side at (-1.4, 0, 0), seen from -x, faces the light with nothing between.
  EXPECT_NEAR(trace_ray(prepared, {{-3, 0, 0}, {1, 0, 0}, 0}, hard_shadows()).g, 0.5, 1e-9);
}

// Which instances a feeler leaving them outward may skip, decided once per instance: closed
// convex solids anywhere, a torus where rho^2 exceeds R^2, nothing else.
TEST(LightBufferShadows, OwnHullsByShape) {
  Scene scene;
  scene.camera = camera_on_z();
  TaperedCylinder open;
  open.top_cap = false;
  for (const ShapeGeometry& shape :
       {ShapeGeometry{Sphere{}}, ShapeGeometry{Cube{}}, ShapeGeometry{TaperedCylinder{}},
        ShapeGeometry{open}, ShapeGeometry{Torus{0.4, 2}}})
    scene.objects.push_back(object(shape, Affine::identity(), kMatte));
  const PreparedScene prepared(scene, BvhMode::Sah);
  for (std::uint32_t k = 0; k < 3; ++k)
    EXPECT_EQ(prepared.own_hull(k).kind, OwnHull::Kind::Convex) << k;
  EXPECT_EQ(prepared.own_hull(3).kind, OwnHull::Kind::None);
  EXPECT_EQ(prepared.own_hull(4).kind, OwnHull::Kind::TorusOuterHalf);
  EXPECT_EQ(prepared.own_hull(4).torus_radius_squared, 4.0);
}

// A feeler that leaves a sphere, a cube or a torus's outer half outward, towards a light with
// nothing else near, tests no shape at all: its own object is its only candidate, and skipped.
TEST(LightBufferShadows, AFeelerLeavingItsOwnHullTestsNothing) {
  const ShapeGeometry shapes[] = {Sphere{}, Cube{}, Torus{0.4, 1}};
  for (const ShapeGeometry& shape : shapes) {
    Scene scene;
    scene.camera = camera_on_z();
    scene.objects.push_back(object(shape, Affine::identity(), kMatte));
    scene.lights.push_back(point_light({-5, 0.5, 0.1}, {1, 1, 1}));
    const PreparedScene prepared(scene, BvhMode::Sah);
    ASSERT_NE(prepared.light_buffer(0), nullptr);
    double value = 0;
    EXPECT_EQ(feeler_work(prepared, {{-3, 0, 0}, {1, 0, 0}, 0}, value).shape_tests, 0u)
        << shape.index();
    EXPECT_GT(value, 0.0);
  }
}

// Transparent slabs between a floor and the light straight above it: one or two are each
// tested alone (the buffer's candidates; the floor, 0.01 below the feeler's origin in its
// direction, is not one), three make the feeler walk the BVH. The factor is their product
// either way, and the walk's without a BVH.
TEST(LightBufferShadows, TransparentBlockersMultiply) {
  const double transparencies[] = {0.5, 0.25, 0.75};
  for (int slabs = 0; slabs <= 3; ++slabs) {
    Scene scene;
    scene.camera = camera_on_z();
    scene.globals.shadow_feeler_epsilon = 0.01;
    scene.objects.push_back(
        object(Cube{}, Affine::translation({0, -1, 0}) * Affine::scaling({5, 1, 5}), kMatte));
    double expected = 0.5;
    for (int k = 0; k < slabs; ++k) {
      Material glass = black_material();
      glass.transparency = transparencies[k];
      scene.objects.push_back(object(
          Cube{}, Affine::translation({0, 1.0 + k, 0}) * Affine::scaling({1, 0.1, 1}), glass));
      expected *= transparencies[k];
    }
    scene.lights.push_back(point_light({0, 6, 0}, {1, 1, 1}));
    const PreparedScene prepared(scene, BvhMode::Sah);
    const PreparedScene walked(scene, BvhMode::None);  // no BVH, no buffer
    ASSERT_NE(prepared.light_buffer(0), nullptr);
    ASSERT_EQ(walked.light_buffer(0), nullptr);
    const Ray down{{0, 0.5, 0}, {0, -1, 0}, 0};
    double got = 0;
    const std::uint64_t feeler_nodes = feeler_work(prepared, down, got).bvh_nodes;
    EXPECT_EQ(got, expected) << slabs << " slabs";
    EXPECT_EQ(got, trace_ray(walked, down, hard_shadows()).g) << slabs << " slabs";
    EXPECT_EQ(feeler_nodes == 0, slabs < 3) << slabs << " slabs: " << feeler_nodes;
  }
}

// A torus (R = 1, r = 0.4) under three transparent slabs, lit from straight above its tube at
// (1, 0, 0). A floor point below the tube is in its shadow: the feeler passes through a ball in
// the tube and is settled as blocked, with no shape tested. The tube's top lies nearer the light
// than the far side of that ball, behind more candidates than the cell holds: its feeler walks
// and is lit through the slabs. Both as a render without a BVH has them.

TEST(LightBufferShadows, AnInscribedBallBlocksOnlyFeelersFromBeyondIt) {
  Scene scene;
  scene.camera = camera_on_z();
  scene.objects.push_back(object(Torus{0.4, 1}, Affine::identity(), kMatte));
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 0, -2}) * Affine::scaling({5, 5, 0.1}), kMatte));
  const double transparencies[] = {0.5, 0.25, 0.75};
  for (int k = 0; k < 3; ++k) {
    Material glass = black_material();
    glass.transparency = transparencies[k];
    scene.objects.push_back(object(
        Cube{}, Affine::translation({0, 0, 3.0 + 2 * k}) * Affine::scaling({3, 3, 0.05}), glass));
  }
  scene.lights.push_back(point_light({1, 0, 10}, {1, 1, 1}));
  const PreparedScene prepared(scene, BvhMode::Sah);
  const PreparedScene walked(scene, BvhMode::None);
  ASSERT_NE(prepared.light_buffer(0), nullptr);
  const Ray floor{{1, 0, -1}, {0, 0, -1}, 0}, top{{1, 0, 2}, {0, 0, -1}, 0};
  double floor_value = 0, top_value = 0;
  EXPECT_EQ(feeler_work(prepared, floor, floor_value).shape_tests, 0u);
  EXPECT_EQ(floor_value, 0.0);
  EXPECT_EQ(floor_value, trace_ray(walked, floor, hard_shadows()).g);
  EXPECT_GT(feeler_work(prepared, top, top_value).shape_tests, 0u);
  EXPECT_NEAR(top_value, 0.5 * 0.5 * 0.25 * 0.75, 1e-12);
  EXPECT_EQ(top_value, trace_ray(walked, top, hard_shadows()).g);
}

}  // namespace
}  // namespace tessera::test
