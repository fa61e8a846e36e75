// Polynomial arithmetic and root isolation (polynomial.h).
#include "common/math/polynomial.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <utility>

#include "common/math/float_error.h"

namespace tessera {

namespace {

// The degree without leading zero coefficients, so that derivatives and root counts are right.
// Never above kMaxPolynomialDegree: GCC 12 at -O3 cannot otherwise bound the loops that read
// c[0..degree] and warns that `p` may be read uninitialized.
int effective_degree(const Polynomial& p) {
  int n = std::min(p.degree, kMaxPolynomialDegree);
  while (n > 0 && p.c[n] == 0) --n;
  return n;
}

int sign(double v) { return (v > 0) - (v < 0); }

// Horner's rule on c[0..n] (evaluate), inline so that the root search below, which passes
// a constant degree, gets it unrolled.
inline double horner(const double* c, int n, double x) {
  double v = c[n];
  for (int i = n - 1; i >= 0; --i) v = v * x + c[i];
  return v;
}

// c[0..n] at x (n <= 4) by Estrin's scheme: pairs of terms summed independently, a shorter
// chain of dependent operations than Horner's (about 20 cycles at degree 4 against 32). Each
// term is rounded at most 6 times at degree 4 (5 at 3), against Horner's 8 (6), so Horner's
// error bounds, which the quartic proofs assume of the search's values, hold for it too.
inline double estrin(const double* c, int n, double x) {
  const double x2 = x * x;
  switch (n) {
    case 4:
      return (c[0] + c[1] * x) + x2 * ((c[2] + c[3] * x) + c[4] * x2);
    case 3:
      return (c[0] + c[1] * x) + x2 * (c[2] + c[3] * x);
    case 2:
      return (c[0] + c[1] * x) + c[2] * x2;
    default:
      return horner(c, n, x);
  }
}

// evaluation_error() on c[0..n], inline for the same reason.
inline double horner_error(const double* c, int n, double x) {
  const double ax = std::fabs(x);
  double v = std::fabs(c[n]);
  for (int i = n - 1; i >= 0; --i) v = v * ax + std::fabs(c[i]);
  return gamma_bound(2 * n + 1) * v;
}

// Error-free transformations (Ogita, Rump and Oishi, "Accurate sum and dot product", SIAM J. Sci.
// Comput. 26(6), 2005): a + b = sum + error and a * b = product + error exactly, in plain
// additions and multiplications (no FMA: the build has none to rely on). Dekker's splitting
// overflows above about 2^996, making the error, and so the compensated value, NaN.
inline double two_sum(double a, double b, double& error) {
  const double sum = a + b, b_part = sum - a;
  error = (a - (sum - b_part)) + (b - b_part);
  return sum;
}
struct Split {
  double high, low;
};
inline Split split(double a) {
  const double scaled = 134217729.0 * a;  // 2^27 + 1
  const double high = scaled - (scaled - a);
  return {high, a - high};
}
inline double two_product(double a, const Split& b_split, double b, double& error) {
  const double product = a * b;
  const Split a_split = split(a);
  error = a_split.low * b_split.low -
          (((product - a_split.high * b_split.high) - a_split.low * b_split.high) -
           a_split.high * b_split.low);
  return product;
}

// Compensated Horner's rule (Graillat, Langlois and Louvet, "Compensated Horner scheme", 2005):
// c[0..n] at x as accurately as if evaluated in twice the precision and then rounded, so that a
// Newton step from within a few ulps of a root lands on the root correctly rounded (when the
// root's condition number is below about 1/eps).
inline double compensated_horner(const double* c, int n, double x) {
  const Split x_split = split(x);
  double v = c[n], v_error = 0;
  for (int i = n - 1; i >= 0; --i) {
    double product_error, sum_error;
    const double product = two_product(v, x_split, x, product_error);
    v = two_sum(product, c[i], sum_error);
    v_error = v_error * x + (product_error + sum_error);
  }
  return v + v_error;
}

// The root in (a, b), where the degree-N polynomial c is monotone and c(a) = fa, c(b) have
// opposite signs, neither zero (dc: its derivative): Newton steps that stay inside the bracket,
// bisection otherwise. The bracket shrinks every step, so it ends within an ulp or two of the
// root, or at a point where the polynomial rounds to zero.
template <int N>
double bracketed_root(const double* c, const double* dc, double a, double b, double fa) {
  // The sign at the bracket's left end, which stays the same as the end moves.
  const bool positive_at_a = fa > 0;
  double x = a + (b - a) / 2;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double fx = horner(c, N, x);
    if (fx == 0) return x;
    if (positive_at_a ? fx > 0 : fx < 0)
      a = x;
    else
      b = x;
    const double dfx = horner(dc, N - 1, x);
    // Converged: Newton's step is below the rounding of x. Tested before the step is kept in
    // the bracket: x may have just become an end of it, and a step smaller than its ulp, taken
    // for leaving the bracket, would otherwise restart a bisection that crawls back to x.
    if (dfx != 0 && std::fabs(fx / dfx) <= 2 * kMachineEpsilon * std::fabs(x)) {
      const double next = x - fx / dfx;
      return next > a && next < b ? next : x;
    }
    double next = dfx != 0 ? x - fx / dfx : a + (b - a) / 2;
    if (!(next > a && next < b)) next = a + (b - a) / 2;
    if (!(next > a && next < b)) return x;  // the bracket holds no double between its ends
    x = next;
  }
  return x;
}

// bracketed_root's root correctly rounded, for polished_root: Halley steps (cubic convergence, one
// division each like Newton's; about 4 evaluations from the bracket's midpoint where Newton's
// took 6) that stay inside the bracket, bisection otherwise, until Newton's step is below the
// rounding of x (or the polynomial rounds to zero there, or the bracket holds no double between
// its ends); then one Newton step on the compensated value at x. That last step makes the result
// the exact root of c correctly rounded (bench/polish_accuracy.cpp: every root of 166,181 logged
// and random brackets but the 6 that round to an end of theirs, outside the open bracket), whatever
// the start and path: so the steps before it may use Estrin's faster evaluation, and a different
// bracket no longer moves the root.
template <int N>
double correctly_rounded_root(const double* c, const double* dc, double a, double b, double fa) {
  double ddc[N - 1];
  for (int i = 1; i < N; ++i) ddc[i - 1] = i * dc[i];
  const double lo = a, hi = b;
  // x polished: one Newton step on the compensated value, kept in the whole bracket (a and b
  // come from plain values, whose signs may be wrong within their rounding of the root); a step
  // to or past an end of it means the root rounds to that end, so the double next to it. Where
  // Dekker's splitting overflows (coefficients or values above about 2^996) the compensated
  // value is NaN, and the step is taken on the plain value fx instead, a few ulps less exact.
  const auto polished = [&](double x, double fx, double dfx) {
    if (dfx == 0) return x;
    const double compensated = compensated_horner(c, N, x);
    const double next = x - (compensated == compensated ? compensated : fx) / dfx;
    if (next <= lo) return std::nextafter(lo, hi);
    if (next >= hi) return std::nextafter(hi, lo);
    return next == next ? next : x;  // NaN from an infinite fx or dfx
  };
  // The sign at the bracket's left end, which stays the same as the end moves.
  const bool positive_at_a = fa > 0;
  double x = a + (b - a) / 2;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double fx = estrin(c, N, x);
    const double dfx = estrin(dc, N - 1, x);
    if (fx == 0) return polished(x, fx, dfx);
    if (positive_at_a ? fx > 0 : fx < 0)
      a = x;
    else
      b = x;
    // Converged: Newton's step is below the rounding of x (|fx / dfx| <= 2 eps |x|, multiplied
    // out: no division besides Halley's). Tested before the step is kept in the bracket: x may
    // have just become an end of it, and a step smaller than its ulp, taken for leaving the
    // bracket, would otherwise restart a bisection that crawls back to x.
    if (std::fabs(fx) <= 2 * kMachineEpsilon * std::fabs(x * dfx)) return polished(x, fx, dfx);
    const double ddfx = estrin(ddc, N - 2, x);
    double next = x - 2 * fx * dfx / (2 * dfx * dfx - fx * ddfx);
    if (!(next > a && next < b)) next = a + (b - a) / 2;
    if (!(next > a && next < b)) return polished(x, fx, dfx);  // no double between the ends
    x = next;
  }
  return x;
}

