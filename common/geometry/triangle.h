// Watertight ray/triangle intersection (Woop, Benthin and Wald 2013; pbrt-v3 §3.6.2), the
// building block of mesh intersection (shapes.h) and of brute-force checks in tests.
#pragma once

#include <cstdint>

#include "common/geometry/local_hit.h"
#include "common/math/ray.h"
#include "common/scene/mesh.h"

namespace tessera {

struct TriangleHit {
  double t = 0;
  double b0 = 0, b1 = 0, b2 = 0;  // barycentric coordinates of the hit
};

// Nearest hit with t in (0, t_max) of the ray with the triangle p0 p1 p2. Rays through a shared
// edge or vertex of a closed mesh hit at least one of its triangles; degenerate triangles are
// never hit; t is conservatively positive (a ray leaving the triangle's plane from an origin
// offset by the hit's error bound does not hit it again).
bool intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Ray& ray,
                        double t_max, TriangleHit& hit);

// The same test split for meshes, where one ray meets many triangles: the ray's share of the
// work (axis permutation and shear) done once, and the degeneracy check done once per triangle
// when the mesh is prepared. The results are bit-identical to the call above.
struct TriangleRay {
  Vec3 origin;
  int kx = 0, ky = 1, kz = 2;  // the direction's largest component is kz
  double sx = 0, sy = 0, sz = 0;
  bool usable = false;  // false for a zero or non-finite direction, which hits nothing
};
TriangleRay prepare_triangle_ray(const Ray& ray);
// Zero or non-finite area: never hit.
bool triangle_is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2);
// For a triangle that is not degenerate.
bool intersect_triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const TriangleRay& ray,
                        double t_max, TriangleHit& hit);

// The local hit on triangle `index` of `mesh`: point with its error bound, geometric normal
// (p1 - p0) x (p2 - p0), and the shading normal interpolated from the corners' normals when
// `interpolate_normals` is set and every corner has one.
LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, bool interpolate_normals,
                            const TriangleHit& hit);

}  // namespace tessera
