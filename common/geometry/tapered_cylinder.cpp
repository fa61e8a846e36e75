// Ray / tapered cylinder intersection (shapes.h).
//
// The wall is x^2 + y^2 = w(z)^2 with w(z) = 1 + k z, k = top_radius - 1, for z in [0, 1]; the
// caps are the disc of radius 1 at z = 0 and the disc of radius |w(1)| at z = 1 (absent for a
// cone, w(1) = 0). The shape is defined with the rounded k and w(1), and every test below uses
// those same values, so wall and caps meet.
//
// Robustness:
//  - a ray starting outside the bounding box is first moved to where it enters the box, so the
//    quadratic is solved in a frame close to the shape (a far origin would otherwise cancel
//    every digit of the discriminant);
//  - the roots use the cancellation-free q form; a root is kept only when it is positive
//    beyond its first-order error bound, so a ray leaving the wall never re-hits it at t ~ 0;
//  - the wall point is re-projected radially onto the wall (its error is then the rounding of
//    the projection alone), and the apex of a cone gets a finite point and normal;
//  - cap distances (h - o_z) / d_z have an exact sign, and the cap point's z is exact.
// point_error bounds the distance from the point to the surface (pbrt's convention): the
// position along the surface, which o + t d computes less accurately for a far origin, is not
// part of it.
#include <algorithm>
#include <cmath>

#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

// Where accepted hits go: the nearest so far, or every one (for CSG).
struct Candidate {
  double t = kInfinity;  // hits must be nearer than this
  LocalHit hit;
  std::vector<LocalHit>* all = nullptr;  // when set, every hit with t < t is kept here

  // Keeps `h`: as the nearest so far (callers only offer hits nearer than t), or among all.
  void take(const LocalHit& h) {
    if (all != nullptr) {
      all->push_back(h);
      return;
    }
    hit = h;
    t = h.t;
  }
};

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

// Completes a wall hit at t = shift + t' when it is nearer than `best` and its z is in [0, 1]:
// the point is re-projected radially onto the wall; the apex of a cone gets a finite point and
// normal.
bool accept_wall_hit(double k, const Vec3& o, const Vec3& d, double shift, double t_local,
                     Candidate& best) {
  const double t = shift + t_local;
  if (!(t < best.t)) return false;
  const double z = o.z + t_local * d.z;
  if (!(z >= 0 && z <= 1)) return false;

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
  hit.t = t;
  hit.shading_normal = hit.normal;
  hit.part = 0;
  best.take(hit);
  return true;
}

// The nearest wall hit (or every one) with shift + t' in (0, best.t), for the ray o + t' d.
void intersect_wall(double k, const Vec3& o, const Vec3& d, double shift, Candidate& best) {
  const double w0 = 1 + k * o.z;
  const double wd = k * d.z;
  // A t^2 + 2 B t + C = 0.
  const double a = d.x * d.x + d.y * d.y - wd * wd;
  const double b = o.x * d.x + o.y * d.y - w0 * wd;
  const double c = o.x * o.x + o.y * o.y - w0 * w0;
  const double disc = b * b - a * c;
  if (!(disc >= 0)) return;
  const double root = std::sqrt(disc);
  const double q = b < 0 ? root - b : -(b + root);
  if (q == 0) {
    // b = disc = 0: a double root at t' = 0 when c = 0 and a != 0. With the origin moved to
    // the box, that is a ray entering exactly at the cone's apex; otherwise the ray starts on
    // the wall. (a = b = c = 0 is a ray lying in the wall: no single hit point.)
    if (c == 0 && a != 0 && shift > 0) accept_wall_hit(k, o, d, shift, 0, best);
    return;
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

  double roots[2] = {c / q, q / a};
  double errors[2] = {c_error / std::fabs(q) + std::fabs(roots[0]) * (q_rel + gamma_bound(1)),
                      std::fabs(roots[1]) * (q_rel + a_error / std::fabs(a) + gamma_bound(1))};
  if (roots[0] > roots[1]) {
    std::swap(roots[0], roots[1]);
    std::swap(errors[0], errors[1]);
  }
  for (int i = 0; i < 2; ++i) {
    const double t_local = roots[i];
    if (!std::isfinite(t_local)) continue;
    const double t = shift + t_local;
    if (!(t > errors[i] + gamma_bound(1) * shift)) continue;
    if (!(t < best.t)) return;
    if (accept_wall_hit(k, o, d, shift, t_local, best) && best.all == nullptr) return;
  }
}

// A cap: the disc x^2 + y^2 <= radius^2 in the plane z = height.
void intersect_cap(double height, double radius, std::uint32_t part, const Vec3& o, const Vec3& d,
                   Candidate& best) {
  if (d.z == 0) return;
  const double t = (height - o.z) / d.z;
  if (!(t > 0 && t < best.t)) return;
  const double x = o.x + t * d.x, y = o.y + t * d.y;
  if (!(x * x + y * y <= radius * radius)) return;
  LocalHit hit;
  hit.t = t;
  hit.point = {x, y, height};
  hit.point_error = {gamma_bound(3) * std::fabs(x), gamma_bound(3) * std::fabs(y), 0};
  hit.normal = {0, 0, height > 0 ? 1.0 : -1.0};
  hit.shading_normal = hit.normal;
  hit.part = part;
  best.take(hit);
}

// The wall's and caps' hits with t in (0, best.t): the nearest, or every one.
void tapered_cylinder_hits(const TaperedCylinder& shape, const Ray& ray, Candidate& best) {
  const double k = shape.top_radius - 1;
  const double top = 1 + k;
  const double r = std::max(1.0, std::fabs(top));
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  if (!is_finite(o) || !is_finite(d) || !(best.t > 0)) return;

  // The box is padded by a few ulps so that it certainly holds the rounded surface.
  double t_enter = 0, t_exit = 0;
  if (!box_span(o, d, r * (1 + gamma_bound(4)), t_enter, t_exit)) return;
  if (!(t_exit > 0) || !(t_enter < best.t)) return;
  const double shift = std::max(t_enter, 0.0);

  intersect_wall(k, shift > 0 ? o + d * shift : o, d, shift, best);
  intersect_cap(0, 1, 1, o, d, best);
  if (top != 0) intersect_cap(1, std::fabs(top), 2, o, d, best);
}

}  // namespace

bool intersect_tapered_cylinder(const TaperedCylinder& shape, const Ray& ray, double t_max,
                                LocalHit& hit) {
  Candidate best;
  best.t = t_max;
  tapered_cylinder_hits(shape, ray, best);
  if (!(best.t < t_max)) return false;
  hit = best.hit;
  return true;
}

std::vector<LocalHit> tapered_cylinder_crossings(const TaperedCylinder& shape, const Ray& ray,
                                                 double t_max) {
  std::vector<LocalHit> crossings;
  Candidate every;
  every.t = t_max;
  every.all = &crossings;
  tapered_cylinder_hits(shape, ray, every);
  std::sort(crossings.begin(), crossings.end(),
            [](const LocalHit& a, const LocalHit& b) { return a.t < b.t; });
  return crossings;
}

}  // namespace tessera
