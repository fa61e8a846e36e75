// Polynomial arithmetic and root isolation (polynomial.h).
#include "common/math/polynomial.h"

#include <algorithm>
#include <cmath>

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

// The root in (a, b), where p is monotone and p(a), p(b) have opposite signs: Newton steps
// that stay inside the bracket, bisection otherwise. The bracket shrinks every step, so it ends
// within an ulp or two of the root, or at a point where p rounds to zero.
double bracketed_root(const Polynomial& p, const Polynomial& dp, double a, double b, double fa) {
  double x = a + (b - a) / 2;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double fx = evaluate(p, x);
    if (fx == 0) return x;
    if (sign(fx) == sign(fa)) {
      a = x;
      fa = fx;
    } else {
      b = x;
    }
    const double dfx = evaluate(dp, x);
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

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  Polynomial r;
  r.degree = std::min(a.degree + b.degree, kMaxPolynomialDegree);
  for (int i = 0; i <= a.degree; ++i)
    for (int j = 0; j <= b.degree && i + j <= kMaxPolynomialDegree; ++j)
      r.c[i + j] += a.c[i] * b.c[j];
  return r;
}

Polynomial derivative(const Polynomial& p) {
  Polynomial r;
  r.degree = std::max(p.degree - 1, 0);
  for (int i = 1; i <= p.degree; ++i) r.c[i - 1] = i * p.c[i];
  return r;
}

double evaluate(const Polynomial& p, double x) {
  double v = p.c[p.degree];
  for (int i = p.degree - 1; i >= 0; --i) v = v * x + p.c[i];
  return v;
}

double evaluation_error(const Polynomial& p, double x) {
  const double ax = std::fabs(x);
  double v = std::fabs(p.c[p.degree]);
  for (int i = p.degree - 1; i >= 0; --i) v = v * ax + std::fabs(p.c[i]);
  return gamma_bound(2 * p.degree + 1) * v;
}

bool visit_real_roots(const Polynomial& p_in, double lo, double hi, RootVisitor visit) {
  Polynomial p = p_in;
  p.degree = effective_degree(p_in);
  if (p.degree == 0 || !(lo < hi)) return true;
  if (p.degree <= 2) {
    PolynomialRoot roots[kMaxPolynomialDegree];
    const int n = low_degree_roots(p, lo, hi, roots);
    for (int i = 0; i < n; ++i)
      if (!visit(roots[i])) return false;
    return true;
  }
  const Polynomial dp = derivative(p);

  // The split points, in order: lo, the derivative's roots (p's extrema and inflections) as they
  // are found, hi. Each piece between two of them is monotone and holds a root when p changes
  // sign across it. An interior split point whose value is lost in rounding is itself a root: p
  // touches zero there (or crosses it at an inflection); whether it touches is known once the
  // next split point's value is, so it is handed on then, before that piece's own root.
  double x_before = lo, value_before = evaluate(p, lo);
  bool zero_pending = false;
  double value_before_zero = 0;
  const auto split_at = [&](double x, double value, bool interior) {
    if (zero_pending) {
      zero_pending = false;
      if (!visit({x_before, sign(value_before_zero) * sign(value) > 0})) return false;
    }
    if (sign(value_before) * sign(value) < 0 &&
        !visit({bracketed_root(p, dp, x_before, x, value_before), false}))
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
    double value = evaluate(p, critical.x);
    if (std::fabs(value) <= evaluation_error(p, critical.x)) value = 0;
    return split_at(critical.x, value, true);
  };
  if (!visit_real_roots(dp, lo, hi, at_critical_point)) return false;
  return split_at(hi, evaluate(p, hi), false);
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
