// Affine transforms of 3-space as 3x4 matrices (the last row is implicitly 0 0 0 1).
//
// SDL's current transform (CT) follows OpenGL: each transform keyword post-multiplies the CT,
// CT = CT * M, so the transform written last is applied to the shape first.
#pragma once

#include <optional>

#include "common/math/vec3.h"

namespace tessera {

struct Affine {
  // m[row][col]; column 3 is the translation.
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  static Affine identity() { return {}; }
  static Affine translation(const Vec3& d);
  static Affine scaling(const Vec3& s);
  // Rotation by `degrees` about `axis` (right-handed); the axis need not be unit length.
  // Returns nullopt when the axis has zero length.
  static std::optional<Affine> rotation(double degrees, const Vec3& axis);
  // The linear part from three column vectors (the images of the x, y and z axes).
  static Affine from_columns(const Vec3& cx, const Vec3& cy, const Vec3& cz);

  Vec3 apply_point(const Vec3& p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 apply_vector(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  // Applies the transpose of the linear part. A normal of a shape with transform M is
  // transformed by the transpose of M's inverse, so call this on the *inverse* transform.
  Vec3 apply_transpose(const Vec3& n) const {
    return {m[0][0] * n.x + m[1][0] * n.y + m[2][0] * n.z,
            m[0][1] * n.x + m[1][1] * n.y + m[2][1] * n.z,
            m[0][2] * n.x + m[1][2] * n.y + m[2][2] * n.z};
  }
  // Per-component bound on the rounding error of apply_point(p) (pbrt-v3 §3.9.4), plus the
  // propagated error `p_error` already carried by `p`.
  Vec3 point_error(const Vec3& p, const Vec3& p_error) const;

  double determinant() const;
  // Nullopt when the transform is singular (a zero scale, say) or not finite.
  std::optional<Affine> inverse() const;
  bool is_finite() const;
  friend bool operator==(const Affine&, const Affine&) = default;
};

// a * b: apply b first, then a.
Affine operator*(const Affine& a, const Affine& b);

}  // namespace tessera
