#include "common/geometry/triangle.h"

#include <cmath>

#include "common/math/float_error.h"

namespace tessera {

bool triangle_is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const double area2 = length_squared(cross(p1 - p0, p2 - p0));
  return !(area2 > 0) || !std::isfinite(area2);
}

bool intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray,
                        double t_max, TriangleHit& hit) {
  if (triangle_is_degenerate(p0, p1, p2)) return false;
  return intersect_triangle(p0, p1, p2, prepare_triangle_ray(ray), t_max, hit);
}

LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, bool interpolate_normals,
                            const TriangleHit& hit) {
  const MeshTriangle& tri = mesh.triangles[index];
  return triangle_local_hit(mesh, index, mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                            mesh.positions[tri.v[2]], interpolate_normals, hit);
}

LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, const Vec3& p0, const Vec3& p1,
                            const Vec3& p2, bool interpolate_normals, const TriangleHit& hit) {
  const Vec3 w0 = p0 * hit.b0, w1 = p1 * hit.b1, w2 = p2 * hit.b2;

  LocalHit out;
  out.t = hit.t;
  out.point = w0 + w1 + w2;
  // pbrt-v3 §3.9.6: the barycentric combination is within gamma(7) of its absolute sum.
  out.point_error = (abs(w0) + abs(w1) + abs(w2)) * gamma_bound(7);
  out.normal = cross(p1 - p0, p2 - p0);
  out.shading_normal = out.normal;
  out.part = index;

  if (!interpolate_normals) return out;
  const MeshTriangle& tri = mesh.triangles[index];
  const bool has_normals = tri.n[0] != MeshTriangle::kNoNormal &&
                           tri.n[1] != MeshTriangle::kNoNormal &&
                           tri.n[2] != MeshTriangle::kNoNormal;
  if (has_normals) {
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
