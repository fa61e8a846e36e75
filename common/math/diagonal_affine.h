// Affine transforms whose linear part is diagonal: translate * scale, the form of most SDL and
// VRML instances (the demo's floor and balls, the tori's floor). Kept as two vectors, each
// component costs one product instead of three, and the components lie side by side for the
// vector unit.
//
// Why the results can equal Affine's bit for bit: the off-diagonal entries are exact zeros, and
// with finite inputs a product by zero is +0 or -0, and adding a signed zero to a non-zero value
// changes nothing. Sums and products of values that agree up to the signs of zeros agree up to
// the sign of a zero result (fabs makes them equal). So a result of these functions whose
// components are all non-zero and finite (`same_as_full`) is exactly what Affine's product of
// the same inputs gives; a zero component may differ in its sign and asks for the full product.
// Non-finite inputs need no test of their own: each input component reaches an output through a
// non-zero, finite diagonal entry, so an infinite or NaN input leaves that output non-finite.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "common/math/affine.h"
#include "common/math/float_error.h"
#include "common/math/vec3.h"

namespace tessera {

struct DiagonalAffine {
  Vec3 scale;   // the diagonal of the linear part
  Vec3 offset;  // the translation

  // The transform as such, or nullopt when an entry off the diagonal is not zero.
  static std::optional<DiagonalAffine> of(const Affine& a) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (r != c && a.m[r][c] != 0) return std::nullopt;
    return DiagonalAffine{{a.m[0][0], a.m[1][1], a.m[2][2]}, {a.m[0][3], a.m[1][3], a.m[2][3]}};
  }

  // Affine::apply_point.
  Vec3 apply_point(const Vec3& p) const { return mul(scale, p) + offset; }
  // Affine::apply_vector, and Affine::apply_transpose (a diagonal is its own transpose).
  Vec3 apply_vector(const Vec3& v) const { return mul(scale, v); }
  // |lin(a)| v, as instance.cpp's abs_linear.
  Vec3 abs_linear(const Vec3& v) const { return mul(abs(scale), v); }
  // Affine::point_error.
  Vec3 point_error(const Vec3& p, const Vec3& p_error) const {
    const Vec3 magnitude = abs(mul(scale, p)) + abs(offset);
    return magnitude * gamma_bound(3) + abs_linear(p_error) * (gamma_bound(3) + 1);
  }
};

// Whether results of DiagonalAffine certainly equal Affine's (see the top of this file): when
// the product of their components is non-zero and finite, so is each component. One test for
// all; a product that underflows or overflows refuses results that were fine (components far
// below 1e-50 or above 1e50 for two vectors), which costs only the full products.
inline bool same_as_full(const Vec3& a, const Vec3& b) {
  const double product = std::fabs((a.x * a.y * a.z) * (b.x * b.y * b.z));
  return product > 0 && product < std::numeric_limits<double>::infinity();
}
inline bool same_as_full(const Vec3& v) { return same_as_full(v, {1, 1, 1}); }

}  // namespace tessera
