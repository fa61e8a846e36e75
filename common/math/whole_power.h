// x^e for the shading's exponents (Phong highlights, spotlight fall-off) without libm's pow
// where e is a whole number.
//
// Two reasons. Speed: pow costs some 125 instructions a call, x^40 by binary powering seven
// multiplications (the first exact). Determinism: glibc on x86-64 picks pow's code at run time, an
// FMA variant on CPUs with FMA and AVX2 and an SSE2 one on others, and the two differ by one ulp in
// about one call in 1,500 (docs/STABILITY.md, "Shading"), so a highlight's last bits depended on
// the host. Multiplications in a fixed order give the same double on every IEEE machine.
//
// The price is accuracy: each of the chain's roundings is carried into the power as many times
// as that factor is used, so x^n is within (n - 1) roundings, (n - 1) * 2^-53 relative, of the
// exact value (pow: within about 0.52 ulp). For the exponents scenes use (4 to 120) that is
// at most 1.2 * 10^-14 (98 ulps at n = 120), far below a pixel's float32 step (6 * 10^-8).
// Exponents that are not whole, or above kMaxWholeExponent, go to pow (portable_math.h's, which
// gives the same bits on every host too).
#pragma once

#include <cmath>
#include "common/math/portable_math.h"

namespace tessera {

// Above this, pow's one rounding beats the chain's up to 2 * log2(n) multiplications.
inline constexpr double kMaxWholeExponent = 1024;

// x^n as the product, lowest bit first, of the squares x^(2^k) for each bit k set in n; the
// squares are x, x * x, (x * x) * (x * x), ... This order is the function's contract
// (tests/math/whole_power_test.cpp): changing it changes images.
inline double whole_power(double x, unsigned n) {
  double result = 1;  // 1 * square is exact: the first factor enters unrounded.
  double square = x;
  while (true) {
    if (n & 1) result *= square;
    n >>= 1;
    if (n == 0) return result;
    square *= square;
  }
}

// x^exponent: by whole_power where the exponent is a whole number in [0, kMaxWholeExponent],
// else (fractions, NaN, larger exponents) by tessera::pow.
inline double shading_power(double x, double exponent) {
  if (exponent >= 0 && exponent <= kMaxWholeExponent) {
    const auto n = static_cast<unsigned>(exponent);
    if (static_cast<double>(n) == exponent) return whole_power(x, n);
  }
  return tessera::pow(x, exponent);
}

}  // namespace tessera
