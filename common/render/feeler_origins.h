// Where a hit's shadow feelers start (eq. 4.24's feelers, one or more per light).
#pragma once

#include "common/geometry/instance.h"
#include "common/math/float_error.h"
#include "common/math/vec3.h"

namespace tessera {

// The hit's point pushed off its surface by `offset` (surface_offset, the same for every ray
// leaving the point) to the side a feeler leaves on, rounded away from the surface: for each
// feeler the point offset_ray_origin_by gives, bit for bit. Only the side depends on the
// feeler, so the front one, where a lit point's feelers nearly always leave, is made once per
// hit instead of once per light.
class FeelerOrigins {
 public:
  FeelerOrigins(const WorldHit& hit, const Vec3& offset)
      : hit_(hit), offset_(offset), front_(moved_off_surface(hit.point, offset)) {}
  // Forced inline: as a call (GCC's choice in the lighting loop) it cost more than it saved.
  [[gnu::always_inline]] Vec3 along(const Vec3& d) const {
    // offset_ray_origin_by's test of the side
    return dot(d, hit_.normal) < 0 ? moved_off_surface(hit_.point, -offset_) : front_;
  }

 private:
  const WorldHit& hit_;
  Vec3 offset_;
  Vec3 front_;  // on the side the geometric normal points to
};

}  // namespace tessera
