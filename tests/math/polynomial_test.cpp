// Root isolation (common/math/polynomial.h) against roots constructed exactly.
#include "common/math/polynomial.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <random>
#include <utility>
#include <vector>

#include "common/math/float_error.h"

namespace tessera {
namespace {

// The monic polynomial with the given roots.
Polynomial from_roots(std::initializer_list<double> roots) {
  Polynomial p;
  p.c[0] = 1;
  for (double r : roots) {
    Polynomial factor;
    factor.degree = 1;
    factor.c[0] = -r;
    factor.c[1] = 1;
    p = p * factor;
  }
  return p;
}

TEST(Polynomial, Arithmetic) {
  const Polynomial p = from_roots({1, 2});  // x^2 - 3x + 2
  EXPECT_EQ(p.degree, 2);
  EXPECT_EQ(p.c[0], 2);
  EXPECT_EQ(p.c[1], -3);
  EXPECT_EQ(p.c[2], 1);
  EXPECT_EQ(evaluate(p, 3), 2);
  const Polynomial dp = derivative(p);
  EXPECT_EQ(dp.degree, 1);
  EXPECT_EQ(dp.c[0], -3);
  EXPECT_EQ(dp.c[1], 2);
  const Polynomial sum = p + 2 * dp;
  EXPECT_EQ(sum.c[0], -4);
  EXPECT_EQ(sum.c[1], 1);
  EXPECT_GT(evaluation_error(p, 3), 0);
  EXPECT_LT(evaluation_error(p, 3), 1e-13);
}

// The product's coefficients bit for bit as accumulating a.c[i] * b.c[j] into r.c[i + j] from
// zero, for ascending i then j (the roots searched for depend on every bit), for each pair of
// degrees, truncated above kMaxPolynomialDegree, with signed zeros and wide magnitudes.
TEST(Polynomial, ProductSumsInTheOrderOfAscendingPowers) {
  std::mt19937_64 rng(28);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto bits = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  for (int trial = 0; trial < 2000; ++trial) {
    Polynomial a, b;
    a.degree = trial % (kMaxPolynomialDegree + 1);
    b.degree = trial / (kMaxPolynomialDegree + 1) % (kMaxPolynomialDegree + 1);
    for (Polynomial* p : {&a, &b})
      for (int i = 0; i <= p->degree; ++i)
        p->c[i] = trial % 7 == 0 && i % 2 ? -0.0 : unit(rng) * std::pow(10, 8 * unit(rng));
    Polynomial expected;
    expected.degree = std::min(a.degree + b.degree, kMaxPolynomialDegree);
    for (int i = 0; i <= a.degree; ++i)
      for (int j = 0; j <= b.degree && i + j <= kMaxPolynomialDegree; ++j)
        expected.c[i + j] += a.c[i] * b.c[j];
    const Polynomial r = a * b;
    ASSERT_EQ(r.degree, expected.degree);
    for (int k = 0; k <= kMaxPolynomialDegree; ++k)
      ASSERT_EQ(bits(r.c[k]), bits(expected.c[k])) << trial << " c" << k;
  }
}

TEST(Polynomial, SimpleRootsOfEachDegree) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  ASSERT_EQ(real_roots(from_roots({0.5}), -10, 10, roots), 1);
  EXPECT_EQ(roots[0].x, 0.5);
  ASSERT_EQ(real_roots(from_roots({-3, 0.25}), -10, 10, roots), 2);
  EXPECT_EQ(roots[0].x, -3);
  EXPECT_EQ(roots[1].x, 0.25);
  ASSERT_EQ(real_roots(from_roots({-1, 2, 7}), -10, 10, roots), 3);
  EXPECT_DOUBLE_EQ(roots[2].x, 7);
  ASSERT_EQ(real_roots(from_roots({-1.5, -0.5, 0.5, 1.5}), -10, 10, roots), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(roots[i].x, -1.5 + i, 1e-15);
    EXPECT_FALSE(roots[i].touching);
  }
}

TEST(Polynomial, OnlyRootsInsideTheOpenInterval) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  const Polynomial p = from_roots({-1.5, -0.5, 0.5, 1.5});
  ASSERT_EQ(real_roots(p, 0, 10, roots), 2);
  EXPECT_NEAR(roots[0].x, 0.5, 1e-15);
  EXPECT_EQ(real_roots(p, 0.5, 1.5, roots), 0);  // both ends excluded
  EXPECT_EQ(real_roots(p, 2, 1, roots), 0);      // empty interval
}

