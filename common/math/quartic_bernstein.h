// A quartic's Bernstein coefficients over an interval, for the proofs that stand in for parts of
// its root search (quartic_miss_proof.h, quartic_first_root.h): on [lo, lo + w] the quartic is a
// weighted mean of its five coefficients b[0..4], b[0] and b[4] are its values at the ends, and
// its derivative is 4 / w times a weighted mean of their successive differences.
#pragma once

#include <cmath>

namespace tessera {

inline constexpr int kQuarticDegree = 4;

// The first pass of the Taylor shift of c[0..4] to lo (synthetic division), into q: Horner's rule
// at lo, the root search's own operations in the same order (up to the order of each product's
// and sum's operands), so q[0] is the value it computes there.
inline void quartic_value_pass(const double* c, double lo, double q[kQuarticDegree + 1]) {
  q[4] = c[4];
  q[3] = c[3] + lo * q[4];
  q[2] = c[2] + lo * q[3];
  q[1] = c[1] + lo * q[2];
  q[0] = c[0] + lo * q[1];
}

// The rest of the shift: q becomes the Taylor coefficients at lo.
inline void finish_taylor_shift(double lo, double q[kQuarticDegree + 1]) {
  q[3] += lo * q[4];
  q[2] += lo * q[3];
  q[1] += lo * q[2];
  q[3] += lo * q[4];
  q[2] += lo * q[3];
  q[3] += lo * q[4];
}

// Sum |c_i| m^i, the scale of the rounding errors of everything above for |x| <= m.
inline double quartic_error_scale(const double* c, double m) {
  return (((std::fabs(c[4]) * m + std::fabs(c[3])) * m + std::fabs(c[2])) * m + std::fabs(c[1])) *
             m +
         std::fabs(c[0]);
}

struct QuarticBernstein {
  double b[kQuarticDegree + 1];
};

// The Bernstein coefficients over [lo, lo + w] from q, the Taylor coefficients at lo. With the
// shift, within gamma(17) S of the exact ones (S = quartic_error_scale(c, |lo| + w)).
inline QuarticBernstein bernstein_over(const double* q, double w) {
  const double w2 = w * w;
  const double a1 = q[1] * w, a2 = q[2] * w2, a3 = q[3] * (w2 * w), a4 = q[4] * (w2 * w2);
  return {{q[0], q[0] + a1 * 0.25, q[0] + a1 * 0.5 + a2 * (1.0 / 6),
           q[0] + a1 * 0.75 + a2 * 0.5 + a3 * 0.25, q[0] + a1 + a2 + a3 + a4}};
}

}  // namespace tessera
