// Affine transforms of 3-space as 3x4 matrices (the last row is implicitly 0 0 0 1).
//
// SDL's current transform (CT) follows OpenGL: each transform keyword post-multiplies the CT,
// CT = CT * M, so the transform written last is applied to the shape first.
#pragma once

#include <cmath>
#include <optional>

#include "common/math/float_error.h"
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
  // propagated error `p_error` already carried by `p`. Forced inline (GCC kept it out of line),
  // and each component built whole: returned from a call, or written into a Vec3 by index, the
  // components were stored one by one and read back two at a time, which stalls the load until
  // the stores reach the cache (every hit of every shape pays it).
  [[gnu::always_inline]] Vec3 point_error(const Vec3& p, const Vec3& p_error) const {
    return {row_error(0, p, p_error), row_error(1, p, p_error), row_error(2, p, p_error)};
  }

  double determinant() const;
  // Nullopt when the transform is singular (a zero scale, say) or not finite.
  std::optional<Affine> inverse() const;
  bool is_finite() const;
  friend bool operator==(const Affine&, const Affine&) = default;

 private:
  // Row r of point_error: the rounding of the matrix-vector product and translation, plus the
  // incoming error carried through the linear part (itself rounded).
  double row_error(int r, const Vec3& p, const Vec3& p_error) const {
    const double magnitude = std::fabs(m[r][0] * p.x) + std::fabs(m[r][1] * p.y) +
                             std::fabs(m[r][2] * p.z) + std::fabs(m[r][3]);
    const double carried = std::fabs(m[r][0]) * p_error.x + std::fabs(m[r][1]) * p_error.y +
                           std::fabs(m[r][2]) * p_error.z;
    return gamma_bound(3) * magnitude + (gamma_bound(3) + 1) * carried;
  }
};

// a * b: apply b first, then a.
Affine operator*(const Affine& a, const Affine& b);

}  // namespace tessera
