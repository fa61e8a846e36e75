// Camera rays share their origin, so Tracer::find_packet_hits takes it into each instance's
// object space once (object_origin) and hands it to intersect_instance: everything must be what
// the ray taken into object space whole gives, bit for bit.
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

// The same bits, or NaN in both (a NaN's sign depends on the compiler's operand order).
bool same_values(const Vec3& a, const Vec3& b) {
  const auto same = [](double x, double y) {
    return std::memcmp(&x, &y, sizeof x) == 0 || (std::isnan(x) && std::isnan(y));
  };
  return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z);
}

Instance instance_of(const ShapeGeometry& shape, const Affine& to_world) {
  std::optional<Instance> made = make_instance(shape, to_world, nullptr);
  EXPECT_TRUE(made.has_value());
  return made.value_or(Instance{});
}

// Diagonal transforms with zero translations (object coordinates of zero, whose sign the
// diagonal product may get wrong, for points on those planes), and the tori's turn about x.
std::vector<Affine> transforms() {
  return {
      Affine::translation({0, -2, 0}) * Affine::scaling({8, 0.05, 4}),
      Affine::translation({-0.0, 0, -0.0}) * Affine::scaling({2, 0.5, 1}),
      Affine::translation({1e8, 0, -1e8}) * Affine::scaling({1e-4, 1e4, -3}),
      Affine::translation({-3.6, 0, 0}) * *Affine::rotation(-60, {1, 0, 0}),
  };
}

double component(std::mt19937_64& rng, double spread) {
  static const double kSpecial[] = {
      0.0, -0.0, 1.0, -1.0, 1e-300, 1e300, std::numeric_limits<double>::infinity()};
  const int i = std::uniform_int_distribution<int>(0, 13)(rng);
  if (i < 7) return kSpecial[i];
  return std::uniform_real_distribution<double>(-spread, spread)(rng);
}

TEST(SharedOrigin, ObjectOriginIsTheObjectRaysOrigin) {
  std::mt19937_64 rng(5);
  for (const Affine& m : transforms()) {
    const Instance instance = instance_of(Sphere{}, m);
    for (int i = 0; i < 20000; ++i) {
      const Vec3 p{component(rng, 10), component(rng, 10), component(rng, 10)};
      const Vec3 d{component(rng, 1), component(rng, 1), component(rng, 1)};
      ASSERT_TRUE(same_values(object_origin(instance, p), object_ray(instance, {p, d, 0}).origin))
          << i;
    }
  }
}

// Whole intersections from one eye, as a camera's rays: spheres, cubes, cylinders and tori,
// diagonal and not, the eye on the planes of the translations' zeros; and a moving instance at
// a time other than 0, which is posed first (the shared origin is not its pose's).
TEST(SharedOrigin, IntersectionsAreThoseOfTheWholeRay) {
  std::mt19937_64 rng(9);
  const ShapeGeometry shapes[] = {Sphere{}, Cube{}, TaperedCylinder{0.5}, Torus{0.4, 1.1}};
  std::vector<Instance> instances;
  for (const ShapeGeometry& shape : shapes)
    for (const Affine& m : transforms()) instances.push_back(instance_of(shape, m));
  ObjectMotion motion;
  motion.angle_degrees = 40;
  motion.axis = {0, 1, 0};
  const std::optional<Instance> moving =
      make_moving_instance(Torus{0.4, 1.1}, Affine::translation({0, 0, -5}), motion, 1, nullptr);
  ASSERT_TRUE(moving.has_value());
  instances.push_back(*moving);
  for (const Instance& instance : instances) {
    const Vec3 centre = instance.to_world.apply_point({0, 0, 0});
    const Vec3 eye{0, 3, 12};
    const Vec3 shared = object_origin(instance, eye);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 target =
          centre + Vec3{component(rng, 2), component(rng, 2), component(rng, 2)} * 0.7;
      const Ray ray{eye, target - eye, &instance == &instances.back() ? 0.5 : 0.0};
      IntersectionCounters counters;
      WorldHit a, b;
      const bool hit_a = intersect_instance(instance, ray, shared, kInfinity, a, counters);
      const bool hit_b = intersect_instance(instance, ray, kInfinity, b, counters);
      ASSERT_EQ(hit_a, hit_b) << i;
      if (!hit_a) continue;
      ++hits;
      ASSERT_TRUE(std::memcmp(&a, &b, sizeof a) == 0) << i;
    }
    EXPECT_GT(hits, 100);
  }
}

}  // namespace
}  // namespace tessera
