// Ray / tapered cylinder intersection (shapes.h).
//
// The wall is x^2 + y^2 = w(z)^2 with w(z) = 1 + k z, k = top_radius - 1, for z in [0, 1]; the
// caps are the disc of radius 1 at z = 0 and the disc of radius |w(1)| at z = 1 (absent for a
// cone, w(1) = 0), each unless the shape leaves it out (then its hits are not reported). The
// shape is defined with the rounded k and w(1), and every test below uses those same values,
// so wall and caps meet.
//
// Robustness:
//  - a ray starting outside the bounding box is first moved to where it enters the box, so the
//    quadratic is solved in a frame close to the shape (a far origin would otherwise cancel
//    every digit of the discriminant);
//  - the roots use the cancellation-free q form; a root is kept only when it is positive
//    beyond its first-order error bound, so a ray leaving the wall never re-hits it at t ~ 0;
//  - the wall point is re-projected radially onto the wall (its error is then the rounding of
//    the projection alone), and the apex of a cone gets a finite point and normal;
//  - cap distances (h - o_z) / d_z have an exact sign, and the cap point's z is exact;
//  - the crossings are the ends of the spans where the ray is both within the wall's radius
//    (the quadric x^2 + y^2 <= w(z)^2) and between the caps' planes, so where a ray meets a
//    rim exactly one of wall and cap is reported, never both or neither: crossings come in
//    pairs and a boolean object counts inside and outside right. The nearest hit is the first
//    of those crossings, so both come from the same arithmetic.
// point_error bounds the distance from the point to the surface (pbrt's convention): the
// position along the surface, which o + t d computes less accurately for a far origin, is not
// part of it.
#include <algorithm>
#include <cmath>

#include "common/geometry/ordered_hits.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

// Entry and exit of the ray through [-r, r]^2 x [0, 1]; false when it misses.
bool box_span(const Vec3& o, const Vec3& d, double r, double& t_enter, double& t_exit) {
  const double lo[3] = {-r, -r, 0}, hi[3] = {r, r, 1};
  t_enter = -kInfinity, t_exit = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (!(o[a] >= lo[a] && o[a] <= hi[a])) return false;
      continue;
    }
    double t_near = (lo[a] - o[a]) / d[a], t_far = (hi[a] - o[a]) / d[a];
    if (d[a] < 0) std::swap(t_near, t_far);
    t_enter = std::max(t_enter, t_near);
    t_exit = std::min(t_exit, t_far);
  }
  return t_enter <= t_exit;
}

// The wall hit at t = shift + t' of the ray o + t' d: the point re-projected radially onto the
// wall; the apex of a cone gets a finite point and normal.
LocalHit wall_hit(double k, const Vec3& o, const Vec3& d, double shift, double t_local) {
  const double z = std::clamp(o.z + t_local * d.z, 0.0, 1.0);
  const double x = o.x + t_local * d.x, y = o.y + t_local * d.y;
  const double w = 1 + k * z;
  const double h = std::sqrt(x * x + y * y);
  LocalHit hit;
  // |w| is within gamma(3) (1 + |k z|) of the wall's radius at z; the unit direction (x, y) / h
  // carries gamma(4) relative, and the product one more rounding.
  const double radius_error = gamma_bound(3) * (1 + std::fabs(k * z));
  if (h > 0 && w != 0 && std::isfinite(h)) {
    const double cx = x / h, cy = y / h;
    const double r = std::fabs(w);
    hit.point = {cx * r, cy * r, z};
    hit.point_error = {gamma_bound(5) * std::fabs(hit.point.x) + std::fabs(cx) * radius_error,
                       gamma_bound(5) * std::fabs(hit.point.y) + std::fabs(cy) * radius_error, 0};
    // The gradient of x^2 + y^2 - w^2, divided by 2 |w|.
    hit.normal = {cx, cy, w > 0 ? -k : k};
  } else {
    // The apex of a cone (w = 0): the wall degenerates to a point on the axis.
    hit.point = {0, 0, z};
    hit.point_error = {radius_error + std::fabs(w), radius_error + std::fabs(w), 0};
    hit.normal = {0, 0, k < 0 ? 1.0 : -1.0};
  }
  hit.t = shift + t_local;
  hit.shading_normal = hit.normal;
  hit.part = 0;
  return hit;
}

