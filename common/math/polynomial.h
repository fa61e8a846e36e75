// Univariate polynomials of degree up to 4 and their real roots, for ray/surface intersection
// (torus, algebraic surfaces).
//
// Cubics and quartics are solved without closed forms or Sturm sequences: the roots of the
// derivative (found the same way, recursively, down to a quadratic solved directly) split the
// interval into pieces on which the polynomial is monotone, so each piece holds at most one
// root, found by safeguarded Newton iteration inside its sign-change bracket. Closed-form
// cubics and quartics lose most of their digits near multiple roots;
// bracketing keeps every root that the polynomial's rounding allows to be resolved, and
// reports an extremum whose value is within that rounding as one touching (double) root, as a
// ray grazing a surface needs.
#pragma once

namespace tessera {

inline constexpr int kMaxPolynomialDegree = 4;

// c[0] + c[1] x + ... + c[degree] x^degree, lowest degree first.
struct Polynomial {
  double c[kMaxPolynomialDegree + 1] = {};
  int degree = 0;
};

Polynomial operator+(const Polynomial& a, const Polynomial& b);
Polynomial operator*(double s, const Polynomial& p);
// The product; its degree must not exceed kMaxPolynomialDegree (nor a's or b's be negative: the
// product is unrolled for each pair of degrees and looked up by them).
Polynomial operator*(const Polynomial& a, const Polynomial& b);
Polynomial derivative(const Polynomial& p);

double evaluate(const Polynomial& p, double x);
// A bound on the rounding error of evaluate(p, x) (Horner's rule: gamma(2n) sum |c_i| |x|^i).
double evaluation_error(const Polynomial& p, double x);

struct PolynomialRoot {
  double x = 0;
  bool touching = false;  // the polynomial does not change sign there (even multiplicity)
};

// A non-owning reference to a callable, so that callers need no templates and no allocation;
// the search itself, through the derivatives, is compiled for each degree and calls it only to
// hand over a root or ask about a bracket.
template <class Signature>
class CallableRef;
template <class R, class... Args>
class CallableRef<R(Args...)> {
 public:
  template <class F>
  CallableRef(const F& f)  // NOLINT(google-explicit-constructor): lambdas convert where passed
      : context_(&f), call_([](const void* c, Args... args) -> R {
          return (*static_cast<const F*>(c))(args...);
        }) {}
  R operator()(Args... args) const { return call_(context_, args...); }

 private:
  const void* context_;
  R (*call_)(const void*, Args...);
};

// Receives roots one at a time; returns false to end the search.
using RootVisitor = CallableRef<bool(const PolynomialRoot&)>;
// Asked about a simple root's sign-change bracket [a, b] before the root is polished in it;
// returns true to end the search there, the root neither polished nor visited.
using BracketTest = CallableRef<bool(double a, double b)>;

// The real roots of p in the open interval (lo, hi), ascending, each handed to `visit` as soon
// as it is found; returns false when `visit` ended the search. Roots beyond the one that ends
// it are never computed, nor are the critical points beyond it, so asking for the first root
// costs less than asking for all. lo and hi must be finite. A polynomial that is zero
// everywhere has no isolated roots, and none are reported.
bool visit_real_roots(const Polynomial& p, double lo, double hi, RootVisitor visit);
// The same search, for a caller that needs only to know whether an acceptable root exists (is a
// shadow ray blocked?): before polishing a simple root, it asks ends_search(a, b) about the
// bracket [a, b] that the polished root would lie in, on the same split points as the search
// above, so a caller that can accept every point of the bracket answers what it would have
// answered from the root, without polishing it. Returns false when visit or ends_search ended
// the search. Roots of degree 1 and 2 polynomials, found in closed form, are only visited.
bool visit_real_roots(const Polynomial& p, double lo, double hi, RootVisitor visit,
                      BracketTest ends_search);

// The root in (a, b) of p (degree 3 or 4), monotone on [a, b] with values of opposite signs at a
// and b: the exact root of p's coefficients correctly rounded (a last Newton step on p's
// compensated value), where visit_real_roots's own polish, whose last step the quartic proofs
// bound by an ulp, may be a few ulps off (more where the root is ill-conditioned).
double polished_root(const Polynomial& p, double a, double b);

// Every real root of p in (lo, hi), ascending, as visit_real_roots finds them; returns how many
// (at most p.degree).
int real_roots(const Polynomial& p, double lo, double hi,
               PolynomialRoot roots[kMaxPolynomialDegree]);

}  // namespace tessera
