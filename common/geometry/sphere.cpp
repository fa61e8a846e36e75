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

// The roots with t in (their error bound, t_max), ascending, as hits: at most `wanted` of them,
// so that the nearest-hit routine does not complete the farther one.
int sphere_hits(const Ray& ray, double t_max, int wanted, LocalHit* hits) {
  const Vec3& f = ray.origin;  // the centre is the origin
  const Vec3& d = ray.direction;
  const double a = dot(d, d);
  if (!(a > 0) || !std::isfinite(a)) return 0;
  // a t^2 + 2 beta t + c = 0.
  const double beta = dot(f, d);
  const double f2 = dot(f, f);
  const double c = f2 - 1;
  const double s = beta / a;
  const Vec3 closest = f - d * s;  // the point of the line nearest the centre
  const double l = length(closest);
  const double disc = a * (1 - l) * (1 + l);  // beta^2 - a c, without cancellation
  if (!(disc >= 0)) return 0;
  const double root = std::sqrt(disc);
  const double q = beta < 0 ? root - beta : -(beta + root);
  if (q == 0) return 0;  // origin on the sphere, ray tangent there: both roots are 0

  // Error bounds of the two roots, t0 = c / q and t1 = q / a (first order).
  const double c_error = gamma_bound(4) * (f2 + 1);
  const double l_error = gamma_bound(6) * (std::fabs(s) * std::sqrt(a) + l);
  const double disc_error =
      a * (1 + l) * l_error * 1.01 + a * std::fabs(1 - l) * l_error + gamma_bound(6) * disc;
  const double beta_error = gamma_bound(3) * dot(abs(f), abs(d));
  const double root_error =
      std::min(std::sqrt(disc_error), disc > 0 ? disc_error / root : kInfinity);
  const double q_rel = (beta_error + root_error) / std::fabs(q) + gamma_bound(1);

  double t_candidates[2] = {c / q, q / a};
  double t_errors[2] = {
      c_error / std::fabs(q) + std::fabs(t_candidates[0]) * (q_rel + gamma_bound(1)),
      std::fabs(t_candidates[1]) * (q_rel + gamma_bound(4))};
  if (t_candidates[0] > t_candidates[1]) {
    std::swap(t_candidates[0], t_candidates[1]);
    std::swap(t_errors[0], t_errors[1]);
  }
  int count = 0;
  for (int i = 0; i < 2 && count < wanted; ++i) {
    const double t = t_candidates[i];
    if (!(t > t_errors[i])) continue;  // not certainly in front of the origin (or NaN)
    if (!(t < t_max)) break;
    // From the line's point nearest the centre, which keeps the digits of a far origin when
    // the line is exactly representable (an axis-parallel ray, say); o + t d would not.
    Vec3 p = closest + d * ((i == 0 ? -root : root) / a);
    const double len = length(p);
    if (!(len > 0) || !std::isfinite(len)) break;
    p = p * (1 / len);  // re-project onto the sphere
    LocalHit& hit = hits[count++];
    hit.t = t;
    hit.point = p;
    hit.point_error = abs(p) * gamma_bound(5);
    hit.normal = p;
    hit.shading_normal = p;
    hit.part = 0;
  }
  return count;
}

}  // namespace

bool intersect_sphere(const Ray& ray, double t_max, LocalHit& hit) {
  return sphere_hits(ray, t_max, 1, &hit) == 1;
}

std::vector<LocalHit> sphere_crossings(const Ray& ray, double t_max) {
  LocalHit hits[2];
  const int count = sphere_hits(ray, t_max, 2, hits);
  return std::vector<LocalHit>(hits, hits + count);
}

}  // namespace tessera
