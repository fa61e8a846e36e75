// Moving instances (geometry/motion.h): the pose at a time, and swept bounds that hold every
// pose and every hit over the shutter, also for fast rotations and scalings.
#include "common/geometry/motion.h"
#include "common/math/portable_math.h"

#include <gtest/gtest.h>

#include <random>

namespace tessera {
namespace {

ObjectMotion fast_motion() {
  ObjectMotion m;
  m.scale = {3, 0.5, 1.5};
  m.angle_degrees = 720;  // two turns in a frame
  m.axis = {1, 2, 0.5};
  m.translation = {10, -4, 2};
  return m;
}

Affine object_transform() {
  return Affine::translation({5, 1, -2}) * *Affine::rotation(30, {0, 1, 1}) *
         Affine::scaling({2, 1, 0.5});
}

bool contains(const Bounds3& outer, const Bounds3& inner) {
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
         inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
}

TEST(Motion, AtTimeZeroThePoseIsTheTransformExactly) {
  EXPECT_EQ(transform_at(object_transform(), fast_motion(), 0), object_transform());
}

TEST(Motion, ScaleThenRotateInTheObjectFrameThenTranslateInTheWorld) {
  ObjectMotion m;
  m.scale = {4, 1, 1};
  m.angle_degrees = 90;
  m.axis = {0, 0, 1};
  m.translation = {1, 2, 3};
  const Affine ct = Affine::translation({5, 0, 0});
  // t = 1: (1, 0, 0) scaled to (4, 0, 0), turned to (0, 4, 0), placed at (5, 4, 0), moved by
  // (1, 2, 3).
  const Vec3 end = transform_at(ct, m, 1).apply_point({1, 0, 0});
  EXPECT_NEAR(end.x, 6, 1e-12);
  EXPECT_NEAR(end.y, 6, 1e-12);
  EXPECT_NEAR(end.z, 3, 1e-12);
  // t = -1/2: scale 4^-1/2 = 1/2 (geometric), -45 degrees, half the translation back.
  const Vec3 before = transform_at(ct, m, -0.5).apply_point({1, 0, 0});
  const double h = 0.5 * std::sqrt(0.5);
  EXPECT_NEAR(before.x, 5 + h - 0.5, 1e-12);
  EXPECT_NEAR(before.y, -h - 1, 1e-12);
  EXPECT_NEAR(before.z, -1.5, 1e-12);
}

// transform_at skips pow for a scale of 1 and reuses an axis's power for an equal scale; each
// axis must still get pow(its scale, time), bit for bit.
TEST(Motion, EachAxisScalesByThePowerOfItsOwnScale) {
  for (const Vec3 scale : {Vec3{1, 1, 1}, Vec3{2, 2, 2}, Vec3{1, 2, 2}, Vec3{2, 1, 2},
                           Vec3{2, 2, 1}, Vec3{2, 3, 2}, Vec3{3, 2, 2}, Vec3{2, 3, 5}}) {
    ObjectMotion m;
    m.scale = scale;
    for (const double time : {-0.5, -0.123, 0.3, 1.0}) {
      const Affine expected = Affine::scaling(
          {tessera::pow(scale.x, time), tessera::pow(scale.y, time), tessera::pow(scale.z, time)});
      EXPECT_EQ(transform_at(Affine::identity(), m, time), expected)
          << scale.x << " " << scale.y << " " << scale.z << " at " << time;
    }
  }
}

TEST(Motion, SweptBoundsHoldEveryPoseOfFastObjects) {
  std::mt19937_64 rng(20261123);  // fixed seed: a failure reproduces
  for (const ShapeGeometry& g : {ShapeGeometry{Sphere{}}, ShapeGeometry{Cube{}},
                                 ShapeGeometry{Torus{0.25, 1}}, ShapeGeometry{TaperedCylinder{}}}) {
    for (const double shutter : {0.1, 1.0, 2.5}) {
      const auto moving =
          make_moving_instance(g, object_transform(), fast_motion(), shutter, nullptr);
      ASSERT_TRUE(moving.has_value());
      std::uniform_real_distribution<double> time(-shutter / 2, shutter / 2);
      for (int i = 0; i < 2000; ++i) {
        const auto posed = instance_at(*moving, time(rng));
        ASSERT_TRUE(posed.has_value());
        ASSERT_TRUE(contains(moving->world_bounds, posed->world_bounds)) << shutter << " " << i;
      }
    }
  }
}

TEST(Motion, EveryHitOfARayAtAnyTimeLiesInTheSweptBounds) {
  const auto moving = make_moving_instance(Cube{}, object_transform(), fast_motion(), 1.0, nullptr);
  ASSERT_TRUE(moving.has_value());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target = moving->world_bounds.centroid() +
                        mul(moving->world_bounds.diagonal() * 0.5, Vec3{u(rng), u(rng), u(rng)});
    const Ray ray{{0, 0, 40}, target - Vec3{0, 0, 40}, u(rng) / 2};
    WorldHit hit;
    IntersectionCounters counters;
    if (!intersect_instance(*moving, ray, kInfinity, hit, counters)) continue;
    ++hits;
    const Bounds3& b = moving->world_bounds;
    ASSERT_TRUE(b.lo.x <= hit.point.x && hit.point.x <= b.hi.x && b.lo.y <= hit.point.y &&
                hit.point.y <= b.hi.y && b.lo.z <= hit.point.z && hit.point.z <= b.hi.z);
  }
  EXPECT_GT(hits, 300);  // the rays did find the moving cube (it fills a few % of its sweep)
}

TEST(Motion, ARayAtTimeZeroSeesTheStillPose) {
  const Instance still = *make_instance(Sphere{}, object_transform(), nullptr);
  const Instance moving =
      *make_moving_instance(Sphere{}, object_transform(), fast_motion(), 1.0, nullptr);
  const Ray ray{{0, 0, 40}, Vec3{5, 1, -2} - Vec3{0, 0, 40}, 0};
  WorldHit a, b;
  IntersectionCounters counters;
  ASSERT_TRUE(intersect_instance(still, ray, kInfinity, a, counters));
  ASSERT_TRUE(intersect_instance(moving, ray, kInfinity, b, counters));
  EXPECT_EQ(a.t, b.t);
  EXPECT_EQ(a.point, b.point);
  // Half a frame later the sphere has moved 5 units along x: the same ray misses it.
  const Ray later{ray.origin, ray.direction, 0.5};
  EXPECT_FALSE(intersect_instance(moving, later, kInfinity, b, counters));
}

}  // namespace
}  // namespace tessera
