// The first-root proof (quartic_first_root.h).
//
// The search (visit_real_roots, polynomial.h) splits (lo, hi) at the roots of p's derivative dc,
// as a cubic search on dc finds them, and reports a root in the first piece whose ends' computed
// values have opposite signs, or at an interior split point whose value is within horner_error of
// zero. Write S and S3 for sum |c_i| m'^i and sum |dc_i| m'^i, m' >= |x| on [lo, b], b <= hi.
// Say
//  (f1) p's computed value at lo is positive (computed as the search computes it),
//  (f2) the exact cubic dc is below -T3 = -15 eps S3 on [lo, b], and
//  (f3) p(b) < -gamma(128) S.
// By (f2), the mirror of the miss proof's (b2) (quartic_miss_proof.cpp; the cubic search treats
// both signs alike), the cubic search reports no critical point in [lo, b) short of its last
// 4 eps m' (an ulp or two), and p falls on [lo, b]: p has exactly one root r in (lo, b), by (f1)
// and (f3). So the search's first piece is [lo, x1], x1 its first split point, at least b up to
// that ulp or two; p(x1) is negative (p is below -gamma(128) S at b and can rise after it only at
// a critical point the cubic search finds, or by what it misses within dc's rounding, V <=
// 56 eps S as quartic_crossing_proof.cpp bounds it), and by more than horner_error (gamma(9) S):
// the piece has a sign change and no zero split point comes before it. The search reports the
// root that bracketed Newton polishes in [lo, x1], where p's only root is r: polished_root(p, lo,
// b) polishes the same root in a narrower bracket, and the two agree up to the rounding of their
// last steps.
//
// (f2) and (f3) are shown on p's Bernstein coefficients over [lo, lo + w] (quartic_bernstein.h),
// w = b - lo rounded, whose end is within an ulp of b (p moves by at most 8 eps S over it): their
// successive differences below -margin (dc is 4 / w times a weighted mean of them; T3 w / 4 <=
// 15 eps S as in the miss proof), and the last below -margin, with the miss proof's margin
// gamma(128) S, which covers T3 and the coefficients' rounding (gamma(17) S). b is m, or where p
// has passed its least value before m, the end of a left half, quarter or eighth of [lo, m],
// whose coefficients de Casteljau's halving gives from these, each a mean of two: a few eps S
// more rounding, which the margin also covers.
#include "common/math/quartic_first_root.h"

#include <cmath>

#include "common/math/float_error.h"
#include "common/math/quartic_bernstein.h"

namespace tessera {

namespace {

// Of [lo, m], down to its left eighth: on features/torus.sdl (320x240, one ray a pixel) the proof
// brackets 4,242 of the 11,875 camera rays' first roots on [lo, m] itself, 9,165 with halvings.
constexpr int kMostHalvings = 3;

// The Bernstein coefficients over the left half of the interval (de Casteljau), each a mean of
// two: the rounding they add is a few eps times the largest, far inside the margin.
void keep_left_half(double* b) {
  const double b01 = 0.5 * (b[0] + b[1]), b12 = 0.5 * (b[1] + b[2]), b23 = 0.5 * (b[2] + b[3]),
               b34 = 0.5 * (b[3] + b[4]);
  const double b012 = 0.5 * (b01 + b12), b123 = 0.5 * (b12 + b23), b234 = 0.5 * (b23 + b34);
  const double b0123 = 0.5 * (b012 + b123), b1234 = 0.5 * (b123 + b234);
  b[1] = b01;
  b[2] = b012;
  b[3] = b0123;
  b[4] = 0.5 * (b0123 + b1234);
}

}  // namespace

std::optional<double> quartic_first_root_bracket(const Polynomial& p, double lo, double m) {
  if (p.degree != kQuarticDegree || p.c[kQuarticDegree] == 0 || !(lo < m)) return std::nullopt;
  const double* c = p.c;
  double q[kQuarticDegree + 1];
  quartic_value_pass(c, lo, q);
  if (!(q[0] > 0)) return std::nullopt;  // (f1)
  finish_taylor_shift(lo, q);
  const double width = m - lo;
  // Rounded up, so that it bounds |x| on [lo, m].
  const double largest = std::fabs(lo) + next_up(width);
  const double s = quartic_error_scale(c, largest);
  // Far from underflow and overflow, where the relative bounds above hold (and not NaN).
  if (!(s > 1e-100 && s < 1e100) || !std::isfinite(largest)) return std::nullopt;
  const double margin = gamma_bound(128) * s;
  QuarticBernstein bernstein = bernstein_over(q, width);
  double* b = bernstein.b;
  double w = width;
  for (int halvings = 0;; ++halvings) {
    if (!(b[4] < -margin)) return std::nullopt;  // (f3)
    // (f2). (Bitwise and: no branch per coefficient.)
    if ((b[1] - b[0] < -margin) & (b[2] - b[1] < -margin) & (b[3] - b[2] < -margin) &
        (b[4] - b[3] < -margin))
      return halvings == 0 ? m : lo + w;
    // Usually p has passed its least value before m: its left part may fall all the way.
    if (halvings == kMostHalvings) return std::nullopt;
    keep_left_half(b);
    w *= 0.5;
  }
}

}  // namespace tessera
