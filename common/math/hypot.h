// sqrt(x^2 + y^2) without the library call, where the torus needs it several times a ray.
//
// libm's hypot cost 4.8 % of a torus render, for its call and its guards against overflow and
// underflow more than for its arithmetic. This is the same computation (Borges, "An Improved
// Algorithm for hypot(a, b)", 2019; glibc's since 2.35 on machines built without FMA, as
// Tessera's are: -ffp-contract=off) with the same operations in the same order, inline, for the
// arguments that need no scaling; the others go to std::hypot. So it returns std::hypot's value
// for every input where libm is glibc >= 2.35 (tests/math/hypot_test.cpp), and on other
// systems the same value as here (about 0.5 ulp) whatever their libm does.
#pragma once

#include <algorithm>
#include <cmath>

namespace tessera {

inline double hypot_inline(double x, double y) {
  const double abs_x = std::fabs(x), abs_y = std::fabs(y);
  const double ax = std::max(abs_x, abs_y), ay = std::min(abs_x, abs_y);
  // glibc's ranges: squares that cannot overflow or underflow, and ay not so small beside ax
  // that the sum is ax (which glibc returns as ax + ay). NaN and infinity fail them too.
  if (!(ax <= 0x1p511 && ay >= 0x1p-459 && ay > ax * 0x1p-54)) return std::hypot(x, y);
  // The rounded square root, corrected by one Newton step on the exact residual of its square.
  double h = std::sqrt(ax * ax + ay * ay);
  double t1, t2;
  if (h <= 2.0 * ay) {
    const double delta = h - ay;
    t1 = ax * (2.0 * delta - ax);
    t2 = (delta - 2.0 * (ax - ay)) * delta;
  } else {
    const double delta = h - ax;
    t1 = 2.0 * delta * (ax - 2.0 * ay);
    t2 = (4.0 * delta - ay) * ay + delta * delta;
  }
  h -= (t1 + t2) / (2.0 * h);
  return h;
}

}  // namespace tessera
