// The quartic sign proof (quartic_crossing_proof.h).
//
// The search (visit_real_roots, polynomial.h) splits (lo, hi) at the roots of p's derivative
// dc as a cubic search finds them, and reports a root in each piece whose ends' computed values
// have opposite signs, and at an interior split point whose value is within horner_error of
// zero. Write S = sum |c_i| m^i with m >= |x| on [lo, hi], and V for how far p can fall short of
// monotone on a piece: the split points miss dc's sign changes only where |dc| is within its
// rounding, gamma(7) S3 <= 28 eps S / m (S3 = sum |dc_i| m^i <= 4 S / m), over a piece no longer
// than 2 m, so V <= 56 eps S. Horner's error on p is at most gamma(9) S.
//
// Say p(a) > M and p(b) < -M, a < b, with M = gamma(256) S > 2 V + 2 gamma(9) S + 9 eps S. The
// piece holding a either starts at a split point whose computed value is positive (p above M - V
// from there to a: no sign change before a), or rises through a to a split point at most b with
// a positive value (a root before a may be reported there). Likewise the piece holding b ends at
// a split point with a negative value, or one at least a has it. Between a positive split point
// and a later negative one the search reports a root, in a piece or at a zero split point, and
// the first such lies in [a, b] unless it is in the piece holding a or b. There, bracketed Newton
// cannot stop left of a: computed p exceeds M - gamma(9) S there, and it stops only on a step
// under 2 eps |x|, which needs |p'| >= (M - gamma(9) S) / (2 eps m) > 4.1 S / m, above any
// value of p' on [lo, hi]; the step it then takes, or the bracket's end it returns, moves it at
// most 2 eps m (an ulp) past a. So the root is in [a - 2 eps m, b + 2 eps m], well inside the
// slack. (bracketed_root's cap of 200 steps, never reached on a simple root, aside.) The other
// way round, p(a) < -M and p(b) > M, is the same argument on -p: the search treats both signs
// alike, and negating p's coefficients negates every value it computes, exactly.
#include "common/math/quartic_crossing_proof.h"

#include <cmath>
#include <limits>

#include "common/math/float_error.h"

namespace tessera {

QuarticSignProof::QuarticSignProof(const Polynomial& p, double lo, double hi) : p_(p) {
  const double* c = p.c;
  const double m = std::fmax(std::fabs(lo), std::fabs(hi));
  const double s =
      (((std::fabs(c[4]) * m + std::fabs(c[3])) * m + std::fabs(c[2])) * m + std::fabs(c[1])) * m +
      std::fabs(c[0]);
  // Far from underflow and overflow, where the relative bounds above hold (and not NaN).
  const bool provable = p.degree == 4 && c[4] != 0 && s > 1e-100 && s < 1e100 && std::isfinite(m);
  margin_ = provable ? gamma_bound(256) * s : std::numeric_limits<double>::quiet_NaN();
  slack_ = 8 * kMachineEpsilon * m;
}

// Horner's rule: within gamma(9) S of p(x), which the margin covers.
bool QuarticSignProof::clearly_positive(double x) const { return evaluate(p_, x) > margin_; }

bool QuarticSignProof::clearly_negative(double x) const { return evaluate(p_, x) < -margin_; }

}  // namespace tessera
