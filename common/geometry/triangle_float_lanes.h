// A float test of several mesh triangles against one ray that decides what it can prove and
// leaves the rest to the double test (intersect_triangle_pair.h): four lanes with SSE, eight
// (two adjacent quads of MeshAccel::leaf_quads) with AVX2. It computes the double test's
// quantities (the corners translated, permuted and sheared, the edge functions, det and the
// scaled distance) in float, with an a-priori bound on how far each may lie from the double
// test's value, and reports a lane
// - missed when the double test must miss it: two edge functions of opposite signs beyond the
//   bound, or a scaled distance at or behind the origin, or beyond t_max;
// - hit (only asked for by any-hit queries) when the double test must hit it: three edge
//   functions of one sign beyond the bound and t inside (delta_t, t_max) beyond the bound;
// - undecided otherwise (the double test decides).
// Neither decision changes a result: a lane reported missed is one the double test misses, and
// an any-hit query's answer is yes or no. Each path computes the same IEEE float operations in
// the same order (no FMA), so the decisions are the same on every path too.
//
// The bounds, with u = 2^-24 (float's unit roundoff), T a lane's largest |coordinate| plus the
// origin's, Q the largest |x|, |y| of its sheared float corners, Z the largest |z| (scaled by
// sz), E the largest |edge function|:
// - a sheared x or y is off by at most 8 u T (rounding the corner, the origin and the shear,
//   then the subtraction, product and sum), z by 4 u T |sz|, counted as 8 u T |sz|;
// - an edge function by 4 Q 8uT + 2 (8uT)^2 + 4 u Q^2, which B = 2^-18 (T (Q + 2^-20 T) + Q^2)
//   + 2^-120 covers twice over (2^-120: float's subnormal products), with the double test's own
//   error (2^29 times smaller);
// - det, three edge functions summed with two roundings, by 4 B + 2^-20 E;
// - the scaled distance sum e_i z_i by 4 (E dz + B (Z + dz)) + 2^-19 E Z, to which
//   2^-44 Q Z^2 is added so that the bound also covers the double test's delta_t det
//   (pbrt-v3's bound: 18 eps E Z + 132 eps Q (Q + Z) Z, eps = 2^-53).
// Anything that overflows makes a bound infinite or a quantity NaN: every decision compares in
// the ordered sense, so such a lane stays undecided.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "common/geometry/intersect_triangle_pair.h"
#include "common/geometry/triangle_pair.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

// The ray as the float lanes take it: the double test's permuted origin and shear in float, and
// the origin's largest |coordinate| rounded up.
struct FloatLanesRay {
  int kx, ky, kz;
  float origin[3];
  float sx, sy, sz;
  float origin_magnitude;
};

inline FloatLanesRay prepare_float_lanes_ray(const TriangleLanesRay& lanes_ray) {
  FloatLanesRay r;
  r.kx = lanes_ray.ray.kx, r.ky = lanes_ray.ray.ky, r.kz = lanes_ray.ray.kz;
  for (int a = 0; a < 3; ++a) r.origin[a] = static_cast<float>(lanes_ray.origin[a]);
  r.sx = static_cast<float>(lanes_ray.ray.sx);
  r.sy = static_cast<float>(lanes_ray.ray.sy);
  r.sz = static_cast<float>(lanes_ray.ray.sz);
  const double m = std::max({std::fabs(lanes_ray.origin[0]), std::fabs(lanes_ray.origin[1]),
                             std::fabs(lanes_ray.origin[2])});
  r.origin_magnitude = static_cast<float>(m) * (1 + 0x1p-20f);
  return r;
}

// The lanes' decisions as bits (bit l: lane l).
struct FloatLaneDecisions {
  unsigned undecided = 0;
  unsigned hit = 0;
};

