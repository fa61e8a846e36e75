// The mesh traversal's shortcut at the root (wide_bvh_traverse.h, starts_inside): a ray whose
// origin lies in the root's box, with t_max >= 0, skips the double slab test because that test
// accepts it whatever the direction. Checked here against intersect_bounds itself, on origins
// inside, on the box's faces and corners and just outside, with the directions and limits that
// stress a slab test (zero and negative-zero components, infinities, NaN, tiny and huge ones).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "common/accel/wide_bvh_traverse.h"
#include "tests/accel/edge_case_rays.h"

namespace tessera {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(WideBvhRoot, StartingInsideTheRootBoxIsAcceptedByTheSlabTest) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2, 2);
  const std::vector<double> special_components = {0.0,    -0.0,    kInfinity, -kInfinity, kNaN,
                                                  1e-300, -1e-300, 1e300,     -1e300};
  const std::vector<double> limits = {kInfinity, 0.0, -0.0, 1e-300, 0.5, 3, -1e-300, -1, kNaN};
  const auto component = [&] {
    const double r = u(rng);
    return r > 1.2 ? special_components[static_cast<std::size_t>(rng() % special_components.size())]
                   : direction_component(rng, u);
  };
  int inside = 0, outside_missed = 0;
  for (int i = 0; i < 200000; ++i) {
    Bounds3 box;
    box.extend(Vec3{u(rng), u(rng), u(rng)});
    box.extend(Vec3{u(rng), u(rng), u(rng)});
    if (i % 7 == 0) box.hi.z = box.lo.z;     // flat, as the box of a planar mesh
    if (i % 11 == 0) box.lo.x = -kInfinity;  // unbounded
    // Each coordinate inside, on a face, or a step outside it.
    const auto coordinate = [&](double lo, double hi) {
      switch (rng() % 6) {
        case 0:
          return lo;
        case 1:
          return hi;
        case 2:
          return std::nextafter(lo, -kInfinity);
        case 3:
          return std::nextafter(hi, kInfinity);
        default:
          return lo + (hi - lo) * (u(rng) + 2) / 4;
      }
    };
    const Ray ray{{coordinate(box.lo.x, box.hi.x), coordinate(box.lo.y, box.hi.y),
                   coordinate(box.lo.z, box.hi.z)},
                  {component(), component(), component()}};
    const double t_max = limits[static_cast<std::size_t>(rng() % limits.size())];
    const Vec3 inv_dir{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
    const bool accepted = intersect_bounds(box, ray.origin, inv_dir, t_max);
    if (starts_inside(box, ray.origin, t_max)) {
      ++inside;
      ASSERT_TRUE(accepted) << "origin " << ray.origin.x << " " << ray.origin.y << " "
                            << ray.origin.z << ", direction " << ray.direction.x << " "
                            << ray.direction.y << " " << ray.direction.z << ", t_max " << t_max;
    } else {
      outside_missed += !accepted;
    }
  }
  // Both sides are exercised: many origins inside, and many rays the slab test rejects.
  EXPECT_GT(inside, 20000);
  EXPECT_GT(outside_missed, 20000);
}

// starts_inside compares in pairs of SIMD lanes: the same answer as its definition, the six
// comparisons (false with a NaN) and t_max >= 0, for each coordinate in each place: below, on,
// just beyond and above each face, signed zeros, infinities and NaNs, in boxes with such corners
// too (the empty box's infinite ones included).
TEST(WideBvhRoot, StartsInsideIsItsSixComparisons) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-2, 2);
  const std::vector<double> specials = {0.0, -0.0, kInfinity, -kInfinity, kNaN, 1e-310, -1e300};
  const std::vector<double> limits = {kInfinity, 0.0, -0.0, 1e-300, 3, -1e-300, -1, kNaN};
  const auto pick = [&](const std::vector<double>& from) {
    return from[static_cast<std::size_t>(rng() % from.size())];
  };
  int inside = 0, outside = 0;
  for (int i = 0; i < 300000; ++i) {
    Bounds3 box;
    if (i % 13 != 0) {
      box.extend(Vec3{u(rng), u(rng), u(rng)});
      box.extend(Vec3{u(rng), u(rng), u(rng)});
    }
    double* corner = &box.lo.x;
    if (i % 5 == 0) corner[rng() % 6] = pick(specials);
    const auto coordinate = [&](double lo, double hi) {
      switch (rng() % 8) {
        case 0:
          return lo;
        case 1:
          return hi;
        case 2:
          return std::nextafter(lo, -kInfinity);
        case 3:
          return std::nextafter(hi, kInfinity);
        case 4:
          return pick(specials);
        default:
          return lo + (hi - lo) * (u(rng) + 2) / 4;
      }
    };
    const Vec3 o{coordinate(box.lo.x, box.hi.x), coordinate(box.lo.y, box.hi.y),
                 coordinate(box.lo.z, box.hi.z)};
    const double t_max = pick(limits);
    const bool defined = box.lo.x <= o.x && o.x <= box.hi.x && box.lo.y <= o.y && o.y <= box.hi.y &&
                         box.lo.z <= o.z && o.z <= box.hi.z && t_max >= 0;
    ASSERT_EQ(starts_inside(box, o, t_max), defined)
        << "box " << box.lo.x << " " << box.lo.y << " " << box.lo.z << " / " << box.hi.x << " "
        << box.hi.y << " " << box.hi.z << ", origin " << o.x << " " << o.y << " " << o.z
        << ", t_max " << t_max;
    (defined ? inside : outside) += 1;
  }
  EXPECT_GT(inside, 30000);
  EXPECT_GT(outside, 30000);
}

}  // namespace
}  // namespace tessera
