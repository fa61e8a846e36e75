// Ray / unit sphere intersection (shapes.h).
//
// The discriminant is computed as in "Precision Improvements for Ray/Sphere Intersection"
// (Haines et al., Ray Tracing Gems ch. 7; pbrt-v4): from the distance l between the centre
// and the ray's line, D = a (1 - l)(1 + l), instead of b^2 - 4ac, which loses every digit for
// a small sphere far from the ray origin. The roots come from the cancellation-free
// q = -(b + sign(b) sqrt(D)) form. The root nearest zero is kept only when it is positive
// beyond its own error bound, so a ray leaving the surface cannot hit it again at t ~ 0.
#include <cmath>

#include "common/geometry/shapes.h"
#include "common/math/float_error.h"

namespace tessera {

namespace {

// The two roots of the ray's quadratic, ascending, with their error bounds, and what a hit at
// either is built from. Shared by the nearest-hit routine and the crossings (CSG); each keeps
// its own loop over the roots, so that the nearest hit compiles to the single early exit it
// had before CSG (a shared loop with a run-time count of wanted hits cost every sphere test
// about 17 instructions, in spilled registers).
struct SphereRoots {
  double t[2];
  double error[2];
  Vec3 closest;  // the point of the line nearest the centre
  double root = 0, a = 0;
};

[[gnu::always_inline]] inline bool sphere_roots(const Ray& ray, SphereRoots& r) {
  const Vec3& f = ray.origin;  // the centre is the origin
  const Vec3& d = ray.direction;
  const double a = dot(d, d);
  if (!(a > 0) || !std::isfinite(a)) return false;
  // a t^2 + 2 beta t + c = 0.
  const double beta = dot(f, d);
  const double f2 = dot(f, f);
  const double c = f2 - 1;
  // An origin outside the sphere moving away from it (a ray leaving its surface, most often):
  // both roots are then <= 0 (their product c / a > 0, their sum -2 beta / a <= 0), and so
  // are the t[] computed below (c / q with q < 0, and q / a), which no error bound lets
  // through: the answer the whole test would give, without its square roots and divisions.
  if (c > 0 && beta >= 0) return false;
  const double s = beta / a;
  const Vec3 closest = f - d * s;
  const double l2 = dot(closest, closest);
  // A line certainly outside the sphere (a miss, most often): then l = sqrt(l2) > 1 + 4e-13 and
  // disc below is negative, not an underflow to -0 (a > 1e-290), so it is decided here without
  // the square root.
  if (l2 > 1 + 1e-12 && a > 1e-290) return false;
  const double l = std::sqrt(l2);
  const double disc = a * (1 - l) * (1 + l);  // beta^2 - a c, without cancellation
  if (!(disc >= 0)) return false;
  const double root = std::sqrt(disc);
  const double q = beta < 0 ? root - beta : -(beta + root);
  if (q == 0) return false;  // origin on the sphere, ray tangent there: both roots are 0

  // Error bounds of the two roots, t0 = c / q and t1 = q / a (first order).
  const double c_error = gamma_bound(4) * (f2 + 1);
  const double l_error = gamma_bound(6) * (std::fabs(s) * std::sqrt(a) + l);
  const double disc_error =
      a * (1 + l) * l_error * 1.01 + a * std::fabs(1 - l) * l_error + gamma_bound(6) * disc;
  const double beta_error = gamma_bound(3) * dot(abs(f), abs(d));
  const double root_error =
      std::min(std::sqrt(disc_error), disc > 0 ? disc_error / root : kInfinity);
  const double q_rel = (beta_error + root_error) / std::fabs(q) + gamma_bound(1);

  r.t[0] = c / q;
  r.t[1] = q / a;
  r.error[0] = c_error / std::fabs(q) + std::fabs(r.t[0]) * (q_rel + gamma_bound(1));
  r.error[1] = std::fabs(r.t[1]) * (q_rel + gamma_bound(4));
  if (r.t[0] > r.t[1]) {
    std::swap(r.t[0], r.t[1]);
    std::swap(r.error[0], r.error[1]);
  }
  r.closest = closest;
  r.root = root;
  r.a = a;
  return true;
}

// The point of root i (ascending) of the ray with direction `d`, before its re-projection onto
// the sphere, and its distance from the centre; false when it cannot be re-projected.
[[gnu::always_inline]] inline bool sphere_point(const SphereRoots& r, const Vec3& d, int i, Vec3& p,
                                                double& len) {
  // From the line's point nearest the centre, which keeps the digits of a far origin when
  // the line is exactly representable (an axis-parallel ray, say); o + t d would not.
  p = r.closest + d * ((i == 0 ? -r.root : r.root) / r.a);
  len = length(p);
  return len > 0 && std::isfinite(len);
}

// The hit at root i (ascending) of the ray with direction `d`; false when its point cannot be
// re-projected onto the sphere.
[[gnu::always_inline]] inline bool sphere_hit(const SphereRoots& r, const Vec3& d, int i,
                                              LocalHit& hit) {
  Vec3 p;
  double len = 0;
  if (!sphere_point(r, d, i, p, len)) return false;
  p = p * (1 / len);  // re-project onto the sphere
  hit.t = r.t[i];
  hit.point = p;
  hit.point_error = abs(p) * gamma_bound(5);
  hit.normal = p;
  hit.shading_normal = p;
  hit.part = 0;
  return true;
}

}  // namespace

bool intersect_sphere(const Ray& ray, double t_max, LocalHit& hit) {
  SphereRoots r;
  if (!sphere_roots(ray, r)) return false;
  for (int i = 0; i < 2; ++i) {
    if (!(r.t[i] > r.error[i])) continue;  // not certainly in front of the origin (or NaN)
    if (!(r.t[i] < t_max)) return false;
    return sphere_hit(r, ray.direction, i, hit);
  }
  return false;
}

bool occluded_sphere(const Ray& ray, double t_max) {
  SphereRoots r;
  if (!sphere_roots(ray, r)) return false;
  for (int i = 0; i < 2; ++i) {
    if (!(r.t[i] > r.error[i])) continue;
    if (!(r.t[i] < t_max)) return false;
    // intersect_sphere's answer, without the hit: the re-projection's check alone.
    Vec3 p;
    double len = 0;
    return sphere_point(r, ray.direction, i, p, len);
  }
  return false;
}

std::vector<LocalHit> sphere_crossings(const Ray& ray, double t_max) {
  std::vector<LocalHit> crossings;
  SphereRoots r;
  if (!sphere_roots(ray, r)) return crossings;
  for (int i = 0; i < 2; ++i) {
    if (!(r.t[i] > r.error[i])) continue;
    LocalHit hit;
    if (!(r.t[i] < t_max) || !sphere_hit(r, ray.direction, i, hit)) break;
    crossings.push_back(hit);
  }
  return crossings;
}

}  // namespace tessera
