// A diagonal instance (translate * scale) applies its transforms without the off-diagonal terms
// (math/diagonal_affine.h); everything it reports must be what the full products give.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/geometry/motion.h"

namespace tessera {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSubnormal = std::numeric_limits<double>::denorm_min() * 5;

template <typename T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// The same bits, or NaN in both: the sign and payload of a NaN that arithmetic makes depend on
// the order in which the compiler puts the operands, which differs even between two inlined
// copies of the same full product (a point at infinity gave NaN here and -NaN there).
bool same_values(const Vec3& a, const Vec3& b) {
  const auto same = [](double x, double y) {
    return std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y));
  };
  return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
}

// The instance and a copy that takes the full products.
struct Pair {
  Instance diagonal;
  Instance full;
};

Pair pair_of(const ShapeGeometry& geometry, const Affine& to_world) {
  std::optional<Instance> made = make_instance(geometry, to_world, nullptr);
  EXPECT_TRUE(made.has_value());
  Pair pair{made.value_or(Instance{}), made.value_or(Instance{})};
  EXPECT_TRUE(pair.diagonal.diagonal.has_value());
  pair.full.diagonal.reset();
  return pair;
}

const std::vector<double> kSpecial = {0.0,         -0.0,   1.0,   -1.0, kSubnormal,
                                      -kSubnormal, 1e-300, 1e300, kInf, -kInf};

double component(std::mt19937_64& rng, double spread) {
  std::uniform_int_distribution<int> pick(0, 2 * static_cast<int>(kSpecial.size()));
  const int i = pick(rng);
  if (i < static_cast<int>(kSpecial.size())) return kSpecial[i];
  return std::uniform_real_distribution<double>(-spread, spread)(rng);
}

Vec3 vector(std::mt19937_64& rng, double spread) {
  return {component(rng, spread), component(rng, spread), component(rng, spread)};
}

// Translations with zero components (the demo's floor, `translate 0 -1 0`) make zero object
// coordinates for world points on those planes, such as a camera at x = 0.
const std::vector<Affine> kTransforms = {
    Affine::translation({0, -1, 0}) * Affine::scaling({8, 0.05, 8}),
    Affine::translation({-1.8, 0.2, -0.5}) * Affine::scaling({1.2, 1.2, 1.2}),
    Affine::translation({1e8, 0, -1e8}) * Affine::scaling({1e-4, 1e4, -3}),
    Affine::scaling({-2, 1, 0.5}) * *Affine::rotation(180, {0, 1, 0}),
};

TEST(DiagonalInstance, ObjectRaysAreTheFullProducts) {
  std::mt19937_64 rng(7);
  for (const Affine& m : kTransforms) {
    const Pair pair = pair_of(Sphere{}, m);
    for (int i = 0; i < 20000; ++i) {
      const Ray world{vector(rng, 10), vector(rng, 1), 0};
      const Ray a = object_ray(pair.diagonal, world);
      const Ray b = object_ray(pair.full, world);
      ASSERT_TRUE(same_values(a.origin, b.origin) && same_values(a.direction, b.direction)) << i;
    }
  }
}

TEST(DiagonalInstance, WorldHitsAreTheFullOnes) {
  std::mt19937_64 rng(11);
  for (const Affine& m : kTransforms) {
    const Pair pair = pair_of(Sphere{}, m);
    for (int i = 0; i < 20000; ++i) {
      LocalHit local;
      local.t = 1;
      local.point = vector(rng, 2);
      local.point_error = abs(vector(rng, 1e-15));
      local.normal = vector(rng, 1);
      // Mostly the geometric normal again, as every shape but smooth meshes reports.
      local.shading_normal = i % 4 == 0 ? vector(rng, 1) : local.normal;
      WorldHit a, b;
      to_world_hit(pair.diagonal, local, a);
      to_world_hit(pair.full, local, b);
      ASSERT_TRUE(same_values(a.point, b.point)) << i;
      ASSERT_TRUE(same_values(a.point_error, b.point_error)) << i;
      ASSERT_TRUE(same_values(a.normal, b.normal)) << i;
      ASSERT_TRUE(same_values(a.shading_normal, b.shading_normal)) << i;
    }
  }
}

// Whole intersections, for each shape that has its own routine: rays from the planes of the
// translations' zeros and along the axes, where object coordinates and normals are zeros.
TEST(DiagonalInstance, IntersectionsAreTheFullOnes) {
  std::mt19937_64 rng(3);
  const ShapeGeometry shapes[] = {Sphere{}, Cube{}, TaperedCylinder{0.5}};
  for (const ShapeGeometry& shape : shapes) {
    for (const Affine& m : kTransforms) {
      const Pair pair = pair_of(shape, m);
      const Vec3 centre = m.apply_point({0, 0, 0});
      int hits = 0;
      for (int i = 0; i < 5000; ++i) {
        const Vec3 origin{i % 3 == 0 ? 0.0 : centre.x + component(rng, 20),
                          centre.y + component(rng, 20), i % 5 == 0 ? -0.0 : centre.z + 30};
        const Vec3 target = centre + Vec3{component(rng, 2), component(rng, 2), 0};
        const Ray ray{origin, target - origin, 0};
        IntersectionCounters counters;
        WorldHit a, b;
        const bool hit_a = intersect_instance(pair.diagonal, ray, kInfinity, a, counters);
        const bool hit_b = intersect_instance(pair.full, ray, kInfinity, b, counters);
        ASSERT_EQ(hit_a, hit_b) << i;
        if (!hit_a) continue;
        ++hits;
        ASSERT_TRUE(same_bits(a, b)) << i;
      }
      EXPECT_GT(hits, 100);
    }
  }
}

// A diagonal instance that turns during the shutter is no longer diagonal when posed: its hits
// are those of the instance made at that pose.
TEST(DiagonalInstance, TurningInstancesAreClassifiedWhenPosed) {
  const Affine start = Affine::translation({0, 0, -5}) * Affine::scaling({2, 0.5, 1});
  ObjectMotion motion;
  motion.angle_degrees = 40;
  motion.axis = {0, 1, 0};
  const std::optional<Instance> moving = make_moving_instance(Cube{}, start, motion, 1, nullptr);
  ASSERT_TRUE(moving.has_value());
  ASSERT_TRUE(moving->diagonal.has_value());
  const double time = 0.5;
  const std::optional<Instance> posed =
      make_instance(Cube{}, transform_at(start, motion, time), nullptr);
  ASSERT_TRUE(posed.has_value());
  EXPECT_FALSE(posed->diagonal.has_value());
  for (int i = 0; i < 50; ++i) {
    const Ray ray{{-1.2 + 0.05 * i, 0.1, 0}, {0, 0, -1}, time};
    IntersectionCounters counters;
    WorldHit a, b;
    const bool hit_a = intersect_instance(*moving, ray, kInfinity, a, counters);
    ASSERT_EQ(hit_a, intersect_instance(*posed, ray, kInfinity, b, counters)) << i;
    if (hit_a) {
      EXPECT_TRUE(same_bits(a, b)) << i;
    }
  }
}

}  // namespace
}  // namespace tessera
