// std::pow(x, y) for a small whole exponent y, bit for bit, mostly without calling it.
//
// The lighting model raises cosines to scene-given powers (a spotlight's fall-off, eq. 4.9's
// highlight) with std::pow, whose answers are part of every image. For a whole n the power can
// be taken exactly enough to know the double nearest to it: x^n in double-double arithmetic
// (Dekker's exact products, no FMA) is within 2^-90 of itself, relatively. glibc's pow (the Arm
// optimized-routines pow, also musl's) is within 0.54 ULP of the exact value. So wherever the
// exact value lies within 0.4 ULP of a double, that double is the only one pow can return (any
// other is at least 0.6 ULP away), and it is returned without calling pow. Nearer a midpoint
// between two doubles (a fifth of the arguments), at a power of two (where the ULP changes) or
// outside the range where the products stay exact, pow is called.
// tests/render/whole_power_test.cpp compares the two on millions of arguments.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>

namespace tessera {

// Exponents up to this are taken here; larger ones cost more products than pow's own work.
inline constexpr int kMaxWholePower = 8;

namespace whole_power_detail {

// A value hi + lo, |lo| at most half an ULP of hi.
struct DoubleDouble {
  double hi, lo;
};

// a = hi + lo with hi holding the top 26 bits (Veltkamp's split, exact for |a| < 2^995).
inline void split(double a, double& hi, double& lo) {
  const double t = 134217729.0 * a;  // 2^27 + 1
  hi = t - (t - a);
  lo = a - hi;
}

// a * b exactly, as p + e (Dekker), while no partial product underflows.
inline DoubleDouble exact_product(double a, double b) {
  double ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  const double p = a * b;
  return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}

// (a.hi + a.lo) * (b.hi + b.lo), to about 2^-104 relatively; a.lo * b.lo is below that.
inline DoubleDouble product(const DoubleDouble& a, const DoubleDouble& b) {
  const DoubleDouble p = exact_product(a.hi, b.hi);
  const double lo = p.lo + (a.hi * b.lo + a.lo * b.hi);
  const double hi = p.hi + lo;
  return {hi, lo - (hi - p.hi)};
}

}  // namespace whole_power_detail

// x^n for 1 <= n <= kMaxWholePower, rounded to nearest, where that is certainly std::pow(x, n);
// nothing where it cannot tell.
inline std::optional<double> certain_whole_power(double x, int n) {
  using namespace whole_power_detail;
  // Inside this range every partial product of x^n (n <= 8) stays far from overflow and
  // underflow, so the products above are exact. NaN fails the test too.
  const double magnitude = std::fabs(x);
  if (!(magnitude >= 0x1p-60 && magnitude <= 0x1p60)) return std::nullopt;
  DoubleDouble power{x, 0};
  // Binary powering from the exponent's top bit down.
  for (int bit = std::bit_width(static_cast<unsigned>(n)) - 2; bit >= 0; --bit) {
    power = product(power, power);
    if ((n >> bit) & 1) power = product(power, DoubleDouble{x, 0});
  }
  // The nearest double to the exact power, and how far the power lies from it.
  const double nearest = power.hi + power.lo;
  const double off = power.lo - (nearest - power.hi);
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(nearest);
  constexpr std::uint64_t kExponent = 0x7FF0000000000000, kMantissa = 0x000FFFFFFFFFFFFF;
  // 0.4 ULP of `nearest`: 2^e of its exponent field times 0.4 * 2^-52.
  const double bound = std::bit_cast<double>(bits & kExponent) * (0.4 * 0x1p-52);
  if ((bits & kMantissa) == 0 || !(std::fabs(off) < bound)) return std::nullopt;
  return nearest;
}

// std::pow(x, y), bit for bit: certain_whole_power's answer where it has one.
inline double power(double x, double y) {
  // The range is checked before the conversion, which is undefined outside int's.
  if (!(y >= 1 && y <= kMaxWholePower)) return std::pow(x, y);
  const int n = static_cast<int>(y);
  if (n != y) return std::pow(x, y);
  if (const std::optional<double> certain = certain_whole_power(x, n)) return *certain;
  return std::pow(x, y);
}

}  // namespace tessera
