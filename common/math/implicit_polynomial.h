// Polynomials in x, y and z, held as their monomials: the implicit functions of the algebraic
// surfaces, evaluated at points and restricted to rays.
#pragma once

#include <span>

#include "common/math/polynomial.h"
#include "common/math/vec3.h"

namespace tessera {

// coefficient * x^px * y^py * z^pz
struct Monomial {
  double coefficient = 0;
  int px = 0, py = 0, pz = 0;
};

// A polynomial of total degree at most kMaxPolynomialDegree.
using ImplicitPolynomial = std::span<const Monomial>;

double evaluate(ImplicitPolynomial f, const Vec3& p);
// A bound on the rounding error of evaluate(f, p).
double evaluation_error(ImplicitPolynomial f, const Vec3& p);
Vec3 gradient(ImplicitPolynomial f, const Vec3& p);

// f(o + s u) as a polynomial in s, expanded monomial by monomial: its coefficients are the
// exact ones up to their own rounding (fitting through samples would not be).
Polynomial along_line(ImplicitPolynomial f, const Vec3& o, const Vec3& u);

}  // namespace tessera
