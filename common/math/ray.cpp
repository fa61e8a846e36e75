#include "common/math/ray.h"

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

}  // namespace tessera
