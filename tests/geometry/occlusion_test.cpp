// Shadow feelers' any-hit query (occluded_instance, instance.h) against the nearest-hit one
// (intersect_instance) on the same rays: the same yes or no, and the same blocking object, for
// every kind of shape, a mesh large enough for its BVH to have depth, a boolean object and a
// moving instance. Rays come from around each shape and from points on its surface (as a
// feeler does), with limits that cut some hits off.
#include <gtest/gtest.h>

#include <deque>
#include <limits>
#include <random>

#include "common/accel/mesh_accel.h"
#include "common/geometry/csg.h"
#include "common/geometry/instance.h"
#include "common/geometry/motion.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::random_unit;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Affine placement() {
  return Affine::translation({3, -1, 2}) * *Affine::rotation(35, {1, 2, 0.5}) *
         Affine::scaling({1.5, 0.7, 1.2});
}

struct Tally {
  int hits = 0;
  int misses = 0;
};

// One ray both ways; counts its answer.
void expect_same_answer(const Instance& instance, const Ray& ray, double t_max, Tally& tally) {
  IntersectionCounters counters;
  WorldHit nearest;
  const bool hit = intersect_instance(instance, ray, t_max, nearest, counters);
  std::uint32_t object = ~0u;
  const bool occluded = occluded_instance(instance, ray, t_max, object, counters);
  ASSERT_EQ(occluded, hit) << "t_max " << t_max << ", nearest t " << nearest.t;
  if (hit) {
    EXPECT_EQ(object, nearest.object);
    ++tally.hits;
  } else {
    ++tally.misses;
  }
}

// Rays from a box around the object-space unit cube towards points in it, or anywhere; and from
// the hits they find, in every direction. Each with no limit and with a limit short of the hit.
Tally compare_on_rays(const Instance& instance, const Affine& to_world, std::uint64_t seed,
                      double time = 0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> around(-2.5, 2.5), inside(-1, 1), unit(0, 1);
  Tally tally;
  for (int i = 0; i < 400; ++i) {
    const Vec3 origin = to_world.apply_point({around(rng), around(rng), around(rng)});
    const Vec3 target = to_world.apply_point({inside(rng), inside(rng), inside(rng)});
    const Vec3 direction = unit(rng) < 0.8 ? target - origin : random_unit(rng);
    const Ray ray{origin, direction, time};
    expect_same_answer(instance, ray, kInfinity, tally);
    IntersectionCounters counters;
    WorldHit hit;
    if (!intersect_instance(instance, ray, kInfinity, hit, counters)) continue;
    expect_same_answer(instance, ray, hit.t * (0.5 + unit(rng)), tally);
    // A feeler from the surface, either way; its own surface is within t of the rounding.
    const Ray feeler{hit.point, random_unit(rng), time};
    expect_same_answer(instance, feeler, kInfinity, tally);
    expect_same_answer(instance, feeler, 1e-6 + unit(rng), tally);
  }
  return tally;
}

void expect_agreement(const Instance& instance, std::uint64_t seed, double time = 0) {
  const Tally tally = compare_on_rays(instance, placement(), seed, time);
  // Both answers occur often enough for the comparison to mean something.
  EXPECT_GT(tally.hits, 100);
  EXPECT_GT(tally.misses, 100);
}

Instance placed(const ShapeGeometry& geometry, const MeshAccel* mesh = nullptr) {
  return make_instance(geometry, placement(), mesh).value();
}

TEST(Occlusion, QuadricsAndTheCubeAnswerAsTheNearestHitDoes) {
  expect_agreement(placed(Sphere{}), 1);
  expect_agreement(placed(Cube{}), 2);
  expect_agreement(placed(TaperedCylinder{0.3}), 3);
  TaperedCylinder open_tube;
  open_tube.base_cap = open_tube.top_cap = false;
  expect_agreement(placed(open_tube), 4);
}

TEST(Occlusion, QuarticsAnswerAsTheNearestHitDoes) {
  expect_agreement(placed(Torus{0.4, 1}), 5);
  expect_agreement(placed(Torus{1, 0.6}), 6);  // a spindle torus
  expect_agreement(placed(AlgebraicSurface{AlgebraicKind::ToothCube, {4, 4, 4}}), 7);
  expect_agreement(placed(AlgebraicSurface{AlgebraicKind::OneSheetHyperboloid, {3, 3, 3}}), 8);
}

TEST(Occlusion, MeshesAnswerAsTheNearestHitDoes) {
  const Mesh octahedron = testing::octahedron();
  const MeshAccel octahedron_accel = build_mesh_accel(octahedron, BvhMode::Sah);
  expect_agreement(placed(MeshShape{}, &octahedron_accel), 9);
  // 1,200 triangles: a tree of several levels, and rays through shared edges and corners.
  const Mesh cube = testing::subdivided_cube(10);
  for (const BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const MeshAccel cube_accel = build_mesh_accel(cube, mode);
    expect_agreement(placed(MeshShape{}, &cube_accel), 10);
  }
}

TEST(Occlusion, ABooleanObjectNamesTheChildItsNearestHitBelongsTo) {
  std::deque<Instance> parts;
  const auto add = [&](Instance instance) -> const Instance& {
    instance.object = static_cast<std::uint32_t>(parts.size());
    return parts.emplace_back(std::move(instance));
  };
  const Instance& cube = add(placed(Cube{}));
  const Instance& ball = add(
      make_instance(Sphere{}, placement() * Affine::translation({0.8, 0.3, 0}), nullptr).value());
  const Instance& difference = add(
      make_csg_instance(CsgShape{CsgOperation::Difference, cube.object, ball.object}, cube, ball));
  expect_agreement(difference, 11);
}

TEST(Occlusion, AMovingInstanceIsPosedAtTheRaysTime) {
  ObjectMotion motion;
  motion.translation = {0.5, 0, 0};
  motion.angle_degrees = 30;
  const Instance moving = make_moving_instance(Sphere{}, placement(), motion, 1, nullptr).value();
  expect_agreement(moving, 12, 0.25);
  expect_agreement(moving, 13, -0.5);
}

}  // namespace
}  // namespace tessera