// The cap hit at t in the plane z = height (part 1 at z = 0, 2 at z = 1).
LocalHit cap_hit(double height, const Vec3& o, const Vec3& d, double t) {
  const double x = o.x + t * d.x, y = o.y + t * d.y;
  LocalHit hit;
  hit.t = t;
  hit.point = {x, y, height};
  hit.point_error = {gamma_bound(3) * std::fabs(x), gamma_bound(3) * std::fabs(y), 0};
  hit.normal = {0, 0, height > 0 ? 1.0 : -1.0};
  hit.shading_normal = hit.normal;
  hit.part = height > 0 ? 2 : 1;
  return hit;
}

// One end of a span: where along the ray, whether it may be reported (a wall root within its
// error bound of the origin is the surface the ray leaves), and which surface it lies on.
struct SpanEnd {
  double t = 0;  // in the ray's own parameter
  bool reportable = false;
  enum class Surface { Wall, BaseCap, TopCap } surface = Surface::Wall;
};

// Where the ray o + t' d (t = shift + t') is within the wall's radius, x^2 + y^2 <= w(z)^2:
// the quadric's value a t'^2 + 2 b t' + c is <= 0 on one span, on two half-lines (a < 0: the
// ray is steeper than the wall, and also meets the mirrored nappe), on the whole line or
// nowhere. Unbounded ends are infinite.
struct WallSpans {
  SpanEnd lo[2], hi[2];
  int count = 0;
};

WallSpans wall_spans(double k, const Vec3& o, const Vec3& d, double shift) {
  const double w0 = 1 + k * o.z;
  const double wd = k * d.z;
  const double a = d.x * d.x + d.y * d.y - wd * wd;
  const double b = o.x * d.x + o.y * d.y - w0 * wd;
  const double c = o.x * o.x + o.y * o.y - w0 * w0;
  const double disc = b * b - a * c;
  WallSpans spans;
  const SpanEnd minus_infinity{-kInfinity, false}, plus_infinity{kInfinity, false};
  const auto add = [&](const SpanEnd& lo, const SpanEnd& hi) {
    spans.lo[spans.count] = lo;
    spans.hi[spans.count++] = hi;
  };
  if (!(disc >= 0)) {
    if (a < 0) add(minus_infinity, plus_infinity);  // always within the radius
    return spans;
  }
  const double root = std::sqrt(disc);
  const double q = b < 0 ? root - b : -(b + root);
  if (q == 0) {
    // b = disc = 0, so a c = 0: a constant value c (a = 0), or a double root at t' = 0 (c = 0),
    // within the radius there alone (a > 0: only touching, no span) or everywhere (a < 0).
    if ((a == 0 && c <= 0) || a < 0) add(minus_infinity, plus_infinity);
    return spans;
  }

  // First-order error bounds of the coefficients and of the two roots.
  const double w0_error = gamma_bound(2) * (1 + std::fabs(k * o.z));
  const double a_error = gamma_bound(3) * (d.x * d.x + d.y * d.y + wd * wd);
  const double b_error =
      gamma_bound(3) * (std::fabs(o.x * d.x) + std::fabs(o.y * d.y) + std::fabs(w0 * wd)) +
      std::fabs(wd) * w0_error;
  const double c_error =
      gamma_bound(3) * (o.x * o.x + o.y * o.y + w0 * w0) + 2.01 * std::fabs(w0) * w0_error;
  const double disc_error = 2.01 * std::fabs(b) * b_error + std::fabs(a) * c_error +
                            std::fabs(c) * a_error + gamma_bound(2) * (b * b + std::fabs(a * c));
  const double root_error =
      std::min(std::sqrt(disc_error), disc > 0 ? disc_error / root : kInfinity);
  const double q_rel = (b_error + root_error) / std::fabs(q) + gamma_bound(1);

  // c / q is always finite; q / a is infinite for a = 0 (the quadric is then linear in t').
  double roots[2] = {c / q, q / a};
  double errors[2] = {c_error / std::fabs(q) + std::fabs(roots[0]) * (q_rel + gamma_bound(1)),
                      std::fabs(roots[1]) * (q_rel + a_error / std::fabs(a) + gamma_bound(1))};
  if (roots[0] > roots[1]) {
    std::swap(roots[0], roots[1]);
    std::swap(errors[0], errors[1]);
  }
  SpanEnd ends[2];
  for (int i = 0; i < 2; ++i) {
    const double t = shift + roots[i];
    ends[i] = {t, std::isfinite(t) && t > errors[i] + gamma_bound(1) * shift};
  }
  if (a > 0) {
    add(ends[0], ends[1]);
  } else if (a < 0) {
    add(minus_infinity, ends[0]);
    add(ends[1], plus_infinity);
  } else if (std::isfinite(ends[0].t)) {  // linear: within the radius on one side of its root
    const SpanEnd& at = ends[0];
    if (b > 0)
      add(minus_infinity, at);
    else
      add(at, plus_infinity);
  }
  return spans;
}

