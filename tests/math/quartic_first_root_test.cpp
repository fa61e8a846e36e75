// The first-root proof (common/math/quartic_first_root.h) against the root search it stands in
// for: whenever it gives a bracket, the search's first root lies in it, and the root polished in
// the bracket is the search's up to the rounding of the polish: both within what the quartic's
// rounding lets a polish resolve of the exact root.
#include "common/math/quartic_first_root.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "common/math/polynomial.h"
#include "tests/math/quartic_factors.h"

namespace tessera {
namespace {

using testing::quadratic_about;
using testing::random_gap;
using testing::random_pair_of_quadratics;

// The root of p (double coefficients, evaluated exactly enough in long double) nearest x.
long double reference_root(const Polynomial& p, double x) {
  long double r = x;
  for (int i = 0; i < 4; ++i) {
    long double v = p.c[4], dv = 0;
    for (int k = 3; k >= 0; --k) {
      dv = dv * r + v;
      v = v * r + p.c[k];
    }
    if (dv == 0) break;
    r -= v / dv;
  }
  return r;
}

// Asks the proof for a bracket of p's first root on (lo, m); where it gives one, checks it against
// the search on (lo, hi) and the polish in it against the search's and the exact root.
struct Checker {
  int bracketed = 0, differ = 0;
  void operator()(const Polynomial& p, double lo, double m, double hi) {
    const std::optional<double> end = quartic_first_root_bracket(p, lo, m);
    if (!end) return;
    ++bracketed;
    ASSERT_GT(*end, lo);
    ASSERT_LE(*end, m);
    PolynomialRoot roots[kMaxPolynomialDegree];
    const int found = real_roots(p, lo, hi, roots);
    const auto describe = [&] {
      char text[400];
      std::snprintf(text, sizeof text,
                    "%.17g x^4 + %.17g x^3 + %.17g x^2 + %.17g x + %.17g on (%.17g, %.17g), "
                    "bracket end %.17g",
                    p.c[4], p.c[3], p.c[2], p.c[1], p.c[0], lo, hi, *end);
      return std::string(text);
    };
    ASSERT_GE(found, 1) << describe();
    ASSERT_FALSE(roots[0].touching) << describe();
    ASSERT_LT(roots[0].x, *end) << describe();
    const double polished = polished_root(p, lo, *end);
    // Both within what p's rounding lets a polish resolve: Horner's error over the slope, and a
    // few ulps.
    const long double reference = reference_root(p, roots[0].x);
    const double resolution =
        4 * evaluation_error(p, roots[0].x) / std::fabs(evaluate(derivative(p), roots[0].x)) +
        4 * std::fabs(roots[0].x) * 0x1p-52;
    ASSERT_LE(std::fabs(roots[0].x - reference), resolution) << describe();
    ASSERT_LE(std::fabs(polished - reference), resolution) << describe();
    differ += polished != roots[0].x;
  }
};

// Two families of quartics, on intervals (lo, hi) with m, where the proof is asked to show the
// quartic negative, anywhere in them: pairs of quadratics with roots close together, touching or
// just apart, or with none, anywhere around the interval; and, as a ray entering a tube has, a
// first root in the first half of the interval, the second after it by a gap from 10^-16 to 1 (a
// grazing ray's pair), two more anywhere or none, with m between the first two or beyond.
TEST(QuarticFirstRoot, BracketsTheSearchsFirstRoot) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  Checker anywhere, entering;
  for (int i = 0; i < 300000; ++i) {
    const double lo = -3 * unit(rng), hi = lo + 5 * unit(rng) + 1e-3;
    const auto place = [&] { return lo - 1 + (hi - lo + 2) * unit(rng); };
    anywhere(random_pair_of_quadratics(rng, place), lo, lo + (hi - lo) * unit(rng), hi);
    if (HasFatalFailure()) return;

    const double first = lo + (hi - lo) / 2 * unit(rng);
    const double gap = std::pow(10.0, -16 * unit(rng));
    Polynomial p = quadratic_about(first + gap / 2, -gap * gap / 4) *
                   quadratic_about(place(), random_gap(rng));
    if (evaluate(p, lo) < 0) p = -1.0 * p;
    entering(p, lo, first + (hi - first) * unit(rng), hi);
    if (HasFatalFailure()) return;
  }
  std::printf("bracketed %d and %d of 300000 each, the polish differing from the search's in %d\n",
              anywhere.bracketed, entering.bracketed, anywhere.differ + entering.differ);
  EXPECT_GT(anywhere.bracketed, 1000);
  EXPECT_GT(entering.bracketed, 3000);
}

}  // namespace
}  // namespace tessera
