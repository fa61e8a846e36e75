#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::octahedron;
using testing::random_unit;
using testing::subdivided_cube;

Mesh single_triangle() {
  Mesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  testing::add_triangle(mesh, 0, 1, 2);
  return mesh;
}

TEST(Triangle, HitWithBarycentrics) {
  TriangleHit hit;
  ASSERT_TRUE(intersect_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {{0.25, 0.5, 2}, {0, 0, -1}},
                                 kInfinity, hit));
  EXPECT_EQ(hit.t, 2);
  EXPECT_DOUBLE_EQ(hit.b0, 0.25);
  EXPECT_DOUBLE_EQ(hit.b1, 0.25);
  EXPECT_DOUBLE_EQ(hit.b2, 0.5);
  // Both sides are hit; t_max is exclusive.
  ASSERT_TRUE(intersect_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {{0.25, 0.5, -2}, {0, 0, 4}},
                                 kInfinity, hit));
  EXPECT_EQ(hit.t, 0.5);
  EXPECT_FALSE(
      intersect_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {{0.25, 0.5, -2}, {0, 0, 4}}, 0.5, hit));
}

TEST(Triangle, Misses) {
  TriangleHit hit;
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_FALSE(intersect_triangle(a, b, c, {{0.6, 0.6, 2}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_FALSE(intersect_triangle(a, b, c, {{0.25, 0.25, 2}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_FALSE(
      intersect_triangle(a, b, c, {{-1, 0.25, 0}, {1, 0, 0}}, kInfinity, hit));  // in plane
  EXPECT_FALSE(intersect_triangle(a, b, c, {{0.25, 0.25, 0}, {0, 0, 1}}, kInfinity, hit));  // t = 0
  EXPECT_FALSE(intersect_triangle(a, b, c, {{0.25, 0.25, 1}, {0, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_triangle(a, b, c, {{0.25, 0.25, 1}, {0, NAN, -1}}, kInfinity, hit));
}

TEST(Triangle, DegenerateTrianglesAreNeverHit) {
  TriangleHit hit;
  const Ray ray{{0.5, 0.5, 2}, {-0.1, -0.1, -1}};
  EXPECT_FALSE(intersect_triangle({0, 0, 0}, {0, 0, 0}, {1, 1, 0}, ray, kInfinity, hit));
  EXPECT_FALSE(intersect_triangle({0, 0, 0}, {1, 1, 0}, {2, 2, 0}, ray, kInfinity, hit));
  EXPECT_FALSE(
      intersect_triangle({0.3, 0.3, 0}, {0.3, 0.3, 0}, {0.3, 0.3, 0}, ray, kInfinity, hit));
  EXPECT_FALSE(intersect_triangle({0, 0, NAN}, {1, 0, 0}, {0, 1, 0}, ray, kInfinity, hit));
}

TEST(Triangle, LocalHitPointNormalAndError) {
  const Mesh mesh = single_triangle();
  TriangleHit th;
  ASSERT_TRUE(intersect_triangle(mesh.positions[0], mesh.positions[1], mesh.positions[2],
                                 {{0.25, 0.5, 2}, {0, 0, -1}}, kInfinity, th));
  const LocalHit hit = triangle_local_hit(mesh, 0, true, th);
  EXPECT_EQ(hit.point, (Vec3{0.25, 0.5, 0}));
  EXPECT_EQ(hit.normal, (Vec3{0, 0, 1}));     // (p1 - p0) x (p2 - p0)
  EXPECT_EQ(hit.shading_normal, hit.normal);  // no vertex normals
  EXPECT_EQ(hit.part, 0u);
  EXPECT_GT(hit.point_error.x, 0);
  EXPECT_LT(max_component(hit.point_error), 1e-15);
}

TEST(Mesh, SmoothShadingInterpolatesVertexNormals) {
  const Mesh mesh = octahedron();
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  IntersectionCounters counters;
  LocalHit flat, smooth;
  // Near the +x vertex of the (+, +, +) face.
  const Ray ray{{5, 0.1, 0.1}, {-1, 0, 0}};
  ASSERT_TRUE(intersect_mesh(accel, false, ray, kInfinity, flat, counters));
  ASSERT_TRUE(intersect_mesh(accel, true, ray, kInfinity, smooth, counters));
  EXPECT_EQ(flat.t, smooth.t);
  EXPECT_NEAR(flat.t, 4.2, 1e-15);
  const Vec3 geometric = flat.normal / length(flat.normal);
  EXPECT_NEAR(geometric.x, 1 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(flat.shading_normal, flat.normal);
  // Barycentrics (0.8, 0.1, 0.1) of the axis normals.
  const Vec3 expected = Vec3{0.8, 0.1, 0.1} / std::sqrt(0.66);
  EXPECT_NEAR(smooth.shading_normal.x, expected.x, 1e-14);
  EXPECT_NEAR(smooth.shading_normal.y, expected.y, 1e-14);
  EXPECT_NEAR(smooth.shading_normal.z, expected.z, 1e-14);
}

TEST(Mesh, ShadingNormalFallsBackToTheGeometricNormal) {
  Mesh mesh = single_triangle();
  mesh.normals = {{0, 0, 1}, {0, 0, -1}, {0, 0, 1}};
  mesh.triangles[0].n = {0, 1, 2};
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  IntersectionCounters counters;
  LocalHit hit;
  // At b = (0.25, 0.5, 0.25)... the z components cancel exactly at b0 + b2 = b1.
  ASSERT_TRUE(intersect_mesh(accel, true, {{0.5, 0.25, 1}, {0, 0, -1}}, kInfinity, hit, counters));
  EXPECT_EQ(hit.shading_normal, hit.normal);
  // A corner without a normal: flat shading for the whole triangle.
  mesh.normals = {{0, 0, 1}, {1, 0, 1}};
  mesh.triangles[0].n = {0, 1, MeshTriangle::kNoNormal};
  ASSERT_TRUE(intersect_mesh(accel, true, {{0.2, 0.2, 1}, {0, 0, -1}}, kInfinity, hit, counters));
  EXPECT_EQ(hit.shading_normal, hit.normal);
}

TEST(Mesh, CountsTestsAndFindsTheNearestTriangle) {
  const Mesh mesh = subdivided_cube(4);
  for (BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const MeshAccel accel = build_mesh_accel(mesh, mode);
    EXPECT_EQ(accel.bounds.lo, (Vec3{-1, -1, -1}));
    EXPECT_EQ(accel.bounds.hi, (Vec3{1, 1, 1}));
    IntersectionCounters counters;
    LocalHit hit;
    ASSERT_TRUE(
        intersect_mesh(accel, false, {{0.1, 0.3, -5}, {0, 0, 1}}, kInfinity, hit, counters));
    EXPECT_EQ(hit.t, 4);
    EXPECT_EQ(hit.point.z, -1);
    EXPECT_LT(hit.normal.z, 0);
    EXPECT_GT(counters.triangle_tests, 0u);
    EXPECT_GT(counters.bvh_nodes, 0u);
    if (mode == BvhMode::None) {
      EXPECT_EQ(counters.triangle_tests, mesh.triangles.size());
    } else {
      EXPECT_LT(counters.triangle_tests, mesh.triangles.size() / 4);
    }
    // From inside: the exit.
    ASSERT_TRUE(intersect_mesh(accel, false, {{0.1, 0.3, 0}, {0, 0, 1}}, kInfinity, hit, counters));
    EXPECT_EQ(hit.t, 1);
    EXPECT_GT(hit.normal.z, 0);
  }
}

// intersect_mesh builds its hit from the corners in the leaf it tested (MeshAccel::leaf_quads):
// bit for bit the hit that the mesh's own positions give, in every lane of a quad, with the
// BVH and without, with normals interpolated and not.
TEST(Mesh, HitFromTheLeafCornersEqualsTheHitFromTheMesh) {
  Mesh mesh = subdivided_cube(5);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.normals.push_back(mesh.positions[i] + Vec3{0.1, 0.2, 0.3});
  for (MeshTriangle& t : mesh.triangles) t.n = t.v;
  std::mt19937_64 rng(18);
  for (BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const MeshAccel accel = build_mesh_accel(mesh, mode);
    IntersectionCounters counters;
    std::vector<bool> lane_seen(4);
    for (int i = 0; i < 2000; ++i) {
      const Ray ray{random_unit(rng) * 0.5, random_unit(rng)};
      for (const bool interpolate : {false, true}) {
        LocalHit hit;
        ASSERT_TRUE(intersect_mesh(accel, interpolate, ray, kInfinity, hit, counters));
        TriangleHit th;
        const MeshTriangle& t = mesh.triangles[hit.part];
        ASSERT_TRUE(intersect_triangle(mesh.positions[t.v[0]], mesh.positions[t.v[1]],
                                       mesh.positions[t.v[2]], ray, kInfinity, th));
        const LocalHit expected = triangle_local_hit(mesh, hit.part, interpolate, th);
        ASSERT_EQ(hit.t, expected.t);
        ASSERT_EQ(hit.point, expected.point);
        ASSERT_EQ(hit.point_error, expected.point_error);
        ASSERT_EQ(hit.normal, expected.normal);
        ASSERT_EQ(hit.shading_normal, expected.shading_normal);
      }
      LocalHit hit;
      intersect_mesh(accel, false, ray, kInfinity, hit, counters);
      const auto& order = accel.bvh.primitive_order;
      const auto position = std::find(order.begin(), order.end(), hit.part) - order.begin();
      lane_seen[static_cast<std::size_t>(position % 4)] = true;
    }
    EXPECT_TRUE(lane_seen[0] && lane_seen[1] && lane_seen[2] && lane_seen[3]);
  }
}

// Rays aimed exactly at shared edges and vertices of a closed mesh never pass through it.
void expect_watertight(const Mesh& mesh, const Vec3& centre, double radius, std::uint64_t seed) {
  SCOPED_TRACE(::testing::Message() << mesh.source << " seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  IntersectionCounters counters;
  int misses = 0, rays = 0;
  auto fire = [&](const Vec3& target) {
    // Along a line through an interior point q and the target: from q outwards, and from
    // outside inwards (a random line through an edge could merely touch the convex mesh).
    const Vec3 q = centre + random_unit(rng) * (radius * 0.1 * unit(rng));
    const Vec3 outside = target + (target - q) * (1 + 9 * unit(rng));
    for (const Vec3& o : {outside, q}) {
      LocalHit hit;
      ++rays;
      if (!intersect_mesh(accel, false, {o, target - o}, kInfinity, hit, counters)) {
        if (++misses <= 5)
          ADD_FAILURE() << "ray from (" << o.x << ", " << o.y << ", " << o.z << ") to (" << target.x
                        << ", " << target.y << ", " << target.z << ") missed";
      }
    }
  };
  for (int round = 0; round < 20; ++round) {
    for (const MeshTriangle& t : mesh.triangles) {
      for (int e = 0; e < 3; ++e) {
        const Vec3& a = mesh.positions[t.v[static_cast<std::size_t>(e)]];
        const Vec3& b = mesh.positions[t.v[static_cast<std::size_t>((e + 1) % 3)]];
        fire(a);                        // a vertex
        fire(a + (b - a) * 0.5);        // an edge's midpoint
        fire(a + (b - a) * unit(rng));  // a point on (or within an ulp of) the edge
      }
    }
  }
  EXPECT_EQ(misses, 0) << "of " << rays << " rays";
}

TEST(Mesh, WatertightThroughAnInstanceFarFromTheOrigin) {
  // The world rays are aimed at the world images of the vertices and edge points; whatever
  // object-space ray the inverse transform makes of them, the watertight test holds for it.
  const Mesh mesh = subdivided_cube(2);
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const Affine m = Affine::translation({1e6, -2e6, 1e6}) * *Affine::rotation(33, {1, 2, 3}) *
                   Affine::scaling({0.5, 2, 1});
  const std::optional<Instance> inst = make_instance(MeshShape{0, false}, m, &accel);
  ASSERT_TRUE(inst.has_value());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  IntersectionCounters counters;
  int misses = 0, rays = 0;
  for (int round = 0; round < 10; ++round) {
    for (const MeshTriangle& t : mesh.triangles) {
      for (std::size_t e = 0; e < 3; ++e) {
        const Vec3& a = mesh.positions[t.v[e]];
        const Vec3& b = mesh.positions[t.v[(e + 1) % 3]];
        for (const Vec3& local : {a, a + (b - a) * 0.5, a + (b - a) * unit(rng)}) {
          const Vec3 target = m.apply_point(local);
          const Vec3 q = m.apply_point(random_unit(rng) * (0.2 * unit(rng)));
          const Vec3 outside = target + (target - q) * (1 + 9 * unit(rng));
          for (const Vec3& o : {outside, q}) {
            WorldHit hit;
            ++rays;
            if (!intersect_instance(*inst, {o, target - o}, kInfinity, hit, counters)) ++misses;
          }
        }
      }
    }
  }
  EXPECT_EQ(misses, 0) << "of " << rays << " rays";
}

TEST(Mesh, WatertightAtEdgesAndVertices) {
  expect_watertight(octahedron(), {}, 1, 1);
  expect_watertight(subdivided_cube(3), {}, 1.8, 2);
  expect_watertight(octahedron(0.75, {1e6, -1e6, 1e6}), {1e6, -1e6, 1e6}, 0.75, 3);
  expect_watertight(subdivided_cube(3, {1e6, 1e6, -1e6}), {1e6, 1e6, -1e6}, 1.8, 4);
}

}  // namespace
}  // namespace tessera