// Whether the shape draws the part a hit is on (a VRML Cylinder or Cone may leave some out:
// then the ray passes where the part would be).
bool drawn(const TaperedCylinder& shape, std::uint32_t part) {
  return part == 0 ? shape.wall : part == 1 ? shape.base_cap : shape.top_cap;
}

// The crossings of the solid with t in (0, t_max), ascending, handed to take(hit, touching)
// until it returns false: the ends of each wall span clipped to the slab between the caps.
template <class Take>
void visit_tapered_cylinder_hits(const TaperedCylinder& shape, const Ray& ray, double t_max,
                                 const Take& take) {
  const double k = shape.top_radius - 1;
  const double top = 1 + k;
  const double r = std::max(1.0, std::fabs(top));
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (!is_finite(o) || !is_finite(d) || !(t_max > 0)) return;

  // The box is padded by a few ulps so that it certainly holds the rounded surface.
  double t_enter = 0, t_exit = 0;
  if (!box_span(o, d, r * (1 + gamma_bound(4)), t_enter, t_exit)) return;
  if (!(t_exit > 0) || !(t_enter < t_max)) return;
  const double shift = std::max(t_enter, 0.0);
  const Vec3 o_near = shift > 0 ? o + d * shift : o;

  // The slab 0 <= z <= 1: the caps' distances have an exact sign.
  SpanEnd slab_lo{-kInfinity, false, SpanEnd::Surface::BaseCap};
  SpanEnd slab_hi{kInfinity, false, SpanEnd::Surface::TopCap};
  if (d.z != 0) {
    // Upwards the ray enters the slab through the base's plane, downwards through the top's.
    slab_lo.t = (0 - o.z) / d.z;
    slab_hi.t = (1 - o.z) / d.z;
    if (d.z < 0) std::swap(slab_lo, slab_hi);
    slab_lo.reportable = slab_lo.t > 0;
    slab_hi.reportable = slab_hi.t > 0;
  } else if (!(o.z >= 0 && o.z <= 1)) {
    return;
  }

  const auto hit_at = [&](const SpanEnd& end) {
    // A cone has no top cap: its top plane meets the wall only at the apex.
    const bool on_wall = end.surface == SpanEnd::Surface::Wall ||
                         (end.surface == SpanEnd::Surface::TopCap && top == 0);
    if (on_wall) return wall_hit(k, o_near, d, shift, end.t - shift);
    return cap_hit(end.surface == SpanEnd::Surface::TopCap ? 1.0 : 0.0, o, d, end.t);
  };
  const WallSpans spans = wall_spans(k, o_near, d, shift);
  for (int i = 0; i < spans.count; ++i) {
    // The span within the slab: its ends are the later start and the earlier end, on the
    // surface that gives them (the wall on a tie).
    const SpanEnd& lo = slab_lo.t > spans.lo[i].t ? slab_lo : spans.lo[i];
    const SpanEnd& hi = slab_hi.t < spans.hi[i].t ? slab_hi : spans.hi[i];
    if (!(lo.t < hi.t)) continue;
    for (const SpanEnd* end : {&lo, &hi}) {
      if (!(end->t < t_max)) return;
      if (!end->reportable) continue;
      const LocalHit hit = hit_at(*end);
      if (drawn(shape, hit.part) && !take(hit, false)) return;
    }
  }
}

}  // namespace

bool intersect_tapered_cylinder(const TaperedCylinder& shape, const Ray& ray, double t_max,
                                LocalHit& hit) {
  return nearest_ordered_hit(
      [&](const auto& take) { visit_tapered_cylinder_hits(shape, ray, t_max, take); }, hit);
}

std::vector<LocalHit> tapered_cylinder_crossings(const TaperedCylinder& shape, const Ray& ray,
                                                 double t_max) {
  return ordered_crossings(
      [&](const auto& take) { visit_tapered_cylinder_hits(shape, ray, t_max, take); });
}

}  // namespace tessera
