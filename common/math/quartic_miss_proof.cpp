// The quartic miss proof (quartic_miss_proof.h).
//
// What the search reports, and so what must be ruled out. visit_real_roots on a quartic p
// splits (lo, hi) at the roots of its derivative, as a cubic search on dc = (i c[i]) finds
// them, and reports a root where p's computed value changes sign between split points, or where
// it is within horner_error of zero at an interior one. So it reports nothing when p's computed
// value at lo is positive (checked as the search computes it) and either
//  (b1) p exceeds T4 = 18 eps S everywhere on [lo, hi], or
//  (b2) the exact dc-cubic exceeds T3 = 15 eps S3 on [lo, hi] and p exceeds T4 on its last
//       4 eps m,
// writing S and S3 for the sums sum |c_i| m^i and sum |dc_i| m^i, with m >= |x| on [lo, hi].
// Above T4, p's computed value (Horner's error is at most gamma(8) S) is positive and above
// horner_error (gamma(9) times the computed sum); likewise the cubic's above T3. Under (b2) the
// cubic search reports no critical point short of the last stretch: its values there are
// positive and not near zero, and a bracketed Newton search does not stop at a point of value
// above 6.1 eps S3 (its step, at least that over |dc'| <= 3 S3 / |x|, exceeds the 2 eps |x| it
// stops at), nor within an ulp of one unless its neighbour is below the margin. Then every
// split point has a positive value: no sign change, no touching root. (bracketed_root's cap of
// 200 steps, never reached on a simple root, aside.) (b2) is the case of a ray leaving the
// surface, whose value at lo is within rounding of zero but rising.
//
// Both are shown on p's Bernstein coefficients over [lo, lo + w] (w >= hi - lo), (b1) also on
// those of its halves, quarters and so on where the whole does not show it: p is a weighted
// mean of them there, and its derivative 4 / w times one of their successive differences. They
// are formed from the power form by a Taylor shift to lo and the change of basis, with a
// rounding error of at most gamma(17) S; with T4, and T3 w / 4 <= 15 eps S (S3 <= 4 S / m,
// w <= m, plus the rounding of 3 c[3] in dc), every test below uses one margin, gamma(128) S.
#include "common/math/quartic_miss_proof.h"

#include <cmath>

#include "common/math/float_error.h"
#include "common/math/quartic_bernstein.h"

namespace tessera {

namespace {

constexpr int kDegree = kQuarticDegree;
using Bernstein = QuarticBernstein;

// (b1). (Bitwise and: no branch per coefficient.)
bool above_margin(const Bernstein& p, double margin) {
  const double* b = p.b;
  return (b[0] > margin) & (b[1] > margin) & (b[2] > margin) & (b[3] > margin) & (b[4] > margin);
}

// The Bernstein coefficients of p's two halves (de Casteljau's midpoints). Each passes through at
// most four rounded sums of values no larger than the largest coefficient, itself below
// (1 + gamma(17)) S, and the halving by 0.5 is exact but for subnormal results (then off by at most
// 2^-1075, against a margin above 1e-114): a halving adds at most about 4 eps S to the error, and
// kMaxHalvings of them keep it well inside the margin: (17 + 4 * 4) eps S for the coefficients and
// 18 eps S for T4, against gamma(128) S. On features/torus.sdl sixteenths settle 594 of the
// shadow rays' 1,413 searches, nearly all the misses among them (tori19 counted 614).
constexpr int kMaxHalvings = 4;

void halve(const Bernstein& p, Bernstein& left, Bernstein& right) {
  const double* b = p.b;
  const double b01 = (b[0] + b[1]) * 0.5, b12 = (b[1] + b[2]) * 0.5, b23 = (b[2] + b[3]) * 0.5,
               b34 = (b[3] + b[4]) * 0.5;
  const double b012 = (b01 + b12) * 0.5, b123 = (b12 + b23) * 0.5, b234 = (b23 + b34) * 0.5;
  const double b0123 = (b012 + b123) * 0.5, b1234 = (b123 + b234) * 0.5;
  const double mid = (b0123 + b1234) * 0.5;
  left = {{b[0], b01, b012, b0123, mid}};
  right = {{mid, b1234, b234, b34, b[4]}};
}

// (b1) on each piece of the interval halved up to `halvings` times where the whole does not show
// it: a grazing miss's quartic dips near zero, and its coefficients over the whole interval
// undershoot its least value by far more than over each half. Fails as soon as a piece's value at
// an end (b[0], b[4]: p there) is below the margin, as it soon is for a ray that hits.
bool above_margin_by_halves(const Bernstein& p, double margin, int halvings) {
  if (above_margin(p, margin)) return true;
  if (halvings == 0 || !(p.b[0] > margin) || !(p.b[4] > margin)) return false;
  Bernstein left, right;
  halve(p, left, right);
  return above_margin_by_halves(left, margin, halvings - 1) &&
         above_margin_by_halves(right, margin, halvings - 1);
}

// (b2): the successive differences above the margin, and p's value at lo + w above it by as
// much as p can rise over the last 4 eps m: 4 / w times the largest difference, which is below
// their sum b[4] - b[0] (by 5 eps m, for the rounding of this bound; multiplied out by w).
bool rises_clear(const Bernstein& p, double w, double m, double margin) {
  const double* b = p.b;
  return (b[1] - b[0] > margin) & (b[2] - b[1] > margin) & (b[3] - b[2] > margin) &
         (b[4] - b[3] > margin) &
         ((b[4] - margin) * w > 5 * kMachineEpsilon * m * kDegree * (b[4] - b[0] + margin));
}

}  // namespace

bool quartic_proven_root_free(const Polynomial& p, double lo, double hi) {
  if (p.degree != kDegree || p.c[kDegree] == 0 || !(lo < hi)) return false;
  // p's Taylor coefficients at lo; the first pass is the search's own value at lo.
  const double* c = p.c;
  double q[kDegree + 1];
  quartic_value_pass(c, lo, q);
  if (!(q[0] > 0)) return false;
  finish_taylor_shift(lo, q);
  // Rounded up, so that [lo, lo + width] holds [lo, hi].
  const double width = next_up(hi - lo);
  const double m = std::fabs(lo) + width;
  const double s = quartic_error_scale(c, m);
  // Far from underflow and overflow, where the relative bounds above hold (and not NaN).
  if (!(s > 1e-100 && s < 1e100) || !std::isfinite(m)) return false;
  const double margin = gamma_bound(128) * s;
  const Bernstein b = bernstein_over(q, width);
  return above_margin_by_halves(b, margin, kMaxHalvings) || rises_clear(b, width, m, margin);
}

}  // namespace tessera
