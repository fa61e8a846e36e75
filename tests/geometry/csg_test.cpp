// Boolean objects (csg.h): entry and exit t known in closed form, nesting, the coincident-face
// rule (A - A empty, A n A and A u A equal to A) and rays leaving a boolean object's surface.
#include "common/geometry/csg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>
#include <random>

#include "common/accel/mesh_accel.h"
#include "common/math/float_error.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::random_unit;

// Instances that refer to each other: a deque keeps their addresses.
class Solids {
 public:
  const Instance& shape(const ShapeGeometry& g, const Affine& m = Affine::identity(),
                        const MeshAccel* mesh = nullptr) {
    std::optional<Instance> i = make_instance(g, m, mesh);
    EXPECT_TRUE(i.has_value());
    return add(i.value_or(Instance{}));
  }
  const Instance& csg(CsgOperation op, const Instance& left, const Instance& right) {
    return add(make_csg_instance(CsgShape{op, left.object, right.object}, left, right));
  }

 private:
  const Instance& add(Instance i) {
    i.object = static_cast<std::uint32_t>(instances_.size());
    instances_.push_back(std::move(i));
    return instances_.back();
  }
  std::deque<Instance> instances_;
};

struct Expected {
  double t;
  bool entering;
  Vec3 normal;
};

void expect_crossings(const Instance& solid, const Ray& ray, bool inside_at_origin,
                      const std::vector<Expected>& expected) {
  IntersectionCounters counters;
  const SolidCrossings got = solid_crossings(solid, ray, counters);
  EXPECT_EQ(got.inside_at_origin, inside_at_origin);
  ASSERT_EQ(got.crossings.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_NEAR(got.crossings[i].hit.t, expected[i].t, 1e-12);
    EXPECT_EQ(got.crossings[i].entering, expected[i].entering);
    EXPECT_NEAR(length(got.crossings[i].hit.normal - expected[i].normal), 0, 1e-12);
  }
}

const Vec3 kX{1, 0, 0};
const Vec3 kY{0, 1, 0};

TEST(Csg, SphereUnionSphereAlongTheAxis) {
  Solids s;
  const Instance& a = s.shape(Sphere{}, Affine::translation({-0.5, 0, 0}));
  const Instance& b = s.shape(Sphere{}, Affine::translation({0.5, 0, 0}));
  const Instance& u = s.csg(CsgOperation::Union, a, b);
  expect_crossings(u, {{-5, 0, 0}, kX, 0}, false, {{3.5, true, -kX}, {6.5, false, kX}});
  // From inside, backwards.
  expect_crossings(u, {{0.25, 0, 0}, -kX, 0}, true, {{1.75, false, -kX}});
  // Across the axis through the lens where both overlap: x = 0, |y| < sqrt(3)/2.
  const double h = std::sqrt(0.75);
  // Both enter at once; the left sphere's surface is reported.
  expect_crossings(u, {{0, -5, 0}, kY, 0}, false,
                   {{5 - h, true, {0.5, -h, 0}}, {5 + h, false, {0.5, h, 0}}});
  EXPECT_EQ(u.world_bounds.lo.x, a.world_bounds.lo.x);
  EXPECT_EQ(u.world_bounds.hi.x, b.world_bounds.hi.x);
}

TEST(Csg, SphereIntersectCube) {
  Solids s;
  const Instance& sphere = s.shape(Sphere{});
  const Instance& cube = s.shape(Cube{}, Affine::scaling({0.5, 2, 2}));
  const Instance& i = s.csg(CsgOperation::Intersection, sphere, cube);
  // Along x the cube's faces at +-0.5 are inside the sphere; along y the sphere is inside.
  expect_crossings(i, {{-5, 0, 0}, kX, 0}, false, {{4.5, true, -kX}, {5.5, false, kX}});
  expect_crossings(i, {{0, -5, 0}, kY, 0}, false, {{4, true, -kY}, {6, false, kY}});
  EXPECT_EQ(i.world_bounds.hi.x, cube.world_bounds.hi.x);
  EXPECT_EQ(i.world_bounds.hi.y, sphere.world_bounds.hi.y);
}

