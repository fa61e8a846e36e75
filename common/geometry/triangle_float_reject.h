// A float pre-test for the triangles of a mesh leaf that only rejects: four triangles' corners
// in float (half the bytes of the double corners, MeshAccel::leaf_quads), tested first against a
// ray; a lane it cannot prove missed goes on to the double watertight test (triangle.h,
// intersect_triangle_pair.h), which still decides every hit, so hits are bit for bit those of the
// double test alone. A lane is rejected only when two of its float edge functions have opposite
// signs by more than an a-priori bound on the float error, so that the double test's edge
// functions have opposite signs too (docs/STABILITY.md "A float reject test for leaves").
#pragma once

#include <algorithm>
#include <cmath>

#include "common/geometry/triangle.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

// |x| rounded to a float no smaller than it.
inline float float_magnitude_up(double x) {
  const double a = std::fabs(x);
  const auto f = static_cast<float>(a);
  return static_cast<double>(f) < a ? std::nextafter(f, HUGE_VALF) : f;
}

// Four triangles' corners in float, structure of arrays (corner[c][axis][lane]) so that one load
// brings a coordinate of all four, each rounded to nearest from the double corner. magnitude[l]
// bounds every |coordinate| of lane l's double corners (rounded up); NaN marks a lane the double
// test never hits (padding, degenerate triangles), which the pre-test rejects.
struct alignas(16) FloatTriangleQuad {
  float corner[3][3][4];
  float magnitude[4];
};

// Lane `lane` of `quad` never hit: a gap in a leaf, a degenerate triangle.
inline void set_float_quad_lane_never_hit(FloatTriangleQuad& quad, int lane) {
  for (auto& corner : quad.corner)
    for (auto& axis : corner) axis[lane] = std::nanf("");
  quad.magnitude[lane] = std::nanf("");
}

// Lane `lane` of `quad` for the triangle p[0] p[1] p[2].
inline void set_float_quad_lane(FloatTriangleQuad& quad, int lane, const Vec3 p[3]) {
  double magnitude = 0;
  for (int c = 0; c < 3; ++c) {
    const double coordinates[3] = {p[c].x, p[c].y, p[c].z};
    for (int axis = 0; axis < 3; ++axis) {
      quad.corner[c][axis][lane] = static_cast<float>(coordinates[axis]);
      magnitude = std::max(magnitude, std::fabs(coordinates[axis]));
    }
  }
  quad.magnitude[lane] = float_magnitude_up(magnitude);
}

// The ray's share of the pre-test, in the double test's permuted frame (TriangleRay's kx, ky,
// kz): its origin and shear rounded to nearest, and a bound on |origin| rounded up.
struct FloatTriangleRay {
  float origin[3];
  float sx, sy;
  float origin_magnitude;
};


inline FloatTriangleRay prepare_float_triangle_ray(const TriangleRay& ray) {
  FloatTriangleRay r;
  const Vec3 origin = permute_axes(ray.origin, ray.kx, ray.ky, ray.kz);
  r.origin[0] = static_cast<float>(origin.x);
  r.origin[1] = static_cast<float>(origin.y);
  r.origin[2] = static_cast<float>(origin.z);
  r.sx = static_cast<float>(ray.sx);
  r.sy = static_cast<float>(ray.sy);
  r.origin_magnitude = float_magnitude_up(max_component(abs(ray.origin)));
  return r;
}

// The bound B on |e_float - e_double| for each edge function e (STABILITY.md derives it). With
// u = 2^-24 (float's unit roundoff), T = magnitude + origin_magnitude (bounds |p| + |o| per
// axis) and Q = the largest |x|, |y| of the lane's sheared float corners: the float corners and
// origin are off by u T each and the translation and shear round three times, so each sheared
// coordinate is within 8 u T (+ O(u^2 T)) of its exact value; an edge function's two products and
// difference then add 4 Q (8 u T) + 2 (8 u T)^2 + 4 u Q^2, against which the double test's own
// error (u = 2^-53) is negligible. B = 2^-18 (T (Q + 2^-20 T) + Q^2) = 64 u (Q T + 16 u T^2 + Q^2)
// exceeds that 1.7 times over, enough for the rounding of B's own few operations; 2^-120 covers
// float's subnormal range, where rounding errors are absolute (up to 2^-150 an operation). Any
// infinity or NaN on the way (coordinates beyond float's range, overflowed products) makes B
// infinite or NaN, so that no lane is rejected.
inline constexpr float kFloatRejectScale = 0x1p-18f;
inline constexpr float kFloatRejectTranslation = 0x1p-20f;
inline constexpr float kFloatRejectFloor = 0x1p-120f;

