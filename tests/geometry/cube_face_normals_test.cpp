// A cube instance takes its six faces' normals into world space once (Instance::face_normals);
// every hit must report what taking its own local normal through the transform gives, bit for
// bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/geometry/motion.h"

namespace tessera {
namespace {

// Translate * scale (diagonal, with zero translations and a mirroring scale), turned, sheared,
// and nearly flat.
std::vector<Affine> transforms() {
  Affine shear = Affine::identity();
  shear.m[0][1] = 0.7;
  shear.m[2][0] = -0.3;
  return {
      Affine::translation({0, -2, 0}) * Affine::scaling({8, 0.05, 4}),
      Affine::translation({1, 2, 3}) * Affine::scaling({-2, 1, 0.5}),
      Affine::translation({-3.6, 0, 0}) * *Affine::rotation(-60, {1, 0, 0}),
      Affine::translation({0.5, 0, -1}) * shear,
      Affine::scaling({1e-3, 3, 1e3}) * *Affine::rotation(33, {1, 2, 3}),
  };
}

// Hits on every face from rays aimed at the cube from all sides; the hits of `instance` against
// those of a copy that takes each hit's normal through the transform.
int compare_hits(const Instance& instance, double time, std::mt19937_64& rng) {
  Instance per_hit = instance;
  per_hit.face_normals.reset();
  std::uniform_real_distribution<double> unit(-1, 1);
  int hits = 0;
  std::uint32_t faces = 0;
  for (int i = 0; i < 6000; ++i) {
    const Vec3 from{unit(rng), unit(rng), unit(rng)};
    const Vec3 to{unit(rng) * 0.9, unit(rng) * 0.9, unit(rng) * 0.9};
    const Vec3 origin = instance.to_world.apply_point(from * (3 / length(from)));
    const Ray ray{origin, instance.to_world.apply_point(to) - origin, time};
    IntersectionCounters counters;
    WorldHit a, b;
    const bool hit_a = intersect_instance(instance, ray, kInfinity, a, counters);
    EXPECT_EQ(hit_a, intersect_instance(per_hit, ray, kInfinity, b, counters)) << i;
    if (!hit_a) continue;
    ++hits;
    faces |= 1u << a.part;
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << i;
  }
  EXPECT_EQ(faces, 0x3fu);
  return hits;
}

TEST(CubeFaceNormals, HitsReportTheirNormalsTakenThroughTheTransform) {
  std::mt19937_64 rng(17);
  for (const Affine& m : transforms()) {
    const std::optional<Instance> cube = make_instance(Cube{}, m, nullptr);
    ASSERT_TRUE(cube.has_value());
    ASSERT_TRUE(cube->face_normals.has_value());
    EXPECT_GT(compare_hits(*cube, 0, rng), 3000);
  }
}

// A cube turning during the shutter: posed at another time, its faces' normals are the pose's.
TEST(CubeFaceNormals, MovingCubesTakeTheirPosesNormals) {
  std::mt19937_64 rng(19);
  ObjectMotion motion;
  motion.angle_degrees = 70;
  motion.axis = {1, 1, 0};
  const std::optional<Instance> moving = make_moving_instance(
      Cube{}, Affine::translation({0, 0, -5}) * Affine::scaling({2, 0.5, 1}), motion, 1, nullptr);
  ASSERT_TRUE(moving.has_value());
  const std::optional<Instance> posed = instance_at(*moving, 0.5);
  ASSERT_TRUE(posed.has_value());
  EXPECT_GT(compare_hits(*posed, 0.5, rng), 3000);
  // The moving instance posed by intersect_instance itself.
  Instance per_hit = *moving;
  per_hit.face_normals.reset();
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const Ray ray{{-2 + 0.02 * i, 0.1, 0}, {0.1, -0.05, -1}, 0.5};
    IntersectionCounters counters;
    WorldHit a, b;
    const bool hit_a = intersect_instance(*moving, ray, kInfinity, a, counters);
    ASSERT_EQ(hit_a, intersect_instance(*posed, ray, kInfinity, b, counters)) << i;
    if (!hit_a) continue;
    ++hits;
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << i;
  }
  EXPECT_GT(hits, 50);
}

}  // namespace
}  // namespace tessera
