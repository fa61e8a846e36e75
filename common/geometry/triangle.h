// Watertight ray/triangle intersection (Woop, Benthin and Wald 2013; pbrt-v3 §3.6.2), the
// building block of mesh intersection (shapes.h) and of brute-force checks in tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "common/geometry/local_hit.h"
#include "common/math/float_error.h"
#include "common/math/ray.h"
#include "common/scene/mesh.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
// Zero or non-finite area: never hit.
bool triangle_is_degenerate(const Vec3& p0, const Vec3& p1, const Vec3& p2);
// The components of v in the order x, y, z. Indexed through an array rather than Vec3's
// operator[], whose branches on the axis mispredicted once per triangle (the axes change from
// ray to ray).
inline Vec3 permute_axes(const Vec3& v, int x, int y, int z) {
  const double c[3] = {v.x, v.y, v.z};
  return {c[x], c[y], c[z]};
}
// Inline: a mesh ray makes it once, before its traversal, and as a call its result went through
// memory field by field (docs/PERFORMANCE.md "An incoherent ray's set-up").
inline TriangleRay prepare_triangle_ray(const Ray& ray) {
  // Translate the vertices so that the ray starts at the origin, permute the axes so that the
  // direction's largest component is z, and shear so that the ray runs along +z. Every vertex
  // is transformed the same way whichever triangle it belongs to, which makes the edge
  // functions of a shared edge exactly opposite (watertightness).
  TriangleRay r;
  r.origin = ray.origin;
  const Vec3& d = ray.direction;
  // max_axis(abs(d)) without its branches, which mispredict for incoherent rays (the largest
  // axis is a coin toss among three): the same axis, NaN included (comparisons with a NaN are
  // false in both).
  const Vec3 m = abs(d);
  const bool x_over_y = m.x > m.y, x_over_z = m.x > m.z, y_over_z = m.y > m.z;
  r.kz = 2 - 2 * static_cast<int>(x_over_y & x_over_z) - static_cast<int>(!x_over_y & y_over_z);
  // The next two axes, cyclically (kx = kz == 2 ? 0 : kz + 1, ky after kx), read from two-bit
  // tables by shifts: GCC turns the ternaries (and their arithmetic forms) into a branch on kz.
  r.kx = (0b00'10'01 >> (2 * r.kz)) & 3;
  r.ky = (0b01'00'10 >> (2 * r.kz)) & 3;
  const Vec3 dp = permute_axes(d, r.kx, r.ky, r.kz);
  // is_finite(dp) as is_finite(d) (the same components) without its short-circuit branches: a
  // magnitude is at most the largest double unless it is infinite or NaN.
  constexpr double kLargest = std::numeric_limits<double>::max();
  r.usable = (dp.z != 0) & (m.x <= kLargest) & (m.y <= kLargest) & (m.z <= kLargest);
#if defined(__SSE2__)
  // -dp.x / dp.z and -dp.y / dp.z in the lanes of one divpd, the same IEEE divisions: inline,
  // GCC made the three divisions three divsd, three uses of the divider at the ray's start.
  const __m128d s = _mm_div_pd(_mm_set_pd(-dp.y, -dp.x), _mm_set1_pd(dp.z));
  r.sx = _mm_cvtsd_f64(s);
  r.sy = _mm_cvtsd_f64(_mm_unpackhi_pd(s, s));
#else
  r.sx = -dp.x / dp.z;
  r.sy = -dp.y / dp.z;
#endif
  r.sz = 1 / dp.z;
  return r;
}
// For a triangle that is not degenerate. Always inline: the mesh loops call it for every triangle
// of every leaf they reach, and a caller that ignores the barycentric coordinates (shadow rays)
// lets the compiler drop them.
[[gnu::always_inline]] inline bool intersect_triangle(const Vec3& p0, const Vec3& p1,
                                                      const Vec3& p2, const TriangleRay& ray,
                                                      double t_max, TriangleHit& hit) {
  if (!ray.usable) return false;
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const double sx = ray.sx, sy = ray.sy, sz = ray.sz;
  Vec3 q0 = permute_axes(p0 - ray.origin, kx, ky, kz);
  Vec3 q1 = permute_axes(p1 - ray.origin, kx, ky, kz);
  Vec3 q2 = permute_axes(p2 - ray.origin, kx, ky, kz);
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
  // Non-short-circuit operators: one branch, taken for most triangles a ray meets, instead of
  // one per sign test, a tenth of a mesh trace's mispredictions (callgrind's model).
  const bool some_negative = (e0 < 0) | (e1 < 0) | (e2 < 0);
  const bool some_positive = (e0 > 0) | (e1 > 0) | (e2 > 0);
  if (some_negative & some_positive) return false;
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

// The local hit on triangle `index` of `mesh`: point with its error bound, geometric normal
// (p1 - p0) x (p2 - p0), and the shading normal interpolated from the corners' normals when
// `interpolate_normals` is set and every corner has one.
LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, bool interpolate_normals,
                            const TriangleHit& hit);
// The same from the triangle's corners p0 p1 p2 (equal to its mesh positions) as the caller has
// them at hand: a mesh trace has just loaded them from its leaf (MeshAccel::leaf_quads), where
// the mesh's index and position arrays would be two more cache misses per hit. The mesh is read
// only for interpolated normals.
LocalHit triangle_local_hit(const Mesh& mesh, std::uint32_t index, const Vec3& p0, const Vec3& p1,
                            const Vec3& p2, bool interpolate_normals, const TriangleHit& hit);

}  // namespace tessera
