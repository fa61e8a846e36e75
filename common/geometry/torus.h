// Parts of the ray / torus intersection (torus.cpp) that its tests reach directly.
#pragma once

#include <cmath>
#include <optional>

#include "common/geometry/local_hit.h"
#include "common/math/float_error.h"
#include "common/math/polynomial.h"
#include "common/math/ray.h"
#include "common/scene/shape.h"

namespace tessera {

// True only when no query of torus.cpp reports a hit of the torus on the ray (object space),
// so that a shadow ray need not form its quartic: its origin lies on or outside the tube's outer
// half (rho >= R) and the ray moves away from the plane there that bounds the whole torus, or it
// lies in the inner half (rho < R) and the ray rises away from the torus's plane, out of its slab
// |z| <= r, faster than it can near the tube, in both cases steeply enough that the quartic's
// rounding cannot put a root beyond the distance at which a hit counts as the surface the ray
// leaves. Most shadow rays leaving a torus's own surface. False says nothing.
bool leaves_the_torus_for_good(const Torus& torus, const Ray& ray);

// True only when every query of torus.cpp finds a hit of the torus on the ray (object space) with
// t in (0, t_max), so that a shadow ray need not form its quartic: the ray enters the padded box
// from outside, far enough from its origin for a hit to count, is clearly outside the tube there,
// and is clearly inside the tube at a later point before t_max (where it crosses the torus's plane
// or, failing that, one nearer the core circle), "clearly" by a margin that covers the rounding of
// the quartic the search would form and of the search itself. Most shadow rays from outside a
// torus that it blocks. False says nothing.
bool crosses_into_the_tube(const Torus& torus, const Ray& ray, double t_max);

// The padding of the torus's bounding box (|x|, |y| <= R + r, |z| <= r), by which the ray's span
// through it certainly holds the rounded surface.
inline constexpr double kTorusBoxPad = 1 + 1e-9;

// surface_hit's (torus.cpp) error bounds on the hit point, per coordinate: a few roundings of
// quantities of size R + r; on the axis, the square root of the rounding (see there).
inline double off_axis_point_error(double big_r, double r) { return gamma_bound(12) * (big_r + r); }
inline double on_axis_point_error(double big_r, double r) {
  return 4 * std::sqrt(kMachineEpsilon) * (big_r + r);
}

// A ray's frame for its quartic, as the nearest-hit query forms it: origin f at the line's point
// nearest the centre, unit direction u, s = (t - t0) len with len = |d|; [s_lo, s_hi] the span
// through the padded box and (0, t_max); P and Q as in F(f + s u) = (A s^2 + B s + C)^2 -
// 4 R^2 (P s^2 + 2 Q s + S); the quartic in s; and the end of the bracket [s_lo, end] of the
// search's first root that the nearest-hit query polishes it in (first_root_bracket in torus.cpp),
// nullopt when none is shown.
struct TorusLine {
  Vec3 u, f;
  double len, t0, s_lo, s_hi, P, Q;
};
struct TorusFrame {
  TorusLine line;
  Polynomial quartic;
  std::optional<double> first_root_end;
};

// The frame of the ray from `origin` along `direction` for intersect_torus with t_max, its
// first-root bracket included; false when the ray is shown to miss before the quartic is formed.
bool torus_frame(const Torus& torus, const Vec3& origin, const Vec3& direction, double t_max,
                 TorusFrame& frame);
// intersect_torus from the ray's frame.
bool nearest_torus_hit(const Torus& torus, const TorusFrame& frame, double t_max, LocalHit& hit);
// nearest_torus_hit in two steps, so that a packet's hits can be re-projected together: the
// nearest hit's root s of the frame's quartic and its t, then the hit itself.
struct TorusRoot {
  double s, t;
};
bool nearest_torus_root(const Torus& torus, const TorusFrame& frame, double t_max, TorusRoot& root);
LocalHit torus_root_hit(const Torus& torus, const TorusLine& line, const TorusRoot& root);

}  // namespace tessera