// Degrees 1 and 2 in closed form (the cancellation-free q form), with the same contract as
// real_roots: accurate to a few ulps for separate roots, and cheap, which matters for the
// derivatives of cubics and quartics, solved several times per ray. A discriminant within its
// rounding of zero is one touching root.
int low_degree_roots(const Polynomial& p, double lo, double hi,
                     PolynomialRoot roots[kMaxPolynomialDegree]) {
  int count = 0;
  const auto keep = [&](double x, bool touching) {
    if (x > lo && x < hi) roots[count++] = {x, touching};
  };
  if (p.degree == 1) {
    keep(-p.c[0] / p.c[1], false);
    return count;
  }
  const double a = p.c[2], b = p.c[1], c = p.c[0];
  const double disc = b * b - 4 * a * c;
  const double disc_error = gamma_bound(3) * (b * b + 4 * std::fabs(a * c));
  if (disc < -disc_error) return 0;
  if (std::fabs(disc) <= disc_error) {
    keep(-b / (2 * a), true);
    return count;
  }
  const double q = -(b + std::copysign(std::sqrt(disc), b)) / 2;
  double x0 = q / a, x1 = c / q;
  if (x0 > x1) std::swap(x0, x1);
  keep(x0, false);
  keep(x1, false);
  return count;
}