TEST(Csg, CubeMinusSphereHasTheHolesNormalsFlipped) {
  Solids s;
  const Instance& cube = s.shape(Cube{});
  const Instance& sphere = s.shape(Sphere{}, Affine::scaling({0.5, 0.5, 0.5}));
  const Instance& d = s.csg(CsgOperation::Difference, cube, sphere);
  // The hole's surface faces into the hole: out of the solid.
  expect_crossings(d, {{-5, 0, 0}, kX, 0}, false,
                   {{4, true, -kX}, {4.5, false, kX}, {5.5, true, -kX}, {6, false, kX}});
  // From the hole's centre: outside the solid.
  expect_crossings(d, {{0, 0, 0}, kY, 0}, false, {{0.5, true, -kY}, {1, false, kY}});
  // A sphere bigger than the cube's corners leaves nothing.
  const Instance& big = s.shape(Sphere{}, Affine::scaling({2, 2, 2}));
  expect_crossings(s.csg(CsgOperation::Difference, cube, big), {{-5, 0.3, 0.2}, kX, 0}, false, {});
  EXPECT_EQ(d.world_bounds.lo.x, cube.world_bounds.lo.x);
}

TEST(Csg, NestedTrees) {
  Solids s;
  // (cube - sphere) u torus, then intersected with a slab: the torus ring passes through the
  // hollow cube.
  const Instance& cube = s.shape(Cube{});
  const Instance& hole = s.shape(Sphere{}, Affine::scaling({0.5, 0.5, 0.5}));
  const Instance& ring = s.shape(Torus{0.25, 1});
  const Instance& hollow = s.csg(CsgOperation::Difference, cube, hole);
  const Instance& both = s.csg(CsgOperation::Union, hollow, ring);
  // Along x: cube [4, 6], hole [4.5, 5.5], torus tube [3.75, 4.25] and [5.75, 6.25].
  expect_crossings(both, {{-5, 0, 0}, kX, 0}, false,
                   {{3.75, true, -kX}, {4.5, false, kX}, {5.5, true, -kX}, {6.25, false, kX}});
  const Instance& slab = s.shape(Cube{}, Affine::scaling({0.6, 2, 2}));
  expect_crossings(s.csg(CsgOperation::Intersection, both, slab), {{-5, 0, 0}, kX, 0}, false,
                   {{4.4, true, -kX}, {4.5, false, kX}, {5.5, true, -kX}, {5.6, false, kX}});
  // A torus and a sphere: the union is entered at the tube and left at the other tube.
  const Instance& ball = s.shape(Sphere{}, Affine::scaling({0.8, 0.8, 0.8}));
  expect_crossings(s.csg(CsgOperation::Union, ring, ball), {{-5, 0, 0}, kX, 0}, false,
                   {{3.75, true, -kX}, {6.25, false, kX}});
}

TEST(Csg, TaperedCylinderAndClosedMeshChildren) {
  Solids s;
  // A cylinder of radius 0.5 along z through the cube, its caps flush with the cube's faces.
  const Instance& cube = s.shape(Cube{});
  const Instance& drill = s.shape(TaperedCylinder{1, false},
                                  Affine::translation({0, 0, -1}) * Affine::scaling({0.5, 0.5, 2}));
  const Instance& d = s.csg(CsgOperation::Difference, cube, drill);
  expect_crossings(d, {{-5, 0, 0}, kX, 0}, false,
                   {{4, true, -kX}, {4.5, false, kX}, {5.5, true, -kX}, {6, false, kX}});
  // Down the drilled hole: the flush faces cancel, nothing is hit.
  expect_crossings(d, {{0.1, 0.2, 5}, {0, 0, -1}, 0}, false, {});
  // Beside it: the cube's faces.
  expect_crossings(d, {{0.7, 0.2, 5}, {0, 0, -1}, 0}, false,
                   {{4, true, {0, 0, 1}}, {6, false, {0, 0, -1}}});

  // The octahedron |x| + |y| + |z| <= 1 as a mesh; the ray along x passes through the vertices
  // that four triangles share: one crossing each.
  const Mesh mesh = testing::octahedron();
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const Instance& octahedron = s.shape(MeshShape{0, false}, Affine::identity(), &accel);
  IntersectionCounters counters;
  const SolidCrossings alone = solid_crossings(octahedron, {{-5, 0, 0}, kX, 0}, counters);
  ASSERT_EQ(alone.crossings.size(), 2u);
  EXPECT_NEAR(alone.crossings[0].hit.t, 4, 1e-12);
  EXPECT_NEAR(alone.crossings[1].hit.t, 6, 1e-12);
  const Instance& cut = s.csg(CsgOperation::Difference, octahedron,
                              s.shape(Sphere{}, Affine::scaling({0.5, 0.5, 0.5})));
  const SolidCrossings got = solid_crossings(cut, {{-5, 0.1, 0.1}, kX, 0}, counters);
  ASSERT_EQ(got.crossings.size(), 4u);
  EXPECT_NEAR(got.crossings[0].hit.t, 4.2, 1e-12);  // |x| = 0.8 on the octahedron
  EXPECT_NEAR(got.crossings[3].hit.t, 5.8, 1e-12);
  EXPECT_NEAR(got.crossings[1].hit.t, 5 - std::sqrt(0.25 - 0.02), 1e-12);
}

