// prepare_triangle_ray's axis permutation, made without branches, against the definition it
// stands for: kz the direction's largest component by magnitude as max_axis picks it (the later
// axis on a tie, none with a NaN), kx and ky the next two cyclically; and the shear from them.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "common/geometry/triangle.h"

namespace tessera {
namespace {

void expect_as_defined(const Vec3& d) {
  const TriangleRay r = prepare_triangle_ray(Ray{{1, 2, 3}, d});
  const int kz = max_axis(abs(d));
  const int kx = kz == 2 ? 0 : kz + 1;
  const int ky = kx == 2 ? 0 : kx + 1;
  ASSERT_EQ(r.kz, kz) << d.x << " " << d.y << " " << d.z;
  ASSERT_EQ(r.kx, kx) << d.x << " " << d.y << " " << d.z;
  ASSERT_EQ(r.ky, ky) << d.x << " " << d.y << " " << d.z;
  const Vec3 dp = permute_axes(d, kx, ky, kz);
  ASSERT_EQ(r.usable, dp.z != 0 && is_finite(dp)) << d.x << " " << d.y << " " << d.z;
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  ASSERT_EQ(bits(r.sx), bits(-dp.x / dp.z));
  ASSERT_EQ(bits(r.sy), bits(-dp.y / dp.z));
  ASSERT_EQ(bits(r.sz), bits(1 / dp.z));
}

TEST(TriangleRay, AxesAreTheLargestComponentsAndTheNextTwo) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Ties of every pair and of all three (either sign), zeros, infinities and NaNs in each place.
  // The largest double and the smallest subnormal: at the edges of `usable`'s finiteness test.
  constexpr double kMax = std::numeric_limits<double>::max();
  constexpr double kTiny = std::numeric_limits<double>::denorm_min();
  const std::vector<double> values = {1,    -1,    0.5,  -0.5, 0,     -0.0,  2,
                                      kInf, -kInf, kNaN, kMax, -kMax, kTiny, -kTiny};
  for (const double x : values)
    for (const double y : values)
      for (const double z : values) {
        expect_as_defined({x, y, z});
        if (HasFatalFailure()) return;
      }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100000; ++i) {
    expect_as_defined({u(rng), u(rng), u(rng)});
    if (HasFatalFailure()) return;
  }
}

}  // namespace
}  // namespace tessera
