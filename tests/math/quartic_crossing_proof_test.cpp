// The quartic sign proof (common/math/quartic_crossing_proof.h) against the root search it stands
// in for: whenever it shows a sign change between a and b, visit_real_roots finds a root there.
#include "common/math/quartic_crossing_proof.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "tests/math/quartic_factors.h"

namespace tessera {
namespace {

using testing::quadratic_about;
using testing::random_gap;

// Pairs of quadratics with roots close together, touching or just apart (as a grazing ray's
// quartic has), or with none; the two points anywhere in the interval, or within 10^-8 of a
// factor's centre, where p nearly vanishes and its computed sign is noise.
TEST(QuarticCrossingProof, TheSearchFindsARootBetweenClearSigns) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  int proven = 0;
  for (int i = 0; i < 200000; ++i) {
    const double lo = -3 * unit(rng), hi = lo + 5 * unit(rng) + 1e-3;
    const double centre1 = lo - 1 + (hi - lo + 2) * unit(rng);
    const double centre2 = lo - 1 + (hi - lo + 2) * unit(rng);
    const double scale = std::pow(10.0, 6 * unit(rng) - 3);
    const Polynomial p = scale * (quadratic_about(centre1, random_gap(rng)) *
                                  quadratic_about(centre2, random_gap(rng)));
    const auto point = [&] {
      const double u = unit(rng);
      const double x = u >= 0.5 ? lo + (hi - lo) * unit(rng)
                                : (u < 0.25 ? centre1 : centre2) + 1e-8 * (2 * unit(rng) - 1);
      return std::clamp(x, lo, hi);
    };
    double a = point(), b = point();
    if (a > b) std::swap(a, b);
    const QuarticSignProof signs(p, lo, hi);
    if (!(a < b) || !((signs.clearly_positive(a) && signs.clearly_negative(b)) ||
                      (signs.clearly_negative(a) && signs.clearly_positive(b))))
      continue;
    ++proven;
    PolynomialRoot roots[kMaxPolynomialDegree];
    const int found = real_roots(p, lo, hi, roots);
    bool between = false;
    for (int k = 0; k < found; ++k)
      between |= roots[k].x >= a - signs.slack() && roots[k].x <= b + signs.slack();
    ASSERT_TRUE(between) << "no root in [" << a << ", " << b << "] of " << p.c[4] << " x^4 + "
                         << p.c[3] << " x^3 + " << p.c[2] << " x^2 + " << p.c[1] << " x + "
                         << p.c[0] << " on (" << lo << ", " << hi << ")";
  }
  EXPECT_GT(proven, 20000) << proven;
}

}  // namespace
}  // namespace tessera
