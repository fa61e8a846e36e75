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

// The outward normal of the face of `axis` that faces +axis when `positive`: +-1 on its axis,
// +0 on the others. A hit's normal is its face's alone (Instance::face_normals relies on it).
[[gnu::always_inline]] inline Vec3 face_normal(int axis, bool positive) {
  const double face = positive ? 1 : -1;
  return {axis == 0 ? face : 0.0, axis == 1 ? face : 0.0, axis == 2 ? face : 0.0};
}

// Where the ray enters and leaves the cube's slabs, and through which faces' axes (-1 when no
// slab bounds that end); false when it misses.
struct SlabSpan {
  double t_enter = -kInfinity, t_exit = kInfinity;
  int enter_axis = -1, exit_axis = -1;
};

// slab_span and face_hit are inline, as they were inside intersect_cube before cube_crossings
// shared them: every cube test pays for the calls otherwise.
[[gnu::always_inline]] inline bool slab_span(const Vec3& o, const Vec3& d, SlabSpan& span) {
  if (!is_finite(o) || !is_finite(d)) return false;
  // An origin outside a slab moving away from it (a ray leaving a face, most often): that
  // slab's far distance (+-1 - o) / d is <= 0 by its exact sign, so the span below would end at
  // t <= 0, which neither caller takes. Deciding it first saves the six divisions.
  for (int a = 0; a < 3; ++a)
    if ((d[a] > 0 && o[a] >= 1) || (d[a] < 0 && o[a] <= -1)) return false;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (!(o[a] >= -1 && o[a] <= 1)) return false;  // parallel and outside (or NaN)
      continue;
    }
    const double t_lo = (-1 - o[a]) / d[a];
    const double t_hi = (1 - o[a]) / d[a];
    const double t_near = d[a] > 0 ? t_lo : t_hi;
    const double t_far = d[a] > 0 ? t_hi : t_lo;
    if (t_near > span.t_enter) span.t_enter = t_near, span.enter_axis = a;
    if (t_far < span.t_exit) span.t_exit = t_far, span.exit_axis = a;
  }
  return span.t_enter <= span.t_exit;  // also rejects NaN
}

// The hit at t on the face of `axis` that faces +axis when `positive_face`, written into `hit`.
// Each vector is built whole from its three components, not written by index: a Vec3 stored a
// component at a time and read back two at a time stalls the load (store forwarding fails),
// which was most of a cube hit's time.
[[gnu::always_inline]] inline void face_hit(const Vec3& o, const Vec3& d, double t, int axis,
                                            bool positive_face, LocalHit& hit) {
  const double face = positive_face ? 1 : -1;
  const auto coordinate = [&](int a, double oa, double da) {
    return a == axis ? face : std::clamp(oa + t * da, -1.0, 1.0);
  };
  const Vec3 p{coordinate(0, o.x, d.x), coordinate(1, o.y, d.y), coordinate(2, o.z, d.z)};
  const auto error = [&](int a, double pa) {
    return a == axis ? 0.0 : gamma_bound(3) * std::fabs(pa);
  };
  const Vec3 n = face_normal(axis, positive_face);
  hit.t = t;
  hit.point = p;
  hit.point_error = {error(0, p.x), error(1, p.y), error(2, p.z)};
  hit.normal = n;
  hit.shading_normal = n;
  hit.part = face_index(axis, positive_face);
}

// The nearest face the ray meets with t in (0, t_max): where, on which axis, and whether it is
// the face towards +axis; false when it meets none.
[[gnu::always_inline]] inline bool nearest_face(const Ray& ray, double t_max, double& t, int& axis,
                                                bool& positive_face) {
  const Vec3& d = ray.direction;
  SlabSpan span;
  if (!slab_span(ray.origin, d, span)) return false;
  if (span.t_enter > 0 && span.enter_axis >= 0) {
    t = span.t_enter, axis = span.enter_axis, positive_face = d[axis] < 0;
  } else if (span.t_exit > 0 && span.exit_axis >= 0) {
    t = span.t_exit, axis = span.exit_axis, positive_face = d[axis] > 0;
  } else {
    return false;
  }
  return t < t_max;
}

}  // namespace

Vec3 cube_face_normal(std::uint32_t part) {
  return face_normal(static_cast<int>(part / 2), part % 2 == 1);
}

bool intersect_cube(const Ray& ray, double t_max, LocalHit& hit) {
  double t = 0;
  int axis = -1;
  bool positive_face = false;
  if (!nearest_face(ray, t_max, t, axis, positive_face)) return false;
  face_hit(ray.origin, ray.direction, t, axis, positive_face, hit);
  return true;
}

bool occluded_cube(const Ray& ray, double t_max) {
  double t = 0;
  int axis = -1;
  bool positive_face = false;
  return nearest_face(ray, t_max, t, axis, positive_face);
}

std::vector<LocalHit> cube_crossings(const Ray& ray, double t_max) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  std::vector<LocalHit> crossings;
  SlabSpan span;
  if (!slab_span(o, d, span)) return crossings;
  // A ray parallel to every slab it is inside (d = 0) has no ends: enter_axis is then -1 too.
  if (span.enter_axis < 0 || span.exit_axis < 0) return crossings;
  const int enter = span.enter_axis, exit = span.exit_axis;
  if (span.t_enter > 0 && span.t_enter < t_max)
    face_hit(o, d, span.t_enter, enter, d[enter] < 0, crossings.emplace_back());
  if (span.t_exit > 0 && span.t_exit < t_max)
    face_hit(o, d, span.t_exit, exit, d[exit] > 0, crossings.emplace_back());
  return crossings;
}

}  // namespace tessera
