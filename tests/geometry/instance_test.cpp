#include "common/geometry/instance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::random_unit;

Affine skewed_transform() {
  // Non-uniform scale, then a rotation, then a translation.
  return Affine::translation({1, -2, 3}) * *Affine::rotation(30, {1, 1, 0}) *
         Affine::scaling({2, 0.5, 3});
}

Instance instance_of(const ShapeGeometry& g, const Affine& m, const MeshAccel* mesh = nullptr) {
  std::optional<Instance> i = make_instance(g, m, mesh);
  EXPECT_TRUE(i.has_value());
  return i.value_or(Instance{});
}

TEST(Instance, RefusesSingularAndNonFiniteTransforms) {
  EXPECT_FALSE(make_instance(Sphere{}, Affine::scaling({1, 0, 1}), nullptr).has_value());
  Affine nan;
  nan.m[0][3] = NAN;
  EXPECT_FALSE(make_instance(Sphere{}, nan, nullptr).has_value());
  Affine inf;
  inf.m[2][2] = INFINITY;
  EXPECT_FALSE(make_instance(Cube{}, inf, nullptr).has_value());
  const std::optional<Instance> ok = make_instance(Cube{}, skewed_transform(), nullptr);
  ASSERT_TRUE(ok.has_value());
  const Affine round_trip = ok->to_world * ok->to_object;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(round_trip.m[r][c], r == c ? 1 : 0, 1e-14);
}

TEST(Instance, WorldBoundsHoldTheShape) {
  const Affine m = skewed_transform();
  const Instance inst = instance_of(Sphere{}, m);
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = m.apply_point(random_unit(rng));
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], inst.world_bounds.lo[a]);
      EXPECT_LE(p[a], inst.world_bounds.hi[a]);
    }
  }
  // Not much larger than the transformed unit box.
  const Bounds3 exact = Bounds3{{-1, -1, -1}, {1, 1, 1}}.transformed(m);
  EXPECT_NEAR(inst.world_bounds.lo.x, exact.lo.x, 1e-13);
  EXPECT_NEAR(inst.world_bounds.hi.z, exact.hi.z, 1e-13);
  // An empty mesh has empty bounds.
  const Mesh empty;
  const MeshAccel accel = build_mesh_accel(empty, BvhMode::Sah);
  EXPECT_TRUE(instance_of(MeshShape{}, m, &accel).world_bounds.empty());
}

TEST(Instance, IdentityMatchesTheLocalRoutine) {
  const Instance inst = instance_of(Sphere{}, Affine::identity());
  IntersectionCounters counters;
  WorldHit hit;
  ASSERT_TRUE(intersect_instance(inst, {{0, 0, -5}, {0, 0, 1}}, kInfinity, hit, counters));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{0, 0, -1}));
  EXPECT_EQ(hit.normal, (Vec3{0, 0, -1}));
  EXPECT_EQ(hit.object_point, (Vec3{0, 0, -1}));
  EXPECT_EQ(counters.shape_tests, 1u);
  EXPECT_FALSE(intersect_instance(inst, {{0, 0, -5}, {0, 0, 1}}, 4, hit, counters));
  EXPECT_EQ(counters.shape_tests, 2u);
}

TEST(Instance, TranslatedScaledSphereExactRoot) {
  const Instance inst =
      instance_of(Sphere{}, Affine::translation({10, 0, 0}) * Affine::scaling({2, 2, 2}));
  IntersectionCounters counters;
  WorldHit hit;
  // t is measured in the world direction's units, whatever its length.
  ASSERT_TRUE(intersect_instance(inst, {{10, 0, -5}, {0, 0, 0.5}}, kInfinity, hit, counters));
  EXPECT_EQ(hit.t, 6);
  EXPECT_EQ(hit.point, (Vec3{10, 0, -2}));
  EXPECT_EQ(hit.normal, (Vec3{0, 0, -1}));
  EXPECT_EQ(hit.object_point, (Vec3{0, 0, -1}));
}

