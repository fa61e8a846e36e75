// Ray / cube [-1, 1]^3 intersection (shapes.h) by the slab method.
//
// Each slab distance (+-1 - o) / d has an exact sign (a rounded difference keeps its sign), so
// an origin just outside a face never sees that face at t > 0. The hit's face coordinate is
// snapped to exactly +-1 and the other two are clamped into [-1, 1], so the reported point lies
// on the cube. As for every shape (and as in pbrt), point_error bounds how far the point may be
// from the surface; where along the surface the ray met it (o + t d loses digits of a far
// origin) does not matter for spawning rays and is not included: the face coordinate has no
// error, the others gamma(3) of their magnitude.
#include <algorithm>
#include <cmath>

#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

// Face numbering (LocalHit::part): -x, +x, -y, +y, -z, +z.
std::uint32_t face_index(int axis, bool positive) {
  return static_cast<std::uint32_t>(2 * axis + (positive ? 1 : 0));
}

}  // namespace

bool intersect_cube(const Ray& ray, double t_max, LocalHit& hit) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (!is_finite(o) || !is_finite(d)) return false;
  double t_enter = -kInfinity, t_exit = kInfinity;
  int enter_axis = -1, exit_axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (!(o[a] >= -1 && o[a] <= 1)) return false;  // parallel and outside (or NaN)
      continue;
    }
    const double t_lo = (-1 - o[a]) / d[a];
    const double t_hi = (1 - o[a]) / d[a];
    const double t_near = d[a] > 0 ? t_lo : t_hi;
    const double t_far = d[a] > 0 ? t_hi : t_lo;
    if (t_near > t_enter) t_enter = t_near, enter_axis = a;
    if (t_far < t_exit) t_exit = t_far, exit_axis = a;
  }
  if (!(t_enter <= t_exit)) return false;  // also rejects NaN

  double t = 0;
  int axis = -1;
  bool positive_face = false;
  if (t_enter > 0 && enter_axis >= 0) {
    t = t_enter, axis = enter_axis, positive_face = d[axis] < 0;
  } else if (t_exit > 0 && exit_axis >= 0) {
    t = t_exit, axis = exit_axis, positive_face = d[axis] > 0;
  } else {
    return false;
  }
  if (!(t < t_max)) return false;

  Vec3 p;
  Vec3 error;
  for (int a = 0; a < 3; ++a) {
    if (a == axis) {
      p[a] = positive_face ? 1 : -1;
      error[a] = 0;
    } else {
      p[a] = std::clamp(o[a] + t * d[a], -1.0, 1.0);
      error[a] = gamma_bound(3) * std::fabs(p[a]);
    }
  }
  Vec3 n;
  n[axis] = positive_face ? 1 : -1;
  hit.t = t;
  hit.point = p;
  hit.point_error = error;
  hit.normal = n;
  hit.shading_normal = n;
  hit.part = face_index(axis, positive_face);
  return true;
}

}  // namespace tessera
