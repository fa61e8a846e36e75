// Parts of the ray / torus intersection (torus.cpp) that its tests reach directly.
#pragma once

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

}  // namespace tessera
