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

// The local hit on triangle `index` of `mesh`: point with its error bound, geometric normal
// (p1 - p0) x (p2 - p0), and the shading normal interpolated from the corners' normals when
// `interpolate_normals` is set and every corner has one.
LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, bool interpolate_normals,
                            const TriangleHit& hit);

}  // namespace tessera
