#include "common/geometry/triangle.h"

#include <cmath>

#include "common/math/float_error.h"

namespace tessera {

namespace {

Vec3 permute(const Vec3& v, int x, int y, int z) { return {v[x], v[y], v[z]}; }

}  // namespace

bool triangle_is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const double area2 = length_squared(cross(p1 - p0, p2 - p0));
  return !(area2 > 0) || !std::isfinite(area2);
}

TriangleRay prepare_triangle_ray(const Ray& ray) {
  // Translate the vertices so that the ray starts at the origin, permute the axes so that the
  // direction's largest component is z, and shear so that the ray runs along +z. Every vertex
  // is transformed the same way whichever triangle it belongs to, which makes the edge
  // functions of a shared edge exactly opposite (watertightness).
  TriangleRay r;
  r.origin = ray.origin;
  const Vec3& d = ray.direction;
  r.kz = max_axis(abs(d));
  r.kx = r.kz == 2 ? 0 : r.kz + 1;
  r.ky = r.kx == 2 ? 0 : r.kx + 1;
  const Vec3 dp = permute(d, r.kx, r.ky, r.kz);
  r.usable = dp.z != 0 && is_finite(dp);
  r.sx = -dp.x / dp.z;
  r.sy = -dp.y / dp.z;
  r.sz = 1 / dp.z;
  return r;
}

bool intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const TriangleRay& ray,
                        double t_max, TriangleHit& hit) {
  if (!ray.usable) return false;
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const double sx = ray.sx, sy = ray.sy, sz = ray.sz;
  Vec3 q0 = permute(p0 - ray.origin, kx, ky, kz);
  Vec3 q1 = permute(p1 - ray.origin, kx, ky, kz);
  Vec3 q2 = permute(p2 - ray.origin, kx, ky, kz);
  q0.x += sx * q0.z;
  q0.y += sy * q0.z;
  q1.x += sx * q1.z;
  q1.y += sy * q1.z;
  q2.x += sx * q2.z;
  q2.y += sy * q2.z;

  // Edge functions: the ray passes inside when all three have the same sign (or are zero).
  const double e0 = q1.x * q2.y - q1.y * q2.x;
  const double e1 = q2.x * q0.y - q2.y * q0.x;
  const double e2 = q0.x * q1.y - q0.y * q1.x;
  if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
  const double det = e0 + e1 + e2;
  if (!(det != 0) || !std::isfinite(det)) return false;

  // Scaled distance, compared with 0 and t_max before the division.
  q0.z *= sz;
  q1.z *= sz;
  q2.z *= sz;
  const double t_scaled = e0 * q0.z + e1 * q1.z + e2 * q2.z;
  if (det < 0 && (t_scaled >= 0 || t_scaled < t_max * det)) return false;
  if (det > 0 && (t_scaled <= 0 || t_scaled > t_max * det)) return false;

  const double inv_det = 1 / det;
  const double t = t_scaled * inv_det;

  // pbrt-v3 §3.9.6: t must exceed the bound on its own rounding error.
  const double max_zt = max_component(abs(Vec3{q0.z, q1.z, q2.z}));
  const double delta_z = gamma_bound(3) * max_zt;
  const double max_xt = max_component(abs(Vec3{q0.x, q1.x, q2.x}));
  const double max_yt = max_component(abs(Vec3{q0.y, q1.y, q2.y}));
  const double delta_x = gamma_bound(5) * (max_xt + max_zt);
  const double delta_y = gamma_bound(5) * (max_yt + max_zt);
  const double delta_e =
      2 * (gamma_bound(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  const double max_e = max_component(abs(Vec3{e0, e1, e2}));
  const double delta_t = 3 *
                         (gamma_bound(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) *
                         std::fabs(inv_det);
  if (!(t > delta_t) || !(t < t_max)) return false;

  hit.t = t;
  hit.b0 = e0 * inv_det;
  hit.b1 = e1 * inv_det;
  hit.b2 = e2 * inv_det;
  return true;
}

bool intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray,
                        double t_max, TriangleHit& hit) {
  if (triangle_is_degenerate(p0, p1, p2)) return false;
  return intersect_triangle(p0, p1, p2, prepare_triangle_ray(ray), t_max, hit);
}

LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, bool interpolate_normals,
                            const TriangleHit& hit) {
  const MeshTriangle& tri = mesh.triangles[index];
  const Vec3& p0 = mesh.positions[tri.v[0]];
  const Vec3& p1 = mesh.positions[tri.v[1]];
  const Vec3& p2 = mesh.positions[tri.v[2]];
  const Vec3 w0 = p0 * hit.b0, w1 = p1 * hit.b1, w2 = p2 * hit.b2;

  LocalHit out;
  out.t = hit.t;
  out.point = w0 + w1 + w2;
  // pbrt-v3 §3.9.6: the barycentric combination is within gamma(7) of its absolute sum.
  out.point_error = (abs(w0) + abs(w1) + abs(w2)) * gamma_bound(7);
  out.normal = cross(p1 - p0, p2 - p0);
  out.shading_normal = out.normal;
  out.part = index;

  const bool has_normals = tri.n[0] != MeshTriangle::kNoNormal &&
                           tri.n[1] != MeshTriangle::kNoNormal &&
                           tri.n[2] != MeshTriangle::kNoNormal;
  if (interpolate_normals && has_normals) {
    const Vec3 n = mesh.normals[tri.n[0]] * hit.b0 + mesh.normals[tri.n[1]] * hit.b1 +
                   mesh.normals[tri.n[2]] * hit.b2;
    // A vanishing interpolation (opposite corner normals) falls back to the geometric normal.
    const Vec3 geometric = normalize_or(out.normal, Vec3{0, 0, 1});
    const double len = length(n);
    if (len > 1e-8 * (length(mesh.normals[tri.n[0]]) + length(mesh.normals[tri.n[1]]) +
                      length(mesh.normals[tri.n[2]])))
      out.shading_normal = normalize_or(n, geometric);
  }
  return out;
}

}  // namespace tessera