#if defined(__SSE2__)
struct Sse2FloatLanes {
  using V = __m128;
  static constexpr int kLanes = 4;
  [[gnu::always_inline]] static void set1(V& r, float x) { r = _mm_set1_ps(x); }
  [[gnu::always_inline]] static void load_corner(V& r, const FloatTriangleQuad* quads, int c,
                                                 int axis) {
    r = _mm_load_ps(quads[0].corner[c][axis]);
  }
  [[gnu::always_inline]] static void load_magnitude(V& r, const FloatTriangleQuad* quads) {
    r = _mm_load_ps(quads[0].magnitude);
  }
  [[gnu::always_inline]] static void add(V& r, const V& a, const V& b) { r = _mm_add_ps(a, b); }
  [[gnu::always_inline]] static void sub(V& r, const V& a, const V& b) { r = _mm_sub_ps(a, b); }
  [[gnu::always_inline]] static void mul(V& r, const V& a, const V& b) { r = _mm_mul_ps(a, b); }
  [[gnu::always_inline]] static void max(V& r, const V& a, const V& b) { r = _mm_max_ps(a, b); }
  [[gnu::always_inline]] static void bit_and(V& r, const V& a, const V& b) { r = _mm_and_ps(a, b); }
  [[gnu::always_inline]] static void bit_or(V& r, const V& a, const V& b) { r = _mm_or_ps(a, b); }
  [[gnu::always_inline]] static void bit_xor(V& r, const V& a, const V& b) { r = _mm_xor_ps(a, b); }
  [[gnu::always_inline]] static void lt(V& r, const V& a, const V& b) { r = _mm_cmplt_ps(a, b); }
  [[gnu::always_inline]] static void le(V& r, const V& a, const V& b) { r = _mm_cmple_ps(a, b); }
  [[gnu::always_inline]] static void gt(V& r, const V& a, const V& b) { r = _mm_cmpgt_ps(a, b); }
  [[gnu::always_inline]] static void ge(V& r, const V& a, const V& b) { r = _mm_cmpge_ps(a, b); }
  [[gnu::always_inline]] static void unordered(V& r, const V& a, const V& b) {
    r = _mm_cmpunord_ps(a, b);
  }
  [[gnu::always_inline]] static unsigned mask(const V& a) {
    return static_cast<unsigned>(_mm_movemask_ps(a));
  }
};

// Two adjacent quads, lanes 0-3 from the first; no FMA.
struct Avx2FloatLanes {
  using V = __m256;
  static constexpr int kLanes = 8;
  [[gnu::target("avx2")]] static void set1(V& r, float x) { r = _mm256_set1_ps(x); }
  [[gnu::target("avx2")]] static void load_corner(V& r, const FloatTriangleQuad* quads, int c,
                                                  int axis) {
    r = _mm256_loadu2_m128(quads[1].corner[c][axis], quads[0].corner[c][axis]);
  }
  [[gnu::target("avx2")]] static void load_magnitude(V& r, const FloatTriangleQuad* quads) {
    r = _mm256_loadu2_m128(quads[1].magnitude, quads[0].magnitude);
  }
  [[gnu::target("avx2")]] static void add(V& r, const V& a, const V& b) { r = _mm256_add_ps(a, b); }
  [[gnu::target("avx2")]] static void sub(V& r, const V& a, const V& b) { r = _mm256_sub_ps(a, b); }
  [[gnu::target("avx2")]] static void mul(V& r, const V& a, const V& b) { r = _mm256_mul_ps(a, b); }
  [[gnu::target("avx2")]] static void max(V& r, const V& a, const V& b) { r = _mm256_max_ps(a, b); }
  [[gnu::target("avx2")]] static void bit_and(V& r, const V& a, const V& b) {
    r = _mm256_and_ps(a, b);
  }
  [[gnu::target("avx2")]] static void bit_or(V& r, const V& a, const V& b) {
    r = _mm256_or_ps(a, b);
  }
  [[gnu::target("avx2")]] static void bit_xor(V& r, const V& a, const V& b) {
    r = _mm256_xor_ps(a, b);
  }
  [[gnu::target("avx2")]] static void lt(V& r, const V& a, const V& b) {
    r = _mm256_cmp_ps(a, b, _CMP_LT_OS);
  }
  [[gnu::target("avx2")]] static void le(V& r, const V& a, const V& b) {
    r = _mm256_cmp_ps(a, b, _CMP_LE_OS);
  }
  [[gnu::target("avx2")]] static void gt(V& r, const V& a, const V& b) {
    r = _mm256_cmp_ps(a, b, _CMP_GT_OS);
  }
  [[gnu::target("avx2")]] static void ge(V& r, const V& a, const V& b) {
    r = _mm256_cmp_ps(a, b, _CMP_GE_OS);
  }
  [[gnu::target("avx2")]] static void unordered(V& r, const V& a, const V& b) {
    r = _mm256_cmp_ps(a, b, _CMP_UNORD_Q);
  }
  [[gnu::target("avx2")]] static unsigned mask(const V& a) {
    return static_cast<unsigned>(_mm256_movemask_ps(a));
  }
};

