// The quartic miss proof (common/math/quartic_miss_proof.h) against the root search it stands in
// for: whenever it proves an interval root-free, visit_real_roots finds no root there.
#include "common/math/quartic_miss_proof.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/math/polynomial.h"
#include "tests/math/quartic_factors.h"

namespace tessera {
namespace {

using testing::quadratic_about;
using testing::random_gap;
using testing::random_pair_of_quadratics;

// x - root.
Polynomial linear_with_root(double root) {
  Polynomial p;
  p.degree = 1;
  p.c[0] = -root;
  p.c[1] = 1;
  return p;
}

// What the search finds on (lo, hi), and whether the proof claims nothing is there; counts the
// claims, and fails on a claim the search contradicts.
struct Checker {
  int proven = 0;
  void operator()(const Polynomial& p, double lo, double hi) {
    if (!quartic_proven_root_free(p, lo, hi)) return;
    ++proven;
    PolynomialRoot roots[kMaxPolynomialDegree];
    const int found = real_roots(p, lo, hi, roots);
    ASSERT_EQ(found, 0) << "root " << roots[0].x << " in (" << lo << ", " << hi << ") of " << p.c[4]
                        << " x^4 + " << p.c[3] << " x^3 + " << p.c[2] << " x^2 + " << p.c[1]
                        << " x + " << p.c[0];
  }
};

// Pairs of quadratics with roots close together, touching or just apart (as a grazing ray's
// quartic has), or with none, anywhere around the interval and just beside its ends.
TEST(QuarticMissProof, NeverWhereTheSearchFindsARoot) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  Checker check;
  for (int i = 0; i < 200000; ++i) {
    const double lo = -3 * unit(rng), hi = lo + 5 * unit(rng) + 1e-3;
    // A quarter of the factors centred within 10^-8 of an end, where p nearly vanishes.
    const auto place = [&] {
      const double u = unit(rng);
      if (u >= 0.25) return lo - 1 + (hi - lo + 2) * unit(rng);
      return (u < 0.125 ? lo : hi) + 1e-8 * (2 * unit(rng) - 1);
    };
    check(random_pair_of_quadratics(rng, place), lo, hi);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(check.proven, 20000);
}

// A grazing miss: the quartic dips to a small positive least value inside the interval, where its
// Bernstein coefficients over the whole interval go negative; over its halves, and theirs, they
// do not.
TEST(QuarticMissProof, GrazingMissesAreProvenByHalves) {
  for (const double least : {1e-2, 1e-3}) {
    for (const double at : {0.3, 0.55, 0.71}) {
      const Polynomial p = quadratic_about(at, least) * quadratic_about(2, 1);
      Checker check;
      check(p, 0, 1);
      if (HasFatalFailure()) return;
      EXPECT_EQ(check.proven, 1) << "least " << least << " at " << at;
    }
  }
}

// A touching root (the search reports one where the value is within rounding of zero) or a
// near-miss just above zero at the points where the proof halves the interval: each piece's value
// there is not zero but within the margin, and must not pass.
TEST(QuarticMissProof, NearTouchingRootsAtTheHalvingPointsAreNotProvenAway) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  Checker check;
  for (int i = 0; i < 20000; ++i) {
    const double at = std::floor(1 + 15 * unit(rng)) / 16, least = std::pow(10.0, -18 * unit(rng));
    check(quadratic_about(at, least) * quadratic_about(3 * unit(rng) - 1, random_gap(rng)), 0, 1);
    if (HasFatalFailure()) return;
  }
}

// A ray leaving the surface: a simple root just before lo (rejected as the surface left) or just
// after it (the search reports it); the proof must tell them apart from lo's value and the slope.
TEST(QuarticMissProof, RootsJustAfterTheStartAreNotProvenAway) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0, 1);
  Checker check;
  int proven_leaving = 0;
  for (int i = 0; i < 200000; ++i) {
    const double lo = 2 * unit(rng) - 1, hi = lo + 3 * unit(rng) + 1e-3;
    const double distance = std::pow(10.0, -16 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const Polynomial p = linear_with_root(lo - distance) * linear_with_root(lo - 3 * unit(rng)) *
                         quadratic_about(lo + 3 * unit(rng), random_gap(rng));
    const int before = check.proven;
    check(unit(rng) < 0.5 ? p : -1.0 * p, lo, hi);
    if (HasFatalFailure()) return;
    proven_leaving += check.proven > before && distance > 0;
  }
  EXPECT_GT(proven_leaving, 10000);
}

}  // namespace
}  // namespace tessera