// Rays from all around, aimed near the solid.
std::vector<Ray> random_rays(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.8, 0.8);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 from = random_unit(rng) * 6;
    const Vec3 target{jitter(rng), jitter(rng), jitter(rng)};
    rays.push_back({from, target - from, 0});
  }
  return rays;
}

TEST(Csg, CoincidentChildrenFollowTheTieBreakRule) {
  Solids s;
  const Affine m = Affine::translation({0.1, -0.2, 0.3}) * *Affine::rotation(25, {1, 2, 3}) *
                   Affine::scaling({0.7, 0.9, 0.6});
  for (const ShapeGeometry& g :
       {ShapeGeometry(Sphere{}), ShapeGeometry(Cube{}), ShapeGeometry(TaperedCylinder{0.4, false}),
        ShapeGeometry(Torus{0.3, 0.7})}) {
    SCOPED_TRACE(g.index());
    const Instance& a = s.shape(g, m);
    const Instance& b = s.shape(g, m);  // the same solid again
    const Instance& a_minus_a = s.csg(CsgOperation::Difference, a, b);
    const Instance& a_and_a = s.csg(CsgOperation::Intersection, a, b);
    const Instance& a_or_a = s.csg(CsgOperation::Union, a, b);
    int hits = 0;
    for (const Ray& ray : random_rays(17, 2000)) {
      IntersectionCounters counters;
      WorldHit alone, h;
      const bool hit = intersect_instance(a, ray, kInfinity, alone, counters);
      hits += hit ? 1 : 0;
      ASSERT_FALSE(intersect_instance(a_minus_a, ray, kInfinity, h, counters));
      for (const Instance* same : {&a_and_a, &a_or_a}) {
        ASSERT_EQ(intersect_instance(*same, ray, kInfinity, h, counters), hit);
        if (!hit) continue;
        // The left child's hit, bit for bit.
        EXPECT_EQ(h.t, alone.t);
        EXPECT_EQ(h.point, alone.point);
        EXPECT_EQ(h.point_error, alone.point_error);
        EXPECT_EQ(h.normal, alone.normal);
        EXPECT_EQ(h.object, a.object);
      }
    }
    EXPECT_GT(hits, 300);

    // The same solid through a transform that rounds differently: the crossings' t differ by
    // a few ulps. A - A' is still empty, A u A' is hit where A is.
    const Affine m2 = m * Affine::scaling({3, 3, 3}) * Affine::scaling({1 / 3.0, 1 / 3.0, 1 / 3.0});
    const Instance& b2 = s.shape(g, m2);
    const Instance& a_minus_b2 = s.csg(CsgOperation::Difference, a, b2);
    const Instance& a_or_b2 = s.csg(CsgOperation::Union, a, b2);
    for (const Ray& ray : random_rays(23, 2000)) {
      IntersectionCounters counters;
      WorldHit alone, h;
      const bool hit = intersect_instance(a, ray, kInfinity, alone, counters);
      ASSERT_FALSE(intersect_instance(a_minus_b2, ray, kInfinity, h, counters));
      ASSERT_EQ(intersect_instance(a_or_b2, ray, kInfinity, h, counters), hit);
    }
  }
}