TEST(Polynomial, NoRealRoots) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  Polynomial p;  // x^4 + x^2 + 1
  p.degree = 4;
  p.c[4] = 1;
  p.c[2] = 1;
  p.c[0] = 1;
  EXPECT_EQ(real_roots(p, -100, 100, roots), 0);
  EXPECT_EQ(real_roots(Polynomial{}, -1, 1, roots), 0);  // zero everywhere: none isolated
}

TEST(Polynomial, LeadingZerosLowerTheDegree) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  Polynomial p = from_roots({2, 3});
  p.degree = 4;  // c[3] = c[4] = 0
  ASSERT_EQ(real_roots(p, -10, 10, roots), 2);
  EXPECT_DOUBLE_EQ(roots[0].x, 2);
  EXPECT_DOUBLE_EQ(roots[1].x, 3);
}

TEST(Polynomial, DoubleRootsAreOneTouchingRoot) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  ASSERT_EQ(real_roots(from_roots({1, 1}), -10, 10, roots), 1);
  EXPECT_EQ(roots[0].x, 1);
  EXPECT_TRUE(roots[0].touching);
  ASSERT_EQ(real_roots(from_roots({-2, 0.3, 0.3, 4}), -10, 10, roots), 3);
  EXPECT_NEAR(roots[1].x, 0.3, 1e-8);
  EXPECT_TRUE(roots[1].touching);
  EXPECT_FALSE(roots[0].touching);
  // A quadruple root: x^4.
  ASSERT_EQ(real_roots(from_roots({0, 0, 0, 0}), -1, 1, roots), 1);
  EXPECT_EQ(roots[0].x, 0);
  EXPECT_TRUE(roots[0].touching);
  // A triple root crosses zero: not touching.
  ASSERT_EQ(real_roots(from_roots({0.5, 0.5, 0.5}), -1, 1, roots), 1);
  EXPECT_NEAR(roots[0].x, 0.5, 1e-5);
  EXPECT_FALSE(roots[0].touching);
}

// A visitor that ends the search gets no further root, and the roots it does get are the
// ones real_roots lists, touching flags included, in the same order.
TEST(Polynomial, VisitingStopsWhereTheVisitorSays) {
  PolynomialRoot all[kMaxPolynomialDegree];
  for (const Polynomial& p : {from_roots({-1.5, -0.5, 0.5, 1.5}), from_roots({-2, 0.3, 0.3, 4}),
                              from_roots({0.25, 0.25, 3}), from_roots({-1, 2, 7})}) {
    const int n = real_roots(p, -10, 10, all);
    ASSERT_GT(n, 1);
    for (int wanted = 1; wanted <= n; ++wanted) {
      std::vector<PolynomialRoot> seen;
      const auto take = [&](const PolynomialRoot& root) {
        seen.push_back(root);
        return static_cast<int>(seen.size()) < wanted;
      };
      EXPECT_EQ(visit_real_roots(p, -10, 10, take), false);
      ASSERT_EQ(static_cast<int>(seen.size()), wanted);
      for (int i = 0; i < wanted; ++i) {
        EXPECT_EQ(seen[i].x, all[i].x);
        EXPECT_EQ(seen[i].touching, all[i].touching);
      }
    }
    // A visitor that never stops sees them all, and the search says it ran to the end.
    int count = 0;
    const auto every = [&](const PolynomialRoot&) { return ++count > 0; };
    EXPECT_TRUE(visit_real_roots(p, -10, 10, every));
    EXPECT_EQ(count, n);
  }
}

// The bracket test is asked about each simple root before it is polished, with a bracket that
// holds the polished root; it is not asked about touching roots, and answering true ends the
// search there without the root.
TEST(Polynomial, BracketTestSeesEachSimpleRootsBracketFirst) {
  for (const Polynomial& p : {from_roots({-1.5, -0.5, 0.5, 1.5}), from_roots({-2, 0.3, 0.3, 4}),
                              from_roots({0.25, 0.25, 3}), from_roots({-1, 2, 7})}) {
    std::vector<PolynomialRoot> seen;
    std::vector<std::pair<double, double>> brackets;
    const auto take = [&](const PolynomialRoot& root) {
      seen.push_back(root);
      return true;
    };
    const auto record = [&](double a, double b) {
      brackets.emplace_back(a, b);
      return false;
    };
    EXPECT_TRUE(visit_real_roots(p, -10, 10, take, record));
    std::vector<PolynomialRoot> simple;
    for (const PolynomialRoot& root : seen)
      if (!root.touching) simple.push_back(root);
    ASSERT_EQ(brackets.size(), simple.size());
    for (std::size_t i = 0; i < simple.size(); ++i) {
      EXPECT_LE(brackets[i].first, simple[i].x);
      EXPECT_GE(brackets[i].second, simple[i].x);
    }
    // Ending at the first bracket: no root visited, nor any bracket after it.
    seen.clear();
    int asked = 0;
    const auto first_ends = [&](double, double) { return ++asked > 0; };
    EXPECT_FALSE(visit_real_roots(p, -10, 10, take, first_ends));
    EXPECT_EQ(asked, 1);
    for (const PolynomialRoot& root : seen) EXPECT_TRUE(root.touching);
  }
}

