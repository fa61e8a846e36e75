// Rays and axis-aligned bounds.
#pragma once

#include <limits>

#include "common/math/affine.h"
#include "common/math/float_error.h"
#include "common/math/vec3.h"

namespace tessera {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Ray {
  Vec3 origin;
  Vec3 direction;   // not necessarily unit length; parameters t are in units of it
  double time = 0;  // shutter time, for motion blur
};

struct Bounds3 {
  Vec3 lo{kInfinity, kInfinity, kInfinity};
  Vec3 hi{-kInfinity, -kInfinity, -kInfinity};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const Bounds3& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  // Whether the two boxes share a point (touching counts).
  bool overlaps(const Bounds3& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y && lo.z <= b.hi.z &&
           b.lo.z <= hi.z;
  }
  Vec3 centroid() const { return (lo + hi) * 0.5; }
  Vec3 diagonal() const { return hi - lo; }
  double surface_area() const {
    if (empty()) return 0;
    const Vec3 d = diagonal();
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
  // The bounds of this box after an affine transform (all eight corners).
  Bounds3 transformed(const Affine& t) const;
};

// Slab test against precomputed reciprocal direction. Returns whether [t0, t1] overlaps the box
// within [0, t_max]; the far distance is enlarged by 2*gamma(3) so that a ray grazing a box
// face is never culled by rounding (pbrt-v3 §3.9.2). Inline and without early exits: the BVH
// traversal calls it for every node it visits, and which slab empties the interval first is
// a branch no predictor guesses.
// `t_entry` receives t0, where the ray enters the box (ordered BVH traversal visits the nearer
// child first).
[[gnu::always_inline]] inline bool intersect_bounds(const Bounds3& b, const Vec3& origin,
                                                    const Vec3& inv_dir, double t_max,
                                                    double& t_entry) {
  constexpr double kFarScale = 1 + 2 * gamma_bound(3);
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    const double inv = inv_dir[a];
    const bool forward = inv >= 0;
    const double t_near = ((forward ? b.lo[a] : b.hi[a]) - origin[a]) * inv;
    const double t_far = ((forward ? b.hi[a] : b.lo[a]) - origin[a]) * inv * kFarScale;
    // A zero direction component makes these infinite, with the sign that keeps or empties the
    // interval as the origin lies inside or outside the slab; with the origin on one of its
    // planes, NaN (0 * inf), which these comparisons leave out: the ray runs along the face
    // of a closed slab.
    t0 = t_near > t0 ? t_near : t0;
    t1 = t_far < t1 ? t_far : t1;
  }
  t_entry = t0;
  return t0 <= t1;
}

[[gnu::always_inline]] inline bool intersect_bounds(const Bounds3& b, const Vec3& origin,
                                                    const Vec3& inv_dir, double t_max) {
  double t_entry;
  return intersect_bounds(b, origin, inv_dir, t_max, t_entry);
}

}  // namespace tessera