// The scalar pre-test: the lanes of `quad` that the double test might hit, as bits (lane l: bit
// l). The SIMD path below computes the same IEEE operations per lane, in the same order.
inline unsigned float_triangle_survivors_scalar(const FloatTriangleQuad& quad,
                                                const TriangleRay& ray,
                                                const FloatTriangleRay& float_ray) {
  if (!ray.usable) return 0;
  const int axes[3] = {ray.kx, ray.ky, ray.kz};
  unsigned survivors = 0;
  for (int lane = 0; lane < 4; ++lane) {
    if (std::isnan(quad.magnitude[lane])) continue;
    float x[3], y[3];
    for (int c = 0; c < 3; ++c) {
      const float dx = quad.corner[c][axes[0]][lane] - float_ray.origin[0];
      const float dy = quad.corner[c][axes[1]][lane] - float_ray.origin[1];
      const float dz = quad.corner[c][axes[2]][lane] - float_ray.origin[2];
      x[c] = dx + float_ray.sx * dz;
      y[c] = dy + float_ray.sy * dz;
    }
    const float e0 = x[1] * y[2] - y[1] * x[2];
    const float e1 = x[2] * y[0] - y[2] * x[0];
    const float e2 = x[0] * y[1] - y[0] * x[1];
    // m = m < v ? v : m, which maxps(v, m) computes, NaN included.
    float q = std::fabs(x[0]);
    for (const float v : {y[0], x[1], y[1], x[2], y[2]}) q = q < std::fabs(v) ? std::fabs(v) : q;
    const float t = quad.magnitude[lane] + float_ray.origin_magnitude;
    const float bound =
        (t * (q + kFloatRejectTranslation * t) + q * q) * kFloatRejectScale + kFloatRejectFloor;
    const float minus_bound = 0.0f - bound;
    const bool negative = (e0 < minus_bound) | (e1 < minus_bound) | (e2 < minus_bound);
    const bool positive = (e0 > bound) | (e1 > bound) | (e2 > bound);
    if (!(negative & positive)) survivors |= 1u << lane;
  }
  return survivors;
}

#if defined(__SSE2__)
// The four lanes at once with SSE (part of every x86-64 CPU; compiled into the AVX2 traversal it
// keeps its operations, only their encoding changes).
[[gnu::always_inline]] inline unsigned float_triangle_survivors_sse(
    const FloatTriangleQuad& quad, const TriangleRay& ray, const FloatTriangleRay& float_ray) {
  if (!ray.usable) return 0;
  const __m128 origin_x = _mm_set1_ps(float_ray.origin[0]);
  const __m128 origin_y = _mm_set1_ps(float_ray.origin[1]);
  const __m128 origin_z = _mm_set1_ps(float_ray.origin[2]);
  const __m128 shear_x = _mm_set1_ps(float_ray.sx);
  const __m128 shear_y = _mm_set1_ps(float_ray.sy);
  const __m128 abs_bits = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  __m128 x[3], y[3];
  for (int c = 0; c < 3; ++c) {
    const __m128 dx = _mm_sub_ps(_mm_load_ps(quad.corner[c][ray.kx]), origin_x);
    const __m128 dy = _mm_sub_ps(_mm_load_ps(quad.corner[c][ray.ky]), origin_y);
    const __m128 dz = _mm_sub_ps(_mm_load_ps(quad.corner[c][ray.kz]), origin_z);
    x[c] = _mm_add_ps(dx, _mm_mul_ps(shear_x, dz));
    y[c] = _mm_add_ps(dy, _mm_mul_ps(shear_y, dz));
  }
  const __m128 e0 = _mm_sub_ps(_mm_mul_ps(x[1], y[2]), _mm_mul_ps(y[1], x[2]));
  const __m128 e1 = _mm_sub_ps(_mm_mul_ps(x[2], y[0]), _mm_mul_ps(y[2], x[0]));
  const __m128 e2 = _mm_sub_ps(_mm_mul_ps(x[0], y[1]), _mm_mul_ps(y[0], x[1]));
  __m128 q = _mm_and_ps(x[0], abs_bits);
  q = _mm_max_ps(_mm_and_ps(y[0], abs_bits), q);
  q = _mm_max_ps(_mm_and_ps(x[1], abs_bits), q);
  q = _mm_max_ps(_mm_and_ps(y[1], abs_bits), q);
  q = _mm_max_ps(_mm_and_ps(x[2], abs_bits), q);
  q = _mm_max_ps(_mm_and_ps(y[2], abs_bits), q);
  const __m128 magnitude = _mm_load_ps(quad.magnitude);
  const __m128 t = _mm_add_ps(magnitude, _mm_set1_ps(float_ray.origin_magnitude));
  const __m128 spread =
      _mm_mul_ps(t, _mm_add_ps(q, _mm_mul_ps(_mm_set1_ps(kFloatRejectTranslation), t)));
  const __m128 bound =
      _mm_add_ps(_mm_mul_ps(_mm_add_ps(spread, _mm_mul_ps(q, q)), _mm_set1_ps(kFloatRejectScale)),
                 _mm_set1_ps(kFloatRejectFloor));
  const __m128 minus_bound = _mm_sub_ps(_mm_setzero_ps(), bound);
  const __m128 negative = _mm_or_ps(
      _mm_or_ps(_mm_cmplt_ps(e0, minus_bound), _mm_cmplt_ps(e1, minus_bound)),
      _mm_cmplt_ps(e2, minus_bound));
  const __m128 positive = _mm_or_ps(
      _mm_or_ps(_mm_cmpgt_ps(e0, bound), _mm_cmpgt_ps(e1, bound)), _mm_cmpgt_ps(e2, bound));
  const __m128 rejected = _mm_or_ps(_mm_and_ps(negative, positive),
                                    _mm_cmpunord_ps(magnitude, magnitude));
  return static_cast<unsigned>(_mm_movemask_ps(rejected)) ^ 15u;
}
#endif

// The lanes of `quad` the double test might hit, with SSE where the build has it.
[[gnu::always_inline]] inline unsigned float_triangle_survivors(const FloatTriangleQuad& quad,
                                                                const TriangleRay& ray,
                                                                const FloatTriangleRay& float_ray) {
#if defined(__SSE2__)
  return float_triangle_survivors_sse(quad, ray, float_ray);
#else
  return float_triangle_survivors_scalar(quad, ray, float_ray);
#endif
}

}  // namespace tessera