// The hit lies on the transformed surface, the normal is perpendicular to the transformed
// tangents and points outward, and t is consistent with the world ray.
TEST(Instance, TransformedShapesHitPointsAndNormals) {
  const Affine m = skewed_transform();
  const Vec3 centre = m.apply_point({0, 0, 0.5});
  std::mt19937_64 rng(11);
  const ShapeGeometry shapes[] = {Sphere{}, Cube{}, TaperedCylinder{0.5, false},
                                  TaperedCylinder{1, false}};
  for (const ShapeGeometry& g : shapes) {
    SCOPED_TRACE(g.index());
    const Instance inst = instance_of(g, m);
    IntersectionCounters counters;
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
      const Vec3 o = centre + random_unit(rng) * 20;
      const Vec3 d = (centre + random_unit(rng) * 1.5 - o) * 0.37;
      WorldHit hit;
      if (!intersect_instance(inst, {o, d}, kInfinity, hit, counters)) continue;
      ++hits;
      const Vec3 on_ray = o + d * hit.t;
      EXPECT_LT(length(on_ray - hit.point), 1e-12);
      EXPECT_NEAR(length(hit.normal), 1, 1e-15);
      EXPECT_NEAR(length(hit.shading_normal), 1, 1e-15);
      EXPECT_LT(dot(hit.normal, d), 0);  // entering from outside
      const Vec3 local = m.inverse()->apply_point(hit.point);
      EXPECT_LT(length(local - hit.object_point), 1e-13);
      // Object-space tangents of the analytic surface at the hit.
      Vec3 t1, t2;
      const Vec3 p = hit.object_point;
      if (std::holds_alternative<Sphere>(g)) {
        EXPECT_NEAR(length(p), 1, 1e-15);
        t1 = cross(p, Vec3{0.3, 0.5, 0.7});
        t2 = cross(p, t1);
      } else if (std::holds_alternative<Cube>(g)) {
        EXPECT_EQ(max_component(abs(p)), 1);
        const int axis = static_cast<int>(hit.part / 2);
        t1 = Vec3{};
        t2 = Vec3{};
        t1[(axis + 1) % 3] = 1;
        t2[(axis + 2) % 3] = 1;
      } else {
        const double k = std::get<TaperedCylinder>(g).top_radius - 1;
        if (hit.part == 0) {
          EXPECT_NEAR(std::hypot(p.x, p.y), 1 + k * p.z, 1e-15);
          t1 = Vec3{-p.y, p.x, 0};
          t2 = Vec3{p.x * k, p.y * k, 1 + k * p.z};  // along the generatrix
        } else {
          EXPECT_EQ(p.z, hit.part == 1 ? 0 : 1);
          t1 = {1, 0, 0};
          t2 = {0, 1, 0};
        }
      }
      const Vec3 w1 = normalize_or(m.apply_vector(t1), {}),
                 w2 = normalize_or(m.apply_vector(t2), {});
      EXPECT_NEAR(dot(hit.normal, w1), 0, 1e-14);
      EXPECT_NEAR(dot(hit.normal, w2), 0, 1e-14);
    }
    EXPECT_GT(hits, 50);
    EXPECT_EQ(counters.shape_tests, 500u);
  }
}

TEST(Instance, EllipsoidNormalIsTheAnalyticGradient) {
  // x^2 / 4 + y^2 / 0.25 + z^2 / 9 = 1 around c: the gradient is (x / 4, y / 0.25, z / 9).
  const Vec3 c{5, -7, 11};
  const Instance inst =
      instance_of(Sphere{}, Affine::translation(c) * Affine::scaling({2, 0.5, 3}));
  std::mt19937_64 rng(13);
  IntersectionCounters counters;
  for (int i = 0; i < 300; ++i) {
    const Vec3 o = c + random_unit(rng) * 10;
    WorldHit hit;
    ASSERT_TRUE(
        intersect_instance(inst, {o, c + random_unit(rng) * 0.4 - o}, kInfinity, hit, counters));
    const Vec3 p = hit.point - c;
    EXPECT_NEAR(p.x * p.x / 4 + p.y * p.y / 0.25 + p.z * p.z / 9, 1, 1e-14);
    const Vec3 expected = normalize_or({p.x / 4, p.y / 0.25, p.z / 9}, {});
    EXPECT_NEAR(hit.normal.x, expected.x, 1e-14);
    EXPECT_NEAR(hit.normal.y, expected.y, 1e-14);
    EXPECT_NEAR(hit.normal.z, expected.z, 1e-14);
  }
}

TEST(Instance, MeshCountsTrianglesAndNodes) {
  const Mesh mesh = testing::subdivided_cube(4);
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const Instance inst = instance_of(MeshShape{0, false}, Affine::translation({0, 0, 10}), &accel);
  IntersectionCounters counters;
  WorldHit hit;
  ASSERT_TRUE(intersect_instance(inst, {{0.1, 0.2, 0}, {0, 0, 1}}, kInfinity, hit, counters));
  EXPECT_EQ(hit.t, 9);
  EXPECT_EQ(hit.normal, (Vec3{0, 0, -1}));
  EXPECT_EQ(counters.shape_tests, 1u);
  EXPECT_GT(counters.triangle_tests, 0u);
  EXPECT_GT(counters.bvh_nodes, 0u);
  // No accel: no hit, no crash.
  const Instance bare = instance_of(MeshShape{0, false}, Affine::identity(), nullptr);
  EXPECT_FALSE(intersect_instance(bare, {{0.1, 0.2, -5}, {0, 0, 1}}, kInfinity, hit, counters));
}

TEST(Instance, ErrorBoundIsRelativeAndSmall) {
  // Far from the origin and tiny: the bound scales with the coordinates, not a fixed epsilon.
  for (double offset : {0.0, 1e3, 1e8}) {
    for (double scale : {1e-4, 1.0, 1e4}) {
      SCOPED_TRACE(::testing::Message() << offset << " " << scale);
      const Instance inst = instance_of(Sphere{}, Affine::translation({offset, -offset, offset}) *
                                                      Affine::scaling({scale, scale, scale}));
      const Vec3 c{offset, -offset, offset};
      IntersectionCounters counters;
      WorldHit hit;
      ASSERT_TRUE(intersect_instance(inst, {c + Vec3{0.1, 0.2, -5} * scale, {0, 0, scale}},
                                     kInfinity, hit, counters));
      const double magnitude = max_component(abs(hit.point));
      EXPECT_GT(max_component(hit.point_error), 0);
      EXPECT_LT(max_component(hit.point_error), 1e-13 * magnitude);
      // The point is on the sphere to within its bound.
      EXPECT_LE(std::fabs(length(hit.point - c) - scale), 3 * max_component(hit.point_error));
    }
  }
}

}  // namespace
}  // namespace tessera
