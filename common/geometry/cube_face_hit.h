// A cube's hit on one of its faces, shared by the cube's tests a ray at a time (cube.cpp) and
// four at a time (cube_packet.cpp), so that both write the same hit from the same t and face.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "common/geometry/local_hit.h"
#include "common/math/float_error.h"

namespace tessera::cube_detail {

// Face numbering (LocalHit::part): 2 axis for the face towards -axis, 2 axis + 1 for the one
// towards +axis (-x, +x, -y, +y, -z, +z).
//
// The outward normal of the face of `axis` that faces +axis when `positive`: +-1 on its axis,
// +0 on the others. A hit's normal is its face's alone (Instance::face_normals relies on it).
[[gnu::always_inline]] inline Vec3 face_normal(int axis, bool positive) {
  const double face = positive ? 1 : -1;
  return {axis == 0 ? face : 0.0, axis == 1 ? face : 0.0, axis == 2 ? face : 0.0};
}

// The hit at t on face `face` (LocalHit::part), written into `hit`. Each vector is built whole
// from its three components, not written by index: a Vec3 stored a component at a time and read
// back two at a time stalls the load (store forwarding fails), which was most of a cube hit's
// time.
[[gnu::always_inline]] inline void face_hit(const Vec3& o, const Vec3& d, double t, int face,
                                            LocalHit& hit) {
  const int axis = face / 2;
  const double face_coordinate = face % 2 == 1 ? 1 : -1;
  const auto coordinate = [&](int a, double oa, double da) {
    return a == axis ? face_coordinate : std::clamp(oa + t * da, -1.0, 1.0);
  };
  const Vec3 p{coordinate(0, o.x, d.x), coordinate(1, o.y, d.y), coordinate(2, o.z, d.z)};
  const auto error = [&](int a, double pa) {
    return a == axis ? 0.0 : gamma_bound(3) * std::fabs(pa);
  };
  const Vec3 n = face_normal(axis, face % 2 == 1);
  hit.t = t;
  hit.point = p;
  hit.point_error = {error(0, p.x), error(1, p.y), error(2, p.z)};
  hit.normal = n;
  hit.shading_normal = n;
  hit.part = static_cast<std::uint32_t>(face);
}

}  // namespace tessera::cube_detail
