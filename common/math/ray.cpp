#include "common/math/ray.h"

#include <cmath>

#include "common/math/float_error.h"

namespace tessera {

Bounds3 Bounds3::transformed(const Affine& t) const {
  if (empty()) return {};
  Bounds3 out;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{(corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y,
                 (corner & 4) ? hi.z : lo.z};
    out.extend(t.apply_point(p));
  }
  return out;
}

bool intersect_bounds(const Bounds3& b, const Vec3& origin, const Vec3& inv_dir, double t_max) {
  // The far distance is enlarged so that rounding never culls a grazing ray (pbrt-v3 §3.9.2).
  constexpr double kFarScale = 1 + 2 * gamma_bound(3);
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double inv = inv_dir[a];
    if (std::isinf(inv)) {
      // Direction component zero: the ray stays in one plane; inside the closed slab or not.
      // (Computing (lo - o) * inf would give NaN when the origin lies on a slab plane.)
      if (!(origin[a] >= b.lo[a] && origin[a] <= b.hi[a])) return false;
      continue;
    }
    const double t_near = ((inv >= 0 ? b.lo[a] : b.hi[a]) - origin[a]) * inv;
    const double t_far = ((inv >= 0 ? b.hi[a] : b.lo[a]) - origin[a]) * inv * kFarScale;
    if (t_near > t0) t0 = t_near;
    if (t_far < t1) t1 = t_far;
    if (!(t0 <= t1)) return false;
  }
  return true;
}

}  // namespace tessera