// Close pairs x = c +- w: resolved to their conditioning, about eps / w, down to the point
// where the pair merges into one touching root.
TEST(Polynomial, NearDoubleRoots) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  for (double w : {1e-2, 1e-4, 1e-6}) {
    SCOPED_TRACE(w);
    const Polynomial p = from_roots({0.7 - w, 0.7 + w, -3, 5});
    ASSERT_EQ(real_roots(p, -10, 10, roots), 4);
    EXPECT_NEAR(roots[1].x, 0.7 - w, 1e-15 / w);
    EXPECT_NEAR(roots[2].x, 0.7 + w, 1e-15 / w);
  }
  const Polynomial p = from_roots({0.7 - 1e-12, 0.7 + 1e-12, -3, 5});
  const int n = real_roots(p, -10, 10, roots);
  ASSERT_TRUE(n == 3 || n == 4);
  EXPECT_NEAR(roots[1].x, 0.7, 1e-7);
}

// Ill-conditioned quartics of the kinds solver papers test (Flocke, "Algorithm 954", ACM TOMS
// 41(4), 2015: roots of widely different magnitudes, clusters, multiple roots), built from known
// roots whose products are exact in double, so the reference is the exact root, not another
// solver. Each simple root must come out to a relative error within the conditioning bound
// (Horner's rounding over the slope) and within a stated figure.
struct KnownQuartic {
  const char* name;
  double roots[4];        // ascending
  double leading;         // the polynomial is leading * prod (x - root)
  double relative_error;  // stated bound on |x - root| / |root| for the simple roots
};

constexpr double k2m10 = 1.0 / 1024;
constexpr KnownQuartic kKnownQuartics[] = {
    {"spread 2^-10..2^20", {k2m10, 1, 1024, 1 << 20}, 1, 1e-15},
    {"spread 2^-20..2^20", {1.0 / (1 << 20), 1.0 / 32, 32, 1 << 20}, 1, 1e-15},
    {"mixed signs", {-(1 << 20), -k2m10, 1.0 / 32, 1 << 15}, 1, 1e-15},
    {"tiny leading coefficient", {-3, 0.25, 1.5, 8}, 1e-12, 1e-15},
    {"huge leading coefficient", {-3, 0.25, 1.5, 8}, 1e12, 1e-15},
    {"cluster of four 2^-10 apart", {1, 1 + k2m10, 1 + 2 * k2m10, 1 + 3 * k2m10}, 1, 2e-7},
    {"cluster of two near 2^20", {-1, 2, 1 << 20, (1 << 20) + 1}, 1, 1e-10},
};

TEST(Polynomial, KnownIllConditionedQuartics) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  for (const KnownQuartic& q : kKnownQuartics) {
    SCOPED_TRACE(q.name);
    const Polynomial p = q.leading * from_roots({q.roots[0], q.roots[1], q.roots[2], q.roots[3]});
    ASSERT_EQ(real_roots(p, -1e7, 1e7, roots), 4);
    for (int k = 0; k < 4; ++k) {
      const double exact = q.roots[k];
      const double relative = std::fabs(roots[k].x - exact) / std::fabs(exact);
      const double conditioning =
          evaluation_error(p, exact) / std::fabs(evaluate(derivative(p), exact)) / std::fabs(exact);
      EXPECT_LE(relative, 2 * conditioning + 4 * kMachineEpsilon) << "root " << exact;
      EXPECT_LE(relative, q.relative_error) << "root " << exact;
      EXPECT_FALSE(roots[k].touching);
    }
  }
}

