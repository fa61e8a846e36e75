// hypot_inline (common/math/hypot.h) against std::hypot, bit for bit where libm is glibc's
// algorithm (>= 2.35), which hypot_inline transcribes.
#include "common/math/hypot.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))

using Limits = std::numeric_limits<double>;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_as_hypot(double x, double y) {
  EXPECT_EQ(bits(hypot_inline(x, y)), bits(std::hypot(x, y))) << x << ' ' << y;
}

TEST(HypotInline, AgreesWithLibmBitForBit) {
  const std::vector<double> edges = {0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     3.0,
                                     4.0,
                                     0x1p511,
                                     0x1.0000000000001p511,
                                     0x1p-459,
                                     0x1.fffffffffffffp-460,
                                     Limits::min(),
                                     Limits::max(),
                                     Limits::denorm_min(),
                                     Limits::infinity(),
                                     1e-300,
                                     1e300,
                                     0.1,
                                     0x1p-54};
  for (double x : edges)
    for (double y : edges) {
      expect_as_hypot(x, y);
      expect_as_hypot(-x, y);
    }
  EXPECT_TRUE(std::isnan(hypot_inline(Limits::quiet_NaN(), 1.0)));
  EXPECT_EQ(hypot_inline(Limits::quiet_NaN(), Limits::infinity()), Limits::infinity());

  // Both branches of the correction (y near x and far below it), ratios around glibc's 2^-54
  // cut-off, and magnitudes across and beyond the inline range.
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> mantissa(1, 2);
  std::uniform_int_distribution<int> exponent(-520, 520), gap(0, 60);
  for (int i = 0; i < 1000000; ++i) {
    const int e = exponent(random);
    const double x = std::ldexp(mantissa(random), e);
    const double y = std::ldexp(mantissa(random), e - gap(random));
    expect_as_hypot(x, y);
    expect_as_hypot(-y, x);
  }
}

#endif

}  // namespace
}  // namespace tessera
