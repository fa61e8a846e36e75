// The implicit polynomials of the algebraic surfaces of §3.3.6. The manual names the surfaces
// but gives no equations; these are the usual forms of each (docs/SDL.md §4.2 lists them), in
// object space, before the CT. The surface is where the polynomial is zero, and its gradient
// is the normal.
#pragma once

#include "common/math/implicit_polynomial.h"
#include "common/scene/shape.h"

namespace tessera {

ImplicitPolynomial algebraic_polynomial(AlgebraicKind kind);

}  // namespace tessera