// Double roots among simple ones, exact coefficients: one touching root each, within the
// square root of the rounding (a double root is only that well defined), and the simple roots
// as accurate as ever.
TEST(Polynomial, KnownDoubleRoots) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  struct Case {
    double roots[4];
    int count;
    double expected[3];
    bool touching[3];
  };
  const Case cases[] = {
      {{1, 1, 2, 2}, 2, {1, 2}, {true, true}},
      {{-1, 0.5, 3, 3}, 3, {-1, 0.5, 3}, {false, false, true}},
      {{1, 2, 1024, 1024}, 3, {1, 2, 1024}, {false, false, true}},
      {{k2m10, k2m10, 1 << 20, 1 << 20}, 2, {k2m10, 1 << 20}, {true, true}},
  };
  for (const Case& c : cases) {
    const Polynomial p = from_roots({c.roots[0], c.roots[1], c.roots[2], c.roots[3]});
    SCOPED_TRACE(c.expected[c.count - 1]);
    ASSERT_EQ(real_roots(p, -1e7, 1e7, roots), c.count);
    for (int k = 0; k < c.count; ++k) {
      const double exact = c.expected[k];
      const double tolerance = c.touching[k] ? 1e-7 : 1e-15;
      EXPECT_LE(std::fabs(roots[k].x - exact), tolerance * std::fabs(exact)) << exact;
      EXPECT_EQ(roots[k].touching, c.touching[k]) << exact;
    }
  }
}

// The root of p near x, by Newton's method in long double on p's own (rounded) coefficients.
long double reference_root(const Polynomial& p, long double x) {
  for (int i = 0; i < 50; ++i) {
    long double v = p.c[p.degree], dv = 0;
    for (int k = p.degree - 1; k >= 0; --k) {
      dv = dv * x + v;
      v = v * x + p.c[k];
    }
    x -= v / dv;
  }
  return x;
}

// Random separated roots: every one found, as accurately as p's rounding allows (its
// evaluation error over its slope).
TEST(Polynomial, RandomQuartics) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-10, 10);
  PolynomialRoot roots[kMaxPolynomialDegree];
  for (int i = 0; i < 2000; ++i) {
    double r[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
    std::sort(r, r + 4);
    if (r[1] - r[0] < 1e-3 || r[2] - r[1] < 1e-3 || r[3] - r[2] < 1e-3) continue;
    const double scale = std::pow(10, unit(rng) / 2);
    const Polynomial p = scale * from_roots({r[0], r[1], r[2], r[3]});
    ASSERT_EQ(real_roots(p, -11, 11, roots), 4) << i;
    for (int k = 0; k < 4; ++k) {
      const double reference = static_cast<double>(reference_root(p, r[k]));
      const double slope = std::fabs(evaluate(derivative(p), reference));
      const double tolerance = 2 * evaluation_error(p, reference) / slope + 1e-15 * 16;
      EXPECT_NEAR(roots[k].x, reference, tolerance) << i;
      EXPECT_NEAR(roots[k].x, r[k], 1e-8) << i;
    }
  }
}

// polished_root gives the exact root of p's (double) coefficients correctly rounded, the
// reference found by Newton's method in quadruple precision: its polish ends with a Newton step
// on the compensated value of p. Roots far from double ones (condition below about 1/eps), so
// that every one can be, each in a bracket of +-0.01 on which p is monotone. The search's own
// polish (visit_real_roots), a last Newton step on the plain value, misses about half of them.
TEST(Polynomial, PolishedRootsAreCorrectlyRounded) {
  __extension__ using Quad = __float128;
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> unit(-10, 10);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const int degree = 3 + i % 2;
    double r[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
    std::sort(r, r + 4);  // all four: GCC's -O3 -Warray-bounds misreads a sort of r[0..degree)
    bool separate = true;
    for (int k = 1; k < degree; ++k) separate &= r[k] - r[k - 1] > 0.1;
    if (!separate) continue;
    const Polynomial p =
        std::pow(10, unit(rng) / 2) *
        (degree == 3 ? from_roots({r[0], r[1], r[2]}) : from_roots({r[0], r[1], r[2], r[3]}));
    const Polynomial dp = derivative(p);
    for (int k = 0; k < degree; ++k) {
      const double a = r[k] - 0.01, b = r[k] + 0.01;
      // Monotone with a sign change on [a, b] (a critical point this near a root is rare).
      if (!(evaluate(p, a) * evaluate(p, b) < 0 && evaluate(dp, a) * evaluate(dp, b) > 0)) continue;
      Quad x = r[k];
      for (int step = 0; step < 4; ++step) {
        Quad v = p.c[p.degree], dv = 0;
        for (int j = p.degree - 1; j >= 0; --j) {
          dv = dv * x + v;
          v = v * x + p.c[j];
        }
        x -= v / dv;
      }
      EXPECT_EQ(polished_root(p, a, b), static_cast<double>(x)) << i << " root " << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 4000);
}

}  // namespace
}  // namespace tessera