TEST(Csg, RaysLeavingTheSurfaceDoNotHitItAgain) {
  Solids s;
  const Affine m = Affine::translation({3e3, -2e3, 1e3}) * Affine::scaling({40, 40, 40});
  const Instance& cube = s.shape(Cube{}, m);
  const Instance& hole = s.shape(Sphere{}, m * Affine::scaling({0.7, 0.7, 0.7}));
  const Instance& d = s.csg(CsgOperation::Difference, cube, hole);
  const Vec3 centre = m.apply_point({0, 0, 0});
  int checked = 0;
  for (const Ray& r : random_rays(5, 3000)) {
    const Ray ray{m.apply_point(r.origin), m.apply_vector(r.direction), 0};
    IntersectionCounters counters;
    WorldHit hit;
    if (!intersect_instance(d, ray, kInfinity, hit, counters)) continue;
    // Leave along the normal (out of the solid) and along its opposite (into it).
    for (const double side : {1.0, -1.0}) {
      const Vec3 direction = hit.normal * side;
      const Ray leaving{offset_ray_origin(hit.point, hit.point_error, hit.normal, direction),
                        direction, 0};
      WorldHit next;
      if (intersect_instance(d, leaving, kInfinity, next, counters)) {
        // Nothing nearer than the smallest feature: the wall between hole and face is 12 wide.
        EXPECT_GT(next.t, 1.0) << "at " << hit.point.x - centre.x;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

// A ray from outside aimed exactly at a rim, an edge or a vertex, where two surfaces of a shape
// meet, must cross the closed solid an even number of times, or a boolean object would take
// the rest of the ray for inside (a streak or speck). The tapered cylinder's wall and caps
// used to be tested apart: 3-4 % of rays at a rim and 41 % at a cone's apex crossed once.
TEST(Csg, RaysAtRimsEdgesAndVerticesCrossAClosedSolidAnEvenNumberOfTimes) {
  Solids s;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto on_circle = [&](double radius, double z) {
    const double a = 3.141592653589793 * unit(rng);
    return Vec3{radius * std::cos(a), radius * std::sin(a), z};
  };
  const Mesh cube_mesh = testing::subdivided_cube(3);
  const MeshAccel cube_accel = build_mesh_accel(cube_mesh, BvhMode::Sah);
  const Mesh octahedron_mesh = testing::octahedron();
  const MeshAccel octahedron_accel = build_mesh_accel(octahedron_mesh, BvhMode::Sah);
  const Affine m = testing::random_transform(rng);
  const Instance& cylinder = s.shape(TaperedCylinder{0.5, false}, m);
  const Instance& cone = s.shape(TaperedCylinder{0, false}, m);
  const Instance& cube = s.shape(Cube{}, m);
  const Instance& mesh_cube = s.shape(MeshShape{0, false}, m, &cube_accel);
  const Instance& octahedron = s.shape(MeshShape{0, false}, m, &octahedron_accel);
  struct Target {
    const char* name;
    const Instance& solid;
    std::function<Vec3()> point;  // in object space
  };
  const Target targets[] = {
      {"cylinder base rim", cylinder, [&] { return on_circle(1, 0); }},
      {"cylinder top rim", cylinder, [&] { return on_circle(0.5, 1); }},
      {"cone base rim", cone, [&] { return on_circle(1, 0); }},
      {"cone apex", cone,
       [] {
         return Vec3{0, 0, 1};
       }},
      {"cube edge", cube,
       [&] {
         return Vec3{1, 1, unit(rng)};
       }},
      {"cube vertex", cube,
       [] {
         return Vec3{1, -1, 1};
       }},
      {"mesh cube edge", mesh_cube,
       [&] {
         return Vec3{1, 1, unit(rng)};
       }},
      {"mesh cube inner edge", mesh_cube,
       [&] {
         return Vec3{1, 1.0 / 3, unit(rng)};
       }},
      {"octahedron vertex", octahedron,
       [] {
         return Vec3{0, 0, 1};
       }},
      {"octahedron edge", octahedron,
       [&] {
         const double x = (unit(rng) + 1) / 2;
         return Vec3{x, 1 - x, 0};
       }},
  };
  for (const Target& target : targets) {
    int odd = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 aim = m.apply_point(target.point());
      const Vec3 direction = random_unit(rng);
      IntersectionCounters counters;
      const SolidCrossings got =
          solid_crossings(target.solid, {aim - direction * 10, direction, 0}, counters);
      if (got.crossings.size() % 2 != 0 || got.inside_at_origin) ++odd;
    }
    EXPECT_EQ(odd, 0) << target.name;
  }
}

}  // namespace
}  // namespace tessera
