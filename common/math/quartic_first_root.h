// A cheap proof of where the root search of polynomial.h finds its first root, for quartics (the
// torus' ray quartic): a camera ray that hits a torus otherwise finds the quartic's first critical
// point (a cubic's root, polished by Newton's method) only to bracket the first root by it.
//
// Like quartic_miss_proof.h, the proof keeps a margin that covers the rounding of the values it
// computes and the search's own tolerances, so that the root it brackets is the search's first.
#pragma once

#include <optional>

#include "common/math/polynomial.h"

namespace tessera {

// A point b in (lo, m] such that visit_real_roots(p, lo, hi, ...), for any hi >= m, reports as
// its first root the one root of p in (lo, b): p's value at lo, as the search computes it, is
// positive, and p falls clearly all the way from there to a clearly negative value at b, so that
// the search finds no critical point before b and brackets the root by lo and a split point at
// or after b. Then polished_root(p, lo, b) is that root, correctly rounded. b is m
// or, where p has passed its least value before m, lo + (m - lo) / 2, / 4 or / 8; nullopt when
// none of them shows it. Tries only quartics (p.degree == 4 with c[4] != 0) and lo < m.
std::optional<double> quartic_first_root_bracket(const Polynomial& p, double lo, double m);

}  // namespace tessera
