// The two-box test of the BVH traversal (SSE2 on x86-64) against the scalar slab test it
// stands for: the same hits and bit-identical entry distances, on random rays and on the
// edge cases (zero direction components, origins on box planes, negative zero, infinite and
// empty boxes), so that images do not depend on which one a build uses.
#include "common/accel/child_boxes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "tests/accel/edge_case_rays.h"

namespace tessera {
namespace {

void expect_same_as_scalar(const Bounds3& first, const Bounds3& second, const Ray& ray,
                           double t_max) {
  const ChildBoxes boxes = make_child_boxes(first, second);
  const BoxRay box_ray(ray);
  double entry[2] = {-1, -1};
  const unsigned hits = intersect_child_boxes(boxes, box_ray, t_max, entry);
  // The scalar test's own inverse, not the one BoxRay made (with divpd under SSE2).
  const Vec3 inv_dir{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
  const Bounds3* children[2] = {&first, &second};
  for (int c = 0; c < 2; ++c) {
    double scalar_entry = -1;
    const bool scalar_hit =
        intersect_bounds(*children[c], ray.origin, inv_dir, t_max, scalar_entry);
    ASSERT_EQ((hits >> c) & 1u, scalar_hit ? 1u : 0u) << "child " << c;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(entry[c]), std::bit_cast<std::uint64_t>(scalar_entry))
        << "child " << c << ": " << entry[c] << " vs " << scalar_entry;
  }
}

TEST(ChildBoxes, MatchTheScalarSlabTestOnRandomRays) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  // Directions with a component of exactly 0 or -0 now and then, and origins on box planes.
  const auto coordinate = [&](double plane) {
    const double r = u(rng);
    return r > 1.6 ? plane : r;
  };
  const auto component = [&] { return direction_component(rng, u); };
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    Bounds3 a, b;
    a.extend(Vec3{u(rng), u(rng), u(rng)});
    a.extend(Vec3{u(rng), u(rng), u(rng)});
    b.extend(Vec3{u(rng), u(rng), u(rng)});
    b.extend(Vec3{u(rng), u(rng), u(rng)});
    const Ray ray{{coordinate(a.lo.x), coordinate(b.hi.y), coordinate(a.hi.z)},
                  {component(), component(), component()}};
    const double t_max = u(rng) > 0 ? kInfinity : 2 + u(rng);
    expect_same_as_scalar(a, b, ray, t_max);
    if (HasFatalFailure()) return;
    hits += intersect_bounds(a, ray.origin, BoxRay(ray).inv_dir, t_max);
  }
  EXPECT_GT(hits, 2000);  // the cases are not all misses
}

TEST(ChildBoxes, MatchTheScalarSlabTestOnEdgeCases) {
  const Bounds3 unit{{0, 0, 0}, {1, 1, 1}};
  const Bounds3 flat{{0, 0, 0.5}, {1, 1, 0.5}};
  const Bounds3 empty;
  const Bounds3 infinite{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, kInfinity, kInfinity}};
  const Bounds3 boxes[] = {unit, flat, empty, infinite};
  for (const Ray& ray : edge_case_rays())
    for (const Bounds3& a : boxes)
      for (const Bounds3& b : boxes)
        for (const double t_max : {kInfinity, 0.25, 0.0}) {
          expect_same_as_scalar(a, b, ray, t_max);
          if (HasFatalFailure()) return;
        }
}

}  // namespace
}  // namespace tessera
