// The algebraic surfaces' polynomials (algebraic_surfaces.h). Where a surface bounds a region,
// the polynomial is negative inside it, so the gradient points out.
#include "common/geometry/algebraic_surfaces.h"

namespace tessera {

namespace {

// x^2 + y^2 - z^2 - 1: one sheet around the z axis, waist radius 1 at z = 0.
constexpr Monomial kOneSheetHyperboloid[] = {{1, 2, 0, 0}, {1, 0, 2, 0}, {-1, 0, 0, 2}, {-1}};
// x^2 + y^2 - z^2 + 1: two sheets opening along +-z from their tips at z = +-1.
constexpr Monomial kTwoSheetHyperboloid[] = {{1, 2, 0, 0}, {1, 0, 2, 0}, {-1, 0, 0, 2}, {1}};
// x^2 + y^2 - 1: radius 1 around the z axis.
constexpr Monomial kEllipticCylinder[] = {{1, 2, 0, 0}, {1, 0, 2, 0}, {-1}};
// x^2 + y^2 - z^2: the double cone around the z axis, apex at the origin.
constexpr Monomial kEllipticCone[] = {{1, 2, 0, 0}, {1, 0, 2, 0}, {-1, 0, 0, 2}};
// x^2 + y^2 - z: a bowl opening along +z.
constexpr Monomial kEllipticParaboloid[] = {{1, 2, 0, 0}, {1, 0, 2, 0}, {-1, 0, 0, 1}};
// x^2 - y^2 - z: the saddle.
constexpr Monomial kHyperbolicParaboloid[] = {{1, 2, 0, 0}, {-1, 0, 2, 0}, {-1, 0, 0, 1}};
// Cayley's nodal cubic x^2 + y^2 + z^2 + 2xyz - 1: pinched at its four nodes (1, 1, -1),
// (1, -1, 1), (-1, 1, 1), (-1, -1, -1), with holes between the cones that leave them.
constexpr Monomial kPinchedSurfaceWithHoles[] = {
    {1, 2, 0, 0}, {1, 0, 2, 0}, {1, 0, 0, 2}, {2, 1, 1, 1}, {-1}};
// The "ding-dong" cubic x^2 + y^2 + z^3 - z^2: a drop-shaped lobe for z in [0, 1] pinched at
// the origin onto a flaring sheet below.
constexpr Monomial kPinchedSurfaceWithLobe[] = {
    {1, 2, 0, 0}, {1, 0, 2, 0}, {1, 0, 0, 3}, {-1, 0, 0, 2}};
// (x^2 - 1)^2 + (y^2 - 1)^2 + z^2 - 1.2: a ring of four lobes around (+-1, +-1, 0).
constexpr Monomial kFourLobes[] = {{1, 4, 0, 0},  {1, 0, 4, 0}, {-2, 2, 0, 0},
                                   {-2, 0, 2, 0}, {1, 0, 0, 2}, {0.8}};
// Steiner's Roman surface x^2 y^2 + y^2 z^2 + z^2 x^2 - xyz, within [-1/2, 1/2]^3. It holds the
// three axes (double lines, where the gradient vanishes).
constexpr Monomial kSteinersRomanSurface[] = {
    {1, 2, 2, 0}, {1, 0, 2, 2}, {1, 2, 0, 2}, {-1, 1, 1, 1}};
// The tooth surface x^4 + y^4 + z^4 - x^2 - y^2 - z^2: a cube with rounded, dented faces.
constexpr Monomial kToothCube[] = {{1, 4, 0, 0},  {1, 0, 4, 0},  {1, 0, 0, 4},
                                   {-1, 2, 0, 0}, {-1, 0, 2, 0}, {-1, 0, 0, 2}};

}  // namespace

ImplicitPolynomial algebraic_polynomial(AlgebraicKind kind) {
  switch (kind) {
    case AlgebraicKind::OneSheetHyperboloid:
      return kOneSheetHyperboloid;
    case AlgebraicKind::TwoSheetHyperboloid:
      return kTwoSheetHyperboloid;
    case AlgebraicKind::EllipticCylinder:
      return kEllipticCylinder;
    case AlgebraicKind::EllipticCone:
      return kEllipticCone;
    case AlgebraicKind::EllipticParaboloid:
      return kEllipticParaboloid;
    case AlgebraicKind::HyperbolicParaboloid:
      return kHyperbolicParaboloid;
    case AlgebraicKind::PinchedSurfaceWithHoles:
      return kPinchedSurfaceWithHoles;
    case AlgebraicKind::PinchedSurfaceWithLobe:
      return kPinchedSurfaceWithLobe;
    case AlgebraicKind::FourLobes:
      return kFourLobes;
    case AlgebraicKind::SteinersRomanSurface:
      return kSteinersRomanSurface;
    case AlgebraicKind::ToothCube:
      return kToothCube;
  }
  return {};
}

}  // namespace tessera