// Roots of degree 1 or 2 in (lo, hi), ascending, handed to visit until it returns false.
template <class Visit>
bool visit_low_degree_roots(const Polynomial& p, double lo, double hi, const Visit& visit) {
  PolynomialRoot roots[kMaxPolynomialDegree];
  const int n = low_degree_roots(p, lo, hi, roots);
  for (int i = 0; i < n; ++i)
    if (!visit(roots[i])) return false;
  return true;
}

// The bracket test of a search that polishes every root: the derivatives' roots, and the
// roots of visit_real_roots without one.
constexpr auto kPolishEveryRoot = [](double, double) { return false; };

// visit_real_roots for the polynomial c[0..N] of degree exactly N >= 3 and lo < hi. The
// degree is a template argument so that the recursion through the derivatives, and the Horner
// loops, are compiled for each degree with no indirect calls between them.
template <int N, class Visit, class EndsSearch>
bool visit_roots(const double* c, double lo, double hi, const Visit& visit,
                 const EndsSearch& ends_search) {
  double dc[N];
  for (int i = 1; i <= N; ++i) dc[i - 1] = i * c[i];

  // The split points, in order: lo, the derivative's roots (p's extrema and inflections) as they
  // are found, hi. Each piece between two of them is monotone and holds a root when p changes
  // sign across it. An interior split point whose value is lost in rounding is itself a root: p
  // touches zero there (or crosses it at an inflection); whether it touches is known once the
  // next split point's value is, so it is handed on then, before that piece's own root.
  double x_before = lo, value_before = horner(c, N, lo);
  bool zero_pending = false;
  double value_before_zero = 0;
  const auto split_at = [&](double x, double value, bool interior) {
    if (zero_pending) {
      zero_pending = false;
      if (!visit(PolynomialRoot{x_before, sign(value_before_zero) * sign(value) > 0})) return false;
    }
    // bracketed_root's result lies in [x_before, x].
    if (sign(value_before) * sign(value) < 0 &&
        (ends_search(x_before, x) ||
         !visit(PolynomialRoot{bracketed_root<N>(c, dc, x_before, x, value_before), false})))
      return false;
    if (interior && value == 0) {
      zero_pending = true;
      value_before_zero = value_before;
    }
    x_before = x;
    value_before = value;
    return true;
  };
  const auto at_critical_point = [&](const PolynomialRoot& critical) {
    double value = horner(c, N, critical.x);
    if (std::fabs(value) <= horner_error(c, N, critical.x)) value = 0;
    return split_at(critical.x, value, true);
  };
  bool complete;
  if constexpr (N == 3) {
    Polynomial derivative_of_degree_2;
    derivative_of_degree_2.degree = 2;
    for (int i = 0; i <= 2; ++i) derivative_of_degree_2.c[i] = dc[i];
    complete = visit_low_degree_roots(derivative_of_degree_2, lo, hi, at_critical_point);
  } else {
    complete = visit_roots<N - 1>(dc, lo, hi, at_critical_point, kPolishEveryRoot);
  }
  if (!complete) return false;
  return split_at(hi, horner(c, N, hi), false);
}

}  // namespace

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  Polynomial r;
  r.degree = std::max(a.degree, b.degree);
  for (int i = 0; i <= r.degree; ++i) r.c[i] = a.c[i] + b.c[i];
  return r;
}