// The decisions for the lanes in `lanes` (bits) of the quads from `quads` on; `t_max` as the
// double test's. Hits are decided only when kDecideHits.
template <typename Lanes, bool kDecideHits>
[[gnu::always_inline]] inline FloatLaneDecisions decide_triangle_float_lanes(
    const FloatTriangleQuad* quads, const FloatLanesRay& r, double t_max, unsigned lanes) {
  using V = typename Lanes::V;
  V origin_x, origin_y, origin_z, shear_x, shear_y, shear_z, product;
  Lanes::set1(origin_x, r.origin[0]);
  Lanes::set1(origin_y, r.origin[1]);
  Lanes::set1(origin_z, r.origin[2]);
  Lanes::set1(shear_x, r.sx);
  Lanes::set1(shear_y, r.sy);
  Lanes::set1(shear_z, r.sz);
  struct Corner {
    V x, y, z;
  };
  const auto transform = [&](Corner& q, int c) {
    Lanes::load_corner(q.x, quads, c, r.kx);
    Lanes::load_corner(q.y, quads, c, r.ky);
    Lanes::load_corner(q.z, quads, c, r.kz);
    Lanes::sub(q.x, q.x, origin_x);
    Lanes::sub(q.y, q.y, origin_y);
    Lanes::sub(q.z, q.z, origin_z);
    Lanes::mul(product, shear_x, q.z);
    Lanes::add(q.x, q.x, product);
    Lanes::mul(product, shear_y, q.z);
    Lanes::add(q.y, q.y, product);
  };
  Corner q0, q1, q2;
  transform(q0, 0);
  transform(q1, 1);
  transform(q2, 2);
  const auto edge = [&](V& e, const Corner& a, const Corner& b) {
    Lanes::mul(e, a.x, b.y);
    Lanes::mul(product, a.y, b.x);
    Lanes::sub(e, e, product);
  };
  V e0, e1, e2;
  edge(e0, q1, q2);
  edge(e1, q2, q0);
  edge(e2, q0, q1);
  V abs_bits, sign_bit;
  Lanes::set1(abs_bits, std::bit_cast<float>(0x7fffffffu));
  Lanes::set1(sign_bit, -0.0f);
  const auto abs = [&](V& v, const V& a) { Lanes::bit_and(v, a, abs_bits); };
  const auto max_abs = [&](V& m, const V& a, const V& b, const V& c) {
    V next;
    abs(m, a);
    abs(next, b);
    Lanes::max(m, next, m);
    abs(next, c);
    Lanes::max(m, next, m);
  };
  // v = k * a, for v other than a.
  const auto times = [&](V& v, float k, const V& a) {
    Lanes::set1(v, k);
    Lanes::mul(v, v, a);
  };
  // B = 2^-18 (T (Q + 2^-20 T) + Q^2) + 2^-120.
  V t_bound, q_bound, q_bound_y, bound, term;
  Lanes::load_magnitude(t_bound, quads);
  // A lane without a triangle (NaN magnitude) is missed.
  V no_triangle;
  Lanes::unordered(no_triangle, t_bound, t_bound);
  Lanes::set1(term, r.origin_magnitude);
  Lanes::add(t_bound, t_bound, term);
  max_abs(q_bound, q0.x, q1.x, q2.x);
  max_abs(q_bound_y, q0.y, q1.y, q2.y);
  Lanes::max(q_bound, q_bound_y, q_bound);
  times(bound, 0x1p-20f, t_bound);
  Lanes::add(bound, bound, q_bound);
  Lanes::mul(bound, bound, t_bound);
  Lanes::mul(product, q_bound, q_bound);
  Lanes::add(bound, bound, product);
  Lanes::set1(term, 0x1p-18f);
  Lanes::mul(bound, bound, term);
  Lanes::set1(term, 0x1p-120f);
  Lanes::add(bound, bound, term);
  V minus_bound, some_negative, some_positive, compared;
  Lanes::bit_xor(minus_bound, bound, sign_bit);
  Lanes::lt(some_negative, e0, minus_bound);
  Lanes::lt(compared, e1, minus_bound);
  Lanes::bit_or(some_negative, some_negative, compared);
  Lanes::lt(compared, e2, minus_bound);
  Lanes::bit_or(some_negative, some_negative, compared);
  Lanes::gt(some_positive, e0, bound);
  Lanes::gt(compared, e1, bound);
  Lanes::bit_or(some_positive, some_positive, compared);
  Lanes::gt(compared, e2, bound);
  Lanes::bit_or(some_positive, some_positive, compared);
  V missed;
  Lanes::bit_and(missed, some_negative, some_positive);
  Lanes::bit_or(missed, missed, no_triangle);
  FloatLaneDecisions decisions;
  decisions.undecided = lanes & ~Lanes::mask(missed);
  if (decisions.undecided == 0) return decisions;

  Lanes::mul(q0.z, q0.z, shear_z);
  Lanes::mul(q1.z, q1.z, shear_z);
  Lanes::mul(q2.z, q2.z, shear_z);
  V det, t_scaled;
  Lanes::add(det, e0, e1);
  Lanes::add(det, det, e2);
  Lanes::mul(t_scaled, e0, q0.z);
  Lanes::mul(product, e1, q1.z);
  Lanes::add(t_scaled, t_scaled, product);
  Lanes::mul(product, e2, q2.z);
  Lanes::add(t_scaled, t_scaled, product);
  V max_e, max_z, dz, det_bound, t_bound_scaled;
  max_abs(max_e, e0, e1, e2);
  max_abs(max_z, q0.z, q1.z, q2.z);
  // dz = 2^-21 T |sz|
  Lanes::set1(term, std::fabs(r.sz) * 0x1p-21f);
  Lanes::mul(dz, t_bound, term);
  // det's bound: 4 B + 2^-20 E
  times(det_bound, 4.0f, bound);
  times(term, 0x1p-20f, max_e);
  Lanes::add(det_bound, det_bound, term);
  // The scaled distance's: 4 (E dz + B (Z + dz)) + 2^-19 E Z + 2^-44 Q Z^2
  Lanes::add(term, max_z, dz);
  Lanes::mul(term, term, bound);
  Lanes::mul(product, max_e, dz);
  Lanes::add(term, term, product);
  times(t_bound_scaled, 4.0f, term);
  times(term, 0x1p-19f, max_e);
  Lanes::mul(term, term, max_z);
  Lanes::add(t_bound_scaled, t_bound_scaled, term);
  times(term, 0x1p-44f, q_bound);
  Lanes::mul(term, term, max_z);
  Lanes::mul(term, term, max_z);
  Lanes::add(t_bound_scaled, t_bound_scaled, term);
  // With det's sign known, the scaled distance on det's side: t = t_scaled / det.
  V det_sign, abs_det, sign_known, t_side, far, far_end;
  Lanes::bit_and(det_sign, det, sign_bit);
  abs(abs_det, det);
  Lanes::gt(sign_known, abs_det, det_bound);
  Lanes::bit_xor(t_side, t_scaled, det_sign);
  // Behind: t_side + bound <= 0.
  V minus_t_bound;
  Lanes::bit_xor(minus_t_bound, t_bound_scaled, sign_bit);
  Lanes::le(compared, t_side, minus_t_bound);
  // Beyond: t_side - bound >= t_max (1 + 2^-20) (|det| + det's bound).
  // t_max rounded up (a float's smallest step added for t_max that round to 0).
  Lanes::set1(far_end, static_cast<float>(t_max) * (1 + 0x1p-20f) + 0x1p-149f);
  Lanes::add(term, abs_det, det_bound);
  Lanes::mul(far_end, far_end, term);
  Lanes::sub(far, t_side, t_bound_scaled);
  Lanes::ge(far, far, far_end);
  Lanes::bit_or(compared, compared, far);
  Lanes::bit_and(compared, compared, sign_known);
  Lanes::bit_or(missed, missed, compared);
  decisions.undecided = lanes & ~Lanes::mask(missed);
  if constexpr (kDecideHits) {
    // Hit: one sign beyond the bound on every edge function, t_side beyond its bound above 0
    // and below t_max (1 - 2^-20) (|det| - det's bound).
    V all_negative, all_positive, hit;
    Lanes::lt(all_negative, e0, minus_bound);
    Lanes::lt(compared, e1, minus_bound);
    Lanes::bit_and(all_negative, all_negative, compared);
    Lanes::lt(compared, e2, minus_bound);
    Lanes::bit_and(all_negative, all_negative, compared);
    Lanes::gt(all_positive, e0, bound);
    Lanes::gt(compared, e1, bound);
    Lanes::bit_and(all_positive, all_positive, compared);
    Lanes::gt(compared, e2, bound);
    Lanes::bit_and(all_positive, all_positive, compared);
    Lanes::bit_or(hit, all_negative, all_positive);
    Lanes::bit_and(hit, hit, sign_known);
    Lanes::gt(compared, t_side, t_bound_scaled);
    Lanes::bit_and(hit, hit, compared);
    // t_max rounded down (an infinite t_max stays so; a finite one beyond float's range is
    // taken as float's largest).
    const float t_max_down =
        std::isinf(t_max)
            ? std::numeric_limits<float>::infinity()
            : static_cast<float>(std::min(t_max, double{std::numeric_limits<float>::max()})) *
                  (1 - 0x1p-20f);
    Lanes::set1(far_end, t_max_down);
    Lanes::sub(term, abs_det, det_bound);
    Lanes::mul(far_end, far_end, term);
    Lanes::add(far, t_side, t_bound_scaled);
    Lanes::lt(compared, far, far_end);
    Lanes::bit_and(hit, hit, compared);
    decisions.hit = decisions.undecided & Lanes::mask(hit);
    decisions.undecided &= ~decisions.hit;
  }
  return decisions;
}
#endif

}  // namespace tessera
