// Polynomials in x, y and z (implicit_polynomial.h).
#include "common/math/implicit_polynomial.h"

#include <cmath>

#include "common/math/float_error.h"

namespace tessera {

namespace {

double power(double v, int n) {
  double r = 1;
  for (int i = 0; i < n; ++i) r *= v;
  return r;
}

double term(const Monomial& m, const Vec3& p) {
  return m.coefficient * power(p.x, m.px) * power(p.y, m.py) * power(p.z, m.pz);
}

}  // namespace

double evaluate(ImplicitPolynomial f, const Vec3& p) {
  double v = 0;
  for (const Monomial& m : f) v += term(m, p);
  return v;
}

double evaluation_error(ImplicitPolynomial f, const Vec3& p) {
  // Each term takes at most kMaxPolynomialDegree products, and the sum one addition per term.
  double magnitude = 0;
  for (const Monomial& m : f) magnitude += std::fabs(term(m, p));
  return gamma_bound(kMaxPolynomialDegree + static_cast<int>(f.size()) + 1) * magnitude;
}

Vec3 gradient(ImplicitPolynomial f, const Vec3& p) {
  Vec3 g;
  for (const Monomial& m : f) {
    if (m.px > 0)
      g.x += m.coefficient * m.px * power(p.x, m.px - 1) * power(p.y, m.py) * power(p.z, m.pz);
    if (m.py > 0)
      g.y += m.coefficient * m.py * power(p.x, m.px) * power(p.y, m.py - 1) * power(p.z, m.pz);
    if (m.pz > 0)
      g.z += m.coefficient * m.pz * power(p.x, m.px) * power(p.y, m.py) * power(p.z, m.pz - 1);
  }
  return g;
}

Polynomial along_line(ImplicitPolynomial f, const Vec3& o, const Vec3& u) {
  // Powers 0..4 of the three linear factors o_i + u_i s.
  Polynomial powers[3][kMaxPolynomialDegree + 1];
  for (int axis = 0; axis < 3; ++axis) {
    Polynomial linear;
    linear.degree = 1;
    linear.c[0] = o[axis];
    linear.c[1] = u[axis];
    powers[axis][0].c[0] = 1;
    for (int n = 1; n <= kMaxPolynomialDegree; ++n) powers[axis][n] = powers[axis][n - 1] * linear;
  }
  Polynomial sum;
  for (const Monomial& m : f)
    sum = sum + m.coefficient * (powers[0][m.px] * powers[1][m.py] * powers[2][m.pz]);
  return sum;
}

}  // namespace tessera
