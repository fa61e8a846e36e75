// next_up / next_down (common/math/float_error.h) against std::nextafter, bit for bit.
#include "common/math/float_error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

using Limits = std::numeric_limits<double>;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_as_nextafter(double x) {
  EXPECT_EQ(bits(next_up(x)), bits(std::nextafter(x, Limits::infinity()))) << x;
  EXPECT_EQ(bits(next_down(x)), bits(std::nextafter(x, -Limits::infinity()))) << x;
}

TEST(NextUpDown, AgreeWithNextafterOnEveryKindOfDouble) {
  const std::vector<double> edges = {0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     Limits::denorm_min(),
                                     -Limits::denorm_min(),
                                     Limits::min(),
                                     -Limits::min(),
                                     std::nextafter(Limits::min(), 0.0),
                                     Limits::max(),
                                     -Limits::max(),
                                     Limits::infinity(),
                                     -Limits::infinity(),
                                     1e5,
                                     -1e-300};
  for (double x : edges) expect_as_nextafter(x);
  EXPECT_TRUE(std::isnan(next_up(Limits::quiet_NaN())));
  EXPECT_TRUE(std::isnan(next_down(Limits::quiet_NaN())));

  // Random bit patterns cover every exponent, both signs and subnormals alike.
  std::mt19937_64 random(7);
  for (int i = 0; i < 100000; ++i) {
    const double x = std::bit_cast<double>(random());
    if (!std::isnan(x)) expect_as_nextafter(x);
  }
}

}  // namespace
}  // namespace tessera
