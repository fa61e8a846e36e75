// common/render/whole_power.h: its answers against std::pow's, bit for bit, for every whole
// exponent it takes, on cosines (the lighting model's arguments) and across its whole range;
// and that it answers most of them itself, or it would save nothing.
#include "common/render/whole_power.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace tessera {
namespace {

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Draws `count` arguments from `draw` and checks each certain answer against std::pow; returns
// the share of arguments answered.
template <typename Draw>
double check_against_pow(int n, int count, Draw&& draw) {
  int answered = 0, wrong = 0;
  for (int k = 0; k < count; ++k) {
    const double x = draw();
    const std::optional<double> certain = certain_whole_power(x, n);
    if (!certain) continue;
    ++answered;
    if (bits(*certain) != bits(std::pow(x, n)) && ++wrong <= 5)
      ADD_FAILURE() << "x = " << std::hexfloat << x << ", n = " << n << ": " << *certain
                    << " against pow's " << std::pow(x, n);
  }
  EXPECT_EQ(wrong, 0) << "n = " << n;
  return static_cast<double>(answered) / count;
}

TEST(WholePower, CosinesAsPowHasThem) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> cosine(0, 1);
  for (int n = 1; n <= kMaxWholePower; ++n) {
    const double share = check_against_pow(n, 2'000'000, [&] { return cosine(rng); });
    // x^1 is always certain; otherwise a fifth of the powers lie near a midpoint.
    EXPECT_GT(share, n == 1 ? 0.999 : 0.75) << "n = " << n;
  }
}

TEST(WholePower, WholeRangeAsPowHasIt) {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> exponent(-62, 62);
  std::bernoulli_distribution negative(0.5);
  for (int n = 1; n <= kMaxWholePower; ++n) {
    check_against_pow(n, 500'000, [&] {
      const double x = std::exp2(exponent(rng));
      return negative(rng) ? -x : x;
    });
  }
}

TEST(WholePower, EdgesGoToPow) {
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (const double x : {0.0, -0.0, kNan, kInf, -kInf, 0x1p-61, 0x1p61, 1e-300})
    for (int n = 1; n <= kMaxWholePower; ++n) EXPECT_FALSE(certain_whole_power(x, n)) << x;
  // Powers of two: the ULP below is half the ULP above, so the bound does not hold.
  EXPECT_FALSE(certain_whole_power(1.0, 4));
  EXPECT_FALSE(certain_whole_power(0.5, 3));
  // power() itself still answers as pow does there, and for exponents it does not take.
  for (const double x : {0.0, -0.0, 1.0, 0.5, 0x1p-70, -3.0})
    for (const double y : {1.0, 2.0, 4.0, 8.0, 2.5, 9.0, 80.0, 0.0, -2.0})
      EXPECT_EQ(bits(power(x, y)), bits(std::pow(x, y))) << x << "^" << y;
  EXPECT_TRUE(std::isnan(power(kNan, 4)));
}

}  // namespace
}  // namespace tessera
