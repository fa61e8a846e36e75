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

#include "common/geometry/cube_face_hit.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

using cube_detail::face_hit;
using cube_detail::face_normal;

// Where the ray enters and leaves the cube's slabs, through which faces (LocalHit::part; -1
// when no slab bounds that end); false when it misses.
struct SlabSpan {
  double t_enter = -kInfinity, t_exit = kInfinity;
  int enter_face = -1, exit_face = -1;
};

// slab_span and face_hit are inline, as they were inside intersect_cube before cube_crossings
// shared them: every cube test pays for the calls otherwise. Each axis is written out rather
// than looped over by index: GCC kept the loop, every d[a] a chain of selects on a.

// Narrows the span by the slab of `axis` (o, d: the origin's and direction's components there);
// false when the ray is parallel to it and outside it. A tie keeps the earlier axis.
[[gnu::always_inline]] inline bool narrow_to_slab(double o, double d, int axis, SlabSpan& span) {
  if (d == 0) return o >= -1 && o <= 1;
  const double t_lo = (-1 - o) / d;
  const double t_hi = (1 - o) / d;
  const bool rising = d > 0;
  const double t_near = rising ? t_lo : t_hi;
  const double t_far = rising ? t_hi : t_lo;
  // The span would end at t <= 0, which no caller takes: most often an origin outside the slab
  // moving away from it (a ray leaving a face; t_far's sign is exact, that of a rounded
  // difference). Deciding it here spares the later axes' divisions.
  if (!(t_far > 0)) return false;
  // Entering through the face towards -axis when rising, leaving through the one towards +axis.
  if (t_near > span.t_enter) span.t_enter = t_near, span.enter_face = 2 * axis + (rising ? 0 : 1);
  if (t_far < span.t_exit) span.t_exit = t_far, span.exit_face = 2 * axis + (rising ? 1 : 0);
  return true;
}

[[gnu::always_inline]] inline bool slab_span(const Vec3& o, const Vec3& d, SlabSpan& span) {
  if (!is_finite(o) || !is_finite(d)) return false;
  return narrow_to_slab(o.x, d.x, 0, span) && narrow_to_slab(o.y, d.y, 1, span) &&
         narrow_to_slab(o.z, d.z, 2, span) && span.t_enter <= span.t_exit;  // also rejects NaN
}

// The nearest face the ray meets with t in (0, t_max): where, and which (LocalHit::part); false
// when it meets none.
[[gnu::always_inline]] inline bool nearest_face(const Ray& ray, double t_max, double& t,
                                                int& face) {
  SlabSpan span;
  if (!slab_span(ray.origin, ray.direction, span)) return false;
  if (span.t_enter > 0 && span.enter_face >= 0) {
    t = span.t_enter, face = span.enter_face;
  } else if (span.t_exit > 0 && span.exit_face >= 0) {
    t = span.t_exit, face = span.exit_face;
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
  int face = -1;
  if (!nearest_face(ray, t_max, t, face)) return false;
  face_hit(ray.origin, ray.direction, t, face, hit);
  return true;
}

bool occluded_cube(const Ray& ray, double t_max) {
  double t = 0;
  int face = -1;
  return nearest_face(ray, t_max, t, face);
}

std::vector<LocalHit> cube_crossings(const Ray& ray, double t_max) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  std::vector<LocalHit> crossings;
  SlabSpan span;
  if (!slab_span(o, d, span)) return crossings;
  // A ray parallel to every slab it is inside (d = 0) has no ends: enter_face is then -1 too.
  if (span.enter_face < 0 || span.exit_face < 0) return crossings;
  if (span.t_enter > 0 && span.t_enter < t_max)
    face_hit(o, d, span.t_enter, span.enter_face, crossings.emplace_back());
  if (span.t_exit > 0 && span.t_exit < t_max)
    face_hit(o, d, span.t_exit, span.exit_face, crossings.emplace_back());
  return crossings;
}

}  // namespace tessera
