// A cheap proof that the root search of polynomial.h finds a root between two points, for
// quartics (the torus' ray quartic): a shadow ray blocked by a torus otherwise computes the
// quartic's critical points up to the first sign change, only to answer "blocked".
//
// Like quartic_miss_proof.h, the proof keeps a margin that covers the rounding of the values it
// computes and the search's own tolerances, so that "proven" means exactly what the search would
// find: images do not change.
#pragma once

#include "common/math/polynomial.h"

namespace tessera {

// The signs of a quartic p (degree 4, c[4] != 0) on [lo, hi] that its root search on (lo, hi)
// cannot mistake.
class QuarticSignProof {
 public:
  QuarticSignProof(const Polynomial& p, double lo, double hi);

  // p(x) is above the margin (below minus it), for x in [lo, hi]; false says nothing.
  bool clearly_positive(double x) const;
  bool clearly_negative(double x) const;

  // When p is clearly positive at a and clearly negative at b (lo <= a < b <= hi), or the other
  // way round, visit_real_roots(p, lo, hi, ...) reports a root in [a - slack, b + slack], unless
  // it was ended at an earlier one.
  double slack() const { return slack_; }

 private:
  const Polynomial& p_;
  double margin_ = 0;  // NaN when no proof is possible (p not a quartic, or near underflow)
  double slack_ = 0;
};

}  // namespace tessera
