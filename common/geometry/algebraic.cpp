// Ray / algebraic surface intersection (shapes.h), one routine for every surface of
// algebraic_surfaces.h.
//
// As for the torus: the surface's polynomial is restricted to the ray, expanded exactly
// (implicit_polynomial.h) in a frame moved to the line's point nearest the object's origin,
// with a unit direction, so a far origin does not cancel its digits; the roots within the
// ray's span through the box extent are isolated and polished by bracketing
// (common/math/polynomial.h). Each hit then takes one Newton step along the gradient back onto
// the surface, and its error bound is the distance that the rounding of the polynomial allows,
// |F| plus F's evaluation error over |grad F|.
//
// Degenerate cases get defined, finite results:
//  - a ray lying in the surface (the axes of Steiner's surface, a cone's or cylinder's
//    generators) restricts the polynomial to zero: no isolated root, no hit;
//  - at singular points (the cone's apex, Cayley's nodes, Steiner's double lines) the gradient
//    vanishes: the hit keeps the root's point, with an error bound of the order of the square
//    root of the rounding (multiple roots are resolved no better), and faces the ray.
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/geometry/algebraic_surfaces.h"
#include "common/geometry/ordered_hits.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

LocalHit surface_hit(ImplicitPolynomial f, const Vec3& root_point, const Vec3& u) {
  LocalHit hit;
  hit.part = 0;
  const double singular_error =
      4 * std::sqrt(kMachineEpsilon) * (1 + max_component(abs(root_point)));
  Vec3 p = root_point;
  Vec3 g = gradient(f, p);
  const double g2 = dot(g, g);
  if (g2 > 0 && std::isfinite(g2)) {
    // One Newton step onto the surface, unless it would jump: near a singular point the
    // gradient is too small to say where the surface is.
    const Vec3 step = g * (evaluate(f, p) / g2);
    if (length(step) < singular_error) {
      p = p - step;
      g = gradient(f, p);
    }
  }
  const double g_len = length(g);
  const double distance =
      g_len > 0 ? (std::fabs(evaluate(f, p)) + evaluation_error(f, p)) / g_len : kInfinity;
  hit.point = p;
  if (distance < singular_error && std::isfinite(g_len)) {
    const double e = 2 * distance;
    hit.point_error = Vec3{e, e, e} + abs(p) * gamma_bound(2);
    hit.normal = g;
  } else {
    hit.point_error = {singular_error, singular_error, singular_error};
    hit.normal = -u;
  }
  hit.shading_normal = hit.normal;
  return hit;
}

// The roots with t in (t_min, t_max), ascending, as hits handed to take(hit, touching) until it
// returns false (see visit_torus_hits).
template <class Take>
void visit_algebraic_hits(const AlgebraicSurface& shape, const Ray& ray, double t_min, double t_max,
                          const Take& take) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  const double dd = dot(d, d);
  t_min = std::max(t_min, 0.0);
  if (!is_finite(o) || !is_finite(d) || !(dd > 0) || !std::isfinite(dd) || !(t_min < t_max) ||
      !std::isfinite(t_max))
    return;

  const ImplicitPolynomial f = algebraic_polynomial(shape.kind);
  const double len = std::sqrt(dd);
  const Vec3 u = d / len;
  const double t0 = -dot(o, d) / dd;
  const Vec3 near = o + d * t0;
  const Polynomial along = along_line(f, near, u);

  const auto at_root = [&](const PolynomialRoot& root) {
    const double t = t0 + root.x / len;
    if (!(t > t_min && t < t_max)) return true;
    LocalHit hit = surface_hit(f, near + u * root.x, u);
    // Within a few error bounds of the origin: the surface the ray is leaving.
    if (!(t * len > 4 * length(hit.point_error))) return true;
    hit.t = t;
    return take(hit, root.touching);
  };
  visit_real_roots(along, (t_min - t0) * len, (t_max - t0) * len, at_root);
}

}  // namespace

bool algebraic_extent_span(const AlgebraicSurface& shape, const Affine& to_world,
                           const Ray& world_ray, double& t_min, double& t_max) {
  const Vec3 centre = to_world.apply_point({0, 0, 0});
  for (int a = 0; a < 3; ++a) {
    const double lo = centre[a] - shape.extent[a] / 2, hi = centre[a] + shape.extent[a] / 2;
    const double o = world_ray.origin[a], d = world_ray.direction[a];
    if (d == 0) {
      if (!(o >= lo && o <= hi)) return false;
      continue;
    }
    double t_near = (lo - o) / d, t_far = (hi - o) / d;
    if (d < 0) std::swap(t_near, t_far);
    t_min = std::max(t_min, t_near);
    t_max = std::min(t_max, t_far);
  }
  return t_min < t_max;
}

Bounds3 algebraic_extent(const AlgebraicSurface& shape, const Affine& to_world) {
  const Vec3 centre = to_world.apply_point({0, 0, 0});
  return {centre - shape.extent / 2, centre + shape.extent / 2};
}

bool intersect_algebraic(const AlgebraicSurface& shape, const Ray& ray, double t_min, double t_max,
                         LocalHit& hit) {
  return nearest_ordered_hit(
      [&](const auto& take) { visit_algebraic_hits(shape, ray, t_min, t_max, take); }, hit);
}

std::vector<LocalHit> algebraic_crossings(const AlgebraicSurface& shape, const Ray& ray,
                                          double t_min, double t_max) {
  return ordered_crossings(
      [&](const auto& take) { visit_algebraic_hits(shape, ray, t_min, t_max, take); });
}

}  // namespace tessera