Polynomial operator*(double s, const Polynomial& p) {
  Polynomial r = p;
  for (int i = 0; i <= r.degree; ++i) r.c[i] *= s;
  return r;
}

namespace {

// a * b for a of degree A and b of degree B, each coefficient summed from zero in a register,
// its products in ascending powers of a: the same additions in the same order as accumulating
// a.c[i] * b.c[j] into r.c[i + j] for ascending i and j, so the same bits, but unrolled for the
// degrees, without the loops' bounds and a load and store of r.c per product (forming an
// algebraic surface's polynomial along a ray is mostly these products).
template <int A, int B>
Polynomial product(const Polynomial& a, const Polynomial& b) {
  constexpr int kDegree = std::min(A + B, kMaxPolynomialDegree);
  Polynomial r;
  r.degree = kDegree;
#pragma GCC unroll 5
  for (int k = 0; k <= kDegree; ++k) {
    double sum = 0;
#pragma GCC unroll 5
    for (int i = 0; i <= A; ++i)
      if (k - i >= 0 && k - i <= B) sum += a.c[i] * b.c[k - i];
    r.c[k] = sum;
  }
  return r;
}

using Product = Polynomial (*)(const Polynomial&, const Polynomial&);

template <int... B>
constexpr auto products_of_degree(auto a_degree, std::integer_sequence<int, B...>) {
  return std::array<Product, sizeof...(B)>{product<decltype(a_degree)::value, B>...};
}
template <int... A>
constexpr auto product_table(std::integer_sequence<int, A...>) {
  return std::array{
      products_of_degree(std::integral_constant<int, A>{},
                         std::make_integer_sequence<int, kMaxPolynomialDegree + 1>{})...};
}
// kProducts[A][B]: product<A, B>.
constexpr auto kProducts =
    product_table(std::make_integer_sequence<int, kMaxPolynomialDegree + 1>{});

}  // namespace

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  return kProducts[a.degree][b.degree](a, b);
}

Polynomial derivative(const Polynomial& p) {
  Polynomial r;
  r.degree = std::max(p.degree - 1, 0);
  for (int i = 1; i <= p.degree; ++i) r.c[i - 1] = i * p.c[i];
  return r;
}

double evaluate(const Polynomial& p, double x) { return horner(p.c, p.degree, x); }

double evaluation_error(const Polynomial& p, double x) { return horner_error(p.c, p.degree, x); }

namespace {

template <class EndsSearch>
bool visit_roots_of_any_degree(const Polynomial& p_in, double lo, double hi, RootVisitor visit,
                               const EndsSearch& ends_search) {
  Polynomial p = p_in;
  p.degree = effective_degree(p_in);
  if (p.degree == 0 || !(lo < hi)) return true;
  if (p.degree == 3) return visit_roots<3>(p.c, lo, hi, visit, ends_search);
  if (p.degree == 4) return visit_roots<4>(p.c, lo, hi, visit, ends_search);
  return visit_low_degree_roots(p, lo, hi, visit);
}

}  // namespace

bool visit_real_roots(const Polynomial& p, double lo, double hi, RootVisitor visit) {
  return visit_roots_of_any_degree(p, lo, hi, visit, kPolishEveryRoot);
}

bool visit_real_roots(const Polynomial& p, double lo, double hi, RootVisitor visit,
                      BracketTest ends_search) {
  return visit_roots_of_any_degree(p, lo, hi, visit, ends_search);
}

double polished_root(const Polynomial& p, double a, double b) {
  double dc[kMaxPolynomialDegree];
  for (int i = 1; i <= p.degree; ++i) dc[i - 1] = i * p.c[i];
  const double fa = horner(p.c, p.degree, a);
  return p.degree == 3 ? correctly_rounded_root<3>(p.c, dc, a, b, fa)
                       : correctly_rounded_root<4>(p.c, dc, a, b, fa);
}

int real_roots(const Polynomial& p, double lo, double hi,
               PolynomialRoot roots[kMaxPolynomialDegree]) {
  int count = 0;
  const auto keep = [&](const PolynomialRoot& root) {
    roots[count++] = root;
    return true;
  };
  visit_real_roots(p, lo, hi, keep);
  return count;
}

}  // namespace tessera
