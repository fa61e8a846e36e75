#include "common/math/affine.h"

#include <cmath>
#include <numbers>

#include "common/math/float_error.h"
#include "common/math/portable_math.h"

namespace tessera {

namespace {

// A transform is singular when |det| is below this fraction of the product of its column
// lengths (Hadamard's bound, which |det| reaches when the columns are orthogonal). The ratio
// does not depend on the transform's scale, so scales of 1e-4 or 1e4 are fine; only nearly
// dependent columns are refused.
constexpr double kSingularRatio = 1e-12;

Vec3 column(const Affine& a, int c) { return {a.m[0][c], a.m[1][c], a.m[2][c]}; }

// sin and cos of an angle in degrees, exact at multiples of 90 degrees (rotate 90 is common in
// scenes, and an exact rotation keeps axis-aligned geometry axis-aligned).
void sincos_degrees(double degrees, double& s, double& c) {
  double r = std::fmod(degrees, 360.0);  // exact
  if (r < 0) r += 360;
  if (r == 0 || r == 360) {
    s = 0, c = 1;
  } else if (r == 90) {
    s = 1, c = 0;
  } else if (r == 180) {
    s = 0, c = -1;
  } else if (r == 270) {
    s = -1, c = 0;
  } else {
    const double radians = r * (std::numbers::pi / 180);
    const SinCos sc = tessera::sincos(radians);
    s = sc.sin;
    c = sc.cos;
  }
}

}  // namespace

Affine Affine::translation(const Vec3& d) {
  Affine a;
  a.m[0][3] = d.x;
  a.m[1][3] = d.y;
  a.m[2][3] = d.z;
  return a;
}

Affine Affine::scaling(const Vec3& s) {
  Affine a;
  a.m[0][0] = s.x;
  a.m[1][1] = s.y;
  a.m[2][2] = s.z;
  return a;
}

std::optional<Affine> Affine::rotation(double degrees, const Vec3& axis) {
  // Scale by the largest component first so that tiny or huge axes do not under- or overflow.
  const double largest = max_component(abs(axis));
  if (!(largest > 0) || !std::isfinite(largest) || !std::isfinite(degrees)) return std::nullopt;
  const Vec3 scaled = axis / largest;
  const Vec3 u = scaled / length(scaled);
  double s = 0, c = 1;
  sincos_degrees(degrees, s, c);
  const double k = 1 - c;
  // Rodrigues: R = c I + s [u]x + (1 - c) u u^T.
  Affine r;
  r.m[0][0] = c + u.x * u.x * k;
  r.m[0][1] = u.x * u.y * k - u.z * s;
  r.m[0][2] = u.x * u.z * k + u.y * s;
  r.m[1][0] = u.y * u.x * k + u.z * s;
  r.m[1][1] = c + u.y * u.y * k;
  r.m[1][2] = u.y * u.z * k - u.x * s;
  r.m[2][0] = u.z * u.x * k - u.y * s;
  r.m[2][1] = u.z * u.y * k + u.x * s;
  r.m[2][2] = c + u.z * u.z * k;
  return r;
}

Affine Affine::from_columns(const Vec3& cx, const Vec3& cy, const Vec3& cz) {
  Affine a;
  for (int r = 0; r < 3; ++r) {
    a.m[r][0] = cx[r];
    a.m[r][1] = cy[r];
    a.m[r][2] = cz[r];
  }
  return a;
}

Affine operator*(const Affine& a, const Affine& b) {
  Affine out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      double v = a.m[r][0] * b.m[0][c] + a.m[r][1] * b.m[1][c] + a.m[r][2] * b.m[2][c];
      if (c == 3) v += a.m[r][3];
      out.m[r][c] = v;
    }
  }
  return out;
}

double Affine::determinant() const {
  return dot(column(*this, 0), cross(column(*this, 1), column(*this, 2)));
}

std::optional<Affine> Affine::inverse() const {
  if (!is_finite()) return std::nullopt;
  const Vec3 c0 = column(*this, 0), c1 = column(*this, 1), c2 = column(*this, 2);
  // The rows of the inverse are the cross products of the columns, divided by det. For the
  // usual translate * rotate * scale products the columns are orthogonal and these cross
  // products suffer no cancellation, so the inverse is accurate to a few ulps per column.
  const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
  const double det = dot(c0, r0);
  const double hadamard = length(c0) * length(c1) * length(c2);
  if (!(std::fabs(det) > kSingularRatio * hadamard)) return std::nullopt;
  Affine inv;
  const Vec3 rows[3] = {r0 / det, r1 / det, r2 / det};
  const Vec3 t = column(*this, 3);
  for (int r = 0; r < 3; ++r) {
    inv.m[r][0] = rows[r].x;
    inv.m[r][1] = rows[r].y;
    inv.m[r][2] = rows[r].z;
    inv.m[r][3] = -dot(rows[r], t);
  }
  if (!inv.is_finite()) return std::nullopt;
  return inv;
}

bool Affine::is_finite() const {
  for (const auto& row : m)
    for (double v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace tessera
