// whole_power and shading_power (common/math/whole_power.h): the fixed order of multiplications
// that images depend on, its distance from pow, and which exponents take it.
#include "common/math/whole_power.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// The contract written out another way: the table of squares x^(2^k) first, then the product of
// those whose bit is set in n, lowest first.
double reference_power(double x, unsigned n) {
  std::vector<double> squares = {x};
  for (unsigned rest = n >> 1; rest != 0; rest >>= 1)
    squares.push_back(squares.back() * squares.back());
  double product = 1;
  for (std::size_t k = 0; k < squares.size(); ++k)
    if ((n >> k) & 1) product *= squares[k];
  return product;
}

// Cosines in (0, 1] as the shading meets them, and some beyond it.
std::vector<double> arguments() {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> xs = {1.0, 0.5, 0.999999, 0x1.fffffffffffffp-1, 0x1p-20, 2.0, 1.5, -0.7};
  for (int i = 0; i < 200000; ++i) xs.push_back(1.0 - unit(rng));
  for (int i = 0; i < 20000; ++i) xs.push_back(1.0 - 1e-3 * unit(rng));  // near highlights' peak
  return xs;
}

TEST(WholePower, MultipliesInTheFixedOrderBitForBit) {
  const std::vector<double> xs = arguments();
  for (unsigned n = 0; n <= 260; ++n)
    for (std::size_t i = 0; i < xs.size(); i += 7)
      ASSERT_EQ(bits(whole_power(xs[i], n)), bits(reference_power(xs[i], n)))
          << std::hexfloat << xs[i] << " ^ " << n;
  for (const unsigned n : {511u, 512u, 777u, 1023u, 1024u})
    for (const double x : xs) ASSERT_EQ(bits(whole_power(x, n)), bits(reference_power(x, n)));
}

// Within n - 1 roundings of the exact power, and pow within one more: (n + 1) * 2^-53 of pow,
// relative, wherever the result is a normal number.
TEST(WholePower, StaysWithinItsRoundingsOfPow) {
  const std::vector<double> xs = arguments();
  for (const unsigned n : {1u, 2u, 3u, 4u, 8u, 20u, 30u, 40u, 60u, 80u, 120u, 200u, 1024u}) {
    const double bound = (n + 1) * 0x1p-53;
    for (const double x : xs) {
      const double expected = std::pow(x, n);
      if (!std::isnormal(expected)) continue;
      ASSERT_LE(std::fabs(whole_power(x, n) - expected), bound * std::fabs(expected))
          << std::hexfloat << x << " ^ " << n;
    }
  }
}

TEST(WholePower, EdgeValuesAsPow) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double x : {0.0, -0.0, 1.0, -1.0, inf, -inf, nan})
    for (const unsigned n : {0u, 1u, 2u, 3u, 40u, 41u}) {
      const double expected = std::pow(x, n);
      if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(whole_power(x, n))) << x << " ^ " << n;
      } else {
        EXPECT_EQ(bits(whole_power(x, n)), bits(expected)) << x << " ^ " << n;
      }
    }
}

TEST(ShadingPower, WholeExponentsMultiplyOthersCallPow) {
  const double x = 0.8123456789;
  for (const double e : {0.0, 1.0, 4.0, 40.0, 120.0, kMaxWholeExponent})
    EXPECT_EQ(bits(shading_power(x, e)), bits(whole_power(x, static_cast<unsigned>(e)))) << e;
  for (const double e : {0.5, 2.5, 25.6, 40.000000000000007, 1e-9, kMaxWholeExponent + 1, 1e6,
                         std::numeric_limits<double>::quiet_NaN()})
    EXPECT_EQ(bits(shading_power(x, e)), bits(tessera::pow(x, e))) << e;
}

}  // namespace
}  // namespace tessera
