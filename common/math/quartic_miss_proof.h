// A cheap proof that the root search of polynomial.h finds nothing in an interval, for quartics
// (the torus' ray quartic): most rays that meet a torus's box miss it, and most of those are
// shadow rays leaving its own surface, whose search computes every critical point to learn that.
//
// The proof works on the quartic's Bernstein coefficients over the interval, with a margin that
// covers their rounding and the search's own tolerances, so that "proven" means exactly
// "visit_real_roots would report no root": images do not change. It costs a fraction of a
// search that finds nothing, and fails fast on rays that hit.
#pragma once

#include "common/math/polynomial.h"

namespace tessera {

// True only when visit_real_roots(p, lo, hi, ...) would report no root at all, so that it need
// not run; false says nothing. Tries only quartics (p.degree == 4 with c[4] != 0) whose value at
// lo, as the search computes it, is positive: outside the surface, where a ray that misses starts
// (and a ray leaving the surface, which the proof takes as rising away from it).
bool quartic_proven_root_free(const Polynomial& p, double lo, double hi);

}  // namespace tessera
