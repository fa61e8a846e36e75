// Several triangles of a mesh leaf tested against one ray at once: the watertight test of
// triangle.h in double lanes, one triangle per lane (the layout: triangle_pair.h). Two at a time,
// a half of a quad, with SSE2, which is part of every x86-64 CPU; a whole quad with AVX2,
// which only the mesh traversal compiled for AVX2 uses (wide_bvh_traverse.h chooses it at run
// time); other CPUs run the scalar test once per lane. Each lane computes exactly the IEEE
// operations of the scalar test in the same order (nothing is fused: the build forbids
// contraction and the "avx2" target does not enable FMA; maxpd(b, a) is std::max(a, b), NaN
// included), so every path gives bit-identical hits (tests/geometry/triangle_pair_test.cpp).
#pragma once

#include <bit>
#include <limits>

#include "common/geometry/triangle.h"
#include "common/geometry/triangle_pair.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

// The most triangles one test covers: a quad.
inline constexpr int kTriangleLanesMax = 4;

// The hits of the lanes tested (meaningful only for the lanes reported hit).
struct TriangleLaneHits {
  alignas(32) double t[kTriangleLanesMax];
  alignas(32) double b0[kTriangleLanesMax];
  alignas(32) double b1[kTriangleLanesMax];
  alignas(32) double b2[kTriangleLanesMax];
  TriangleHit lane(int i) const { return {t[i], b0[i], b1[i], b2[i]}; }
};

// The scalar test of triangle.h once per lane of `quad` from `first_lane`, `lane_count` of them.
// Returns the lanes hit with t in (0, t_max) as bits of the quad's lanes (bit l: lane l, whose
// hit is hits' entry l), as every lane test does.
inline unsigned intersect_triangle_lanes_scalar(const TriangleQuad& quad, int first_lane,
                                                int lane_count, const TriangleRay& ray,
                                                double t_max, TriangleLaneHits& hits) {
  unsigned lanes = 0;
  for (int lane = first_lane; lane < first_lane + lane_count; ++lane) {
    TriangleHit h;
    if (!intersect_triangle(quad_corner(quad, 0, lane), quad_corner(quad, 1, lane),
                            quad_corner(quad, 2, lane), ray, t_max, h))
      continue;
    hits.t[lane] = h.t;
    hits.b0[lane] = h.b0;
    hits.b1[lane] = h.b1;
    hits.b2[lane] = h.b2;
    lanes |= 1u << lane;
  }
  return lanes;
}

// A ray prepared for the lane tests: the triangle test's ray, its permuted origin (components
// kx, ky, kz) and the byte offsets of coordinates kx, ky, kz in a corner of a TriangleQuad, once
// per ray rather than once per test: with the offsets, a quad's nine loads address their
// coordinate without a shift each (docs/PERFORMANCE.md "The leaf visit"). Small, as the leaf
// visitors hold a copy: repeating each value once per lane here cost more in stores and copies
// than the tests' broadcasts (one instruction each, from memory).
struct TriangleLanesRay {
  TriangleRay ray;
  double origin[3];
  int coordinate_offset[3];
};

// The triangle ray is initialized from prepare_triangle_ray's result in place (guaranteed copy
// elision, and the caller's closure receives `r` by NRVO): assigned instead, it went through a
// temporary copied with 16-byte loads across the callee's 8-, 4- and 1-byte stores, which the
// store buffer cannot forward, so each copy waited for the stores to reach the cache
// (docs/PERFORMANCE.md "The incoherent ray's stalls").
inline TriangleLanesRay prepare_triangle_lanes_ray(const Ray& ray) {
  TriangleLanesRay r{prepare_triangle_ray(ray), {}, {}};
  const Vec3 origin = permute_axes(ray.origin, r.ray.kx, r.ray.ky, r.ray.kz);
  r.origin[0] = origin.x;
  r.origin[1] = origin.y;
  r.origin[2] = origin.z;
  constexpr int kCoordinateBytes = sizeof(TriangleQuad::corner[0][0]);
  r.coordinate_offset[0] = r.ray.kx * kCoordinateBytes;
  r.coordinate_offset[1] = r.ray.ky * kCoordinateBytes;
  r.coordinate_offset[2] = r.ray.kz * kCoordinateBytes;
  return r;
}

#if defined(__SSE2__)
// The SIMD paths: one algorithm (intersect_triangle_lanes) over the double vectors of SSE2 (a
// quad's half) or AVX2 (the whole quad), as float_child_boxes.h does for boxes. The operations take
// and give vectors by reference: an AVX vector passed by value through a function compiled without
// AVX changes the ABI, and the algorithm is compiled for the baseline, to be inlined whole
// (gnu::flatten) into functions compiled for AVX2. Comparisons give lane masks; the AVX
// predicates are those of the SSE2 instructions (cmpltpd is _CMP_LT_OS, cmpnltpd _CMP_NLT_US).
struct Sse2DoubleLanes {
  using V = __m128d;
  static constexpr unsigned kAllLanes = 3;
  [[gnu::always_inline]] static void set1(V& r, double x) { r = _mm_set1_pd(x); }
  // A coordinate of the lanes' corners, from its first lane's (16-byte aligned in a quad).
  [[gnu::always_inline]] static void load(V& r, const double* lanes) { r = _mm_load_pd(lanes); }
  [[gnu::always_inline]] static void store(double* p, const V& a) { _mm_store_pd(p, a); }
  [[gnu::always_inline]] static void add(V& r, const V& a, const V& b) { r = _mm_add_pd(a, b); }
  [[gnu::always_inline]] static void sub(V& r, const V& a, const V& b) { r = _mm_sub_pd(a, b); }
  [[gnu::always_inline]] static void mul(V& r, const V& a, const V& b) { r = _mm_mul_pd(a, b); }
  [[gnu::always_inline]] static void div(V& r, const V& a, const V& b) { r = _mm_div_pd(a, b); }
  [[gnu::always_inline]] static void max(V& r, const V& a, const V& b) { r = _mm_max_pd(a, b); }
  [[gnu::always_inline]] static void bit_and(V& r, const V& a, const V& b) { r = _mm_and_pd(a, b); }
  [[gnu::always_inline]] static void bit_or(V& r, const V& a, const V& b) { r = _mm_or_pd(a, b); }
  // ~a & b.
  [[gnu::always_inline]] static void and_not(V& r, const V& a, const V& b) {
    r = _mm_andnot_pd(a, b);
  }
  [[gnu::always_inline]] static void lt(V& r, const V& a, const V& b) { r = _mm_cmplt_pd(a, b); }
  [[gnu::always_inline]] static void le(V& r, const V& a, const V& b) { r = _mm_cmple_pd(a, b); }
  [[gnu::always_inline]] static void gt(V& r, const V& a, const V& b) { r = _mm_cmpgt_pd(a, b); }
  [[gnu::always_inline]] static void ge(V& r, const V& a, const V& b) { r = _mm_cmpge_pd(a, b); }
  [[gnu::always_inline]] static void eq(V& r, const V& a, const V& b) { r = _mm_cmpeq_pd(a, b); }
  // !(a < b), true with a NaN.
  [[gnu::always_inline]] static void not_lt(V& r, const V& a, const V& b) {
    r = _mm_cmpnlt_pd(a, b);
  }
  [[gnu::always_inline]] static unsigned mask(const V& a) {
    return static_cast<unsigned>(_mm_movemask_pd(a));
  }
};

// A quad's four lanes; no FMA: the "avx2" target does not enable it.
struct Avx2DoubleLanes {
  using V = __m256d;
  static constexpr unsigned kAllLanes = 15;
  [[gnu::target("avx2")]] static void set1(V& r, double x) { r = _mm256_set1_pd(x); }
  // A coordinate of the quad's corners (32-byte aligned).
  [[gnu::target("avx2")]] static void load(V& r, const double* lanes) { r = _mm256_load_pd(lanes); }
  [[gnu::target("avx2")]] static void store(double* p, const V& a) { _mm256_store_pd(p, a); }
  [[gnu::target("avx2")]] static void add(V& r, const V& a, const V& b) { r = _mm256_add_pd(a, b); }
  [[gnu::target("avx2")]] static void sub(V& r, const V& a, const V& b) { r = _mm256_sub_pd(a, b); }
  [[gnu::target("avx2")]] static void mul(V& r, const V& a, const V& b) { r = _mm256_mul_pd(a, b); }
  [[gnu::target("avx2")]] static void div(V& r, const V& a, const V& b) { r = _mm256_div_pd(a, b); }
  [[gnu::target("avx2")]] static void max(V& r, const V& a, const V& b) { r = _mm256_max_pd(a, b); }
  [[gnu::target("avx2")]] static void bit_and(V& r, const V& a, const V& b) {
    r = _mm256_and_pd(a, b);
  }
  [[gnu::target("avx2")]] static void bit_or(V& r, const V& a, const V& b) {
    r = _mm256_or_pd(a, b);
  }
  [[gnu::target("avx2")]] static void and_not(V& r, const V& a, const V& b) {
    r = _mm256_andnot_pd(a, b);
  }
  [[gnu::target("avx2")]] static void lt(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_LT_OS);
  }
  [[gnu::target("avx2")]] static void le(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_LE_OS);
  }
  [[gnu::target("avx2")]] static void gt(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_GT_OS);
  }
  [[gnu::target("avx2")]] static void ge(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_GE_OS);
  }
  [[gnu::target("avx2")]] static void eq(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_EQ_OQ);
  }
  [[gnu::target("avx2")]] static void not_lt(V& r, const V& a, const V& b) {
    r = _mm256_cmp_pd(a, b, _CMP_NLT_US);
  }
  [[gnu::target("avx2")]] static unsigned mask(const V& a) {
    return static_cast<unsigned>(_mm256_movemask_pd(a));
  }
};

// The scalar test's operations in every lane of `Lanes`, on the lanes of `quad` from
// `first_lane` on. Always inline, as the scalar test: a caller that ignores the hits (shadow
// rays) lets the compiler drop them.
template <typename Lanes>
[[gnu::always_inline]] inline unsigned intersect_triangle_lanes(const TriangleQuad& quad,
                                                                int first_lane,
                                                                const TriangleLanesRay& lanes_ray,
                                                                double t_max,
                                                                TriangleLaneHits& hits) {
  using V = typename Lanes::V;
  const TriangleRay& ray = lanes_ray.ray;
  if (!ray.usable) return 0;
  // Written out rather than as loops over arrays of vectors, which GCC kept as loops through
  // the stack.
  V origin_x, origin_y, origin_z, shear_x, shear_y, shear_z, product;
  Lanes::set1(origin_x, lanes_ray.origin[0]);
  Lanes::set1(origin_y, lanes_ray.origin[1]);
  Lanes::set1(origin_z, lanes_ray.origin[2]);
  Lanes::set1(shear_x, ray.sx);
  Lanes::set1(shear_y, ray.sy);
  Lanes::set1(shear_z, ray.sz);
  // Translate, permute (p - o, then its components kx, ky, kz, as the scalar test) and shear.
  struct Corner {
    V x, y, z;
  };
  // Coordinate `offset` (bytes, coordinate_offset) of corner c, from lane first_lane on.
  const auto coordinate = [&](int c, int offset) {
    return reinterpret_cast<const double*>(reinterpret_cast<const char*>(quad.corner[c]) + offset) +
           first_lane;
  };
  const auto transform = [&](Corner& q, int c) {
    Lanes::load(q.x, coordinate(c, lanes_ray.coordinate_offset[0]));
    Lanes::load(q.y, coordinate(c, lanes_ray.coordinate_offset[1]));
    Lanes::load(q.z, coordinate(c, lanes_ray.coordinate_offset[2]));
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
  // Edge functions: e = a.x * b.y - a.y * b.x.
  const auto edge = [&](V& e, const Corner& a, const Corner& b) {
    Lanes::mul(e, a.x, b.y);
    Lanes::mul(product, a.y, b.x);
    Lanes::sub(e, e, product);
  };
  V e0, e1, e2;
  edge(e0, q1, q2);
  edge(e1, q2, q0);
  edge(e2, q0, q1);
  V zero, some_negative, some_positive, compared;
  Lanes::set1(zero, 0.0);
  Lanes::lt(some_negative, e0, zero);
  Lanes::lt(compared, e1, zero);
  Lanes::bit_or(some_negative, some_negative, compared);
  Lanes::lt(compared, e2, zero);
  Lanes::bit_or(some_negative, some_negative, compared);
  Lanes::gt(some_positive, e0, zero);
  Lanes::gt(compared, e1, zero);
  Lanes::bit_or(some_positive, some_positive, compared);
  Lanes::gt(compared, e2, zero);
  Lanes::bit_or(some_positive, some_positive, compared);
  V det;
  Lanes::add(det, e0, e1);
  Lanes::add(det, det, e2);
  V abs_bits;
  Lanes::set1(abs_bits, std::bit_cast<double>(0x7fffffffffffffffull));
  const auto abs = [&](V& r, const V& a) { Lanes::bit_and(r, a, abs_bits); };
  // Missed: mixed signs, a zero determinant or one that is not finite (NaN or infinite).
  V missed, infinity, abs_det;
  Lanes::bit_and(missed, some_negative, some_positive);
  Lanes::eq(compared, det, zero);
  Lanes::bit_or(missed, missed, compared);
  Lanes::set1(infinity, std::numeric_limits<double>::infinity());
  abs(abs_det, det);
  Lanes::not_lt(compared, abs_det, infinity);
  Lanes::bit_or(missed, missed, compared);
  if (Lanes::mask(missed) == Lanes::kAllLanes) return 0;

  Lanes::mul(q0.z, q0.z, shear_z);
  Lanes::mul(q1.z, q1.z, shear_z);
  Lanes::mul(q2.z, q2.z, shear_z);
  V t_scaled, t_max_det;
  Lanes::mul(t_scaled, e0, q0.z);
  Lanes::mul(product, e1, q1.z);
  Lanes::add(t_scaled, t_scaled, product);
  Lanes::mul(product, e2, q2.z);
  Lanes::add(t_scaled, t_scaled, product);
  Lanes::set1(t_max_det, t_max);
  Lanes::mul(t_max_det, t_max_det, det);
  V out, side, beyond;
  // det < 0 && (t_scaled >= 0 || t_scaled < t_max * det)
  Lanes::lt(side, det, zero);
  Lanes::ge(compared, t_scaled, zero);
  Lanes::lt(beyond, t_scaled, t_max_det);
  Lanes::bit_or(compared, compared, beyond);
  Lanes::bit_and(out, side, compared);
  Lanes::bit_or(missed, missed, out);
  // det > 0 && (t_scaled <= 0 || t_scaled > t_max * det)
  Lanes::gt(side, det, zero);
  Lanes::le(compared, t_scaled, zero);
  Lanes::gt(beyond, t_scaled, t_max_det);
  Lanes::bit_or(compared, compared, beyond);
  Lanes::bit_and(out, side, compared);
  Lanes::bit_or(missed, missed, out);
  if (Lanes::mask(missed) == Lanes::kAllLanes) return 0;

  V one, inv_det, t;
  Lanes::set1(one, 1.0);
  Lanes::div(inv_det, one, det);
  Lanes::mul(t, t_scaled, inv_det);
  // max_component(abs(a, b, c)) is std::max({a, b, c}): m = a, then m = m < x ? x : m, which
  // maxpd(x, m) computes, NaN included.
  const auto max_abs = [&](V& r, const V& a, const V& b, const V& c) {
    V abs_next;
    abs(r, a);
    abs(abs_next, b);
    Lanes::max(r, abs_next, r);
    abs(abs_next, c);
    Lanes::max(r, abs_next, r);
  };
  V max_xt, max_yt, max_zt, max_e;
  max_abs(max_xt, q0.x, q1.x, q2.x);
  max_abs(max_yt, q0.y, q1.y, q2.y);
  max_abs(max_zt, q0.z, q1.z, q2.z);
  max_abs(max_e, e0, e1, e2);
  // k * v, the constant first as in the scalar test.
  const auto times = [&](V& r, double k, const V& v) {
    Lanes::set1(r, k);
    Lanes::mul(r, r, v);
  };
  V delta_x, delta_y, delta_z, delta_e, delta_t, term;
  times(delta_z, gamma_bound(3), max_zt);
  Lanes::add(term, max_xt, max_zt);
  times(delta_x, gamma_bound(5), term);
  Lanes::add(term, max_yt, max_zt);
  times(delta_y, gamma_bound(5), term);
  // delta_e = 2 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt)
  times(term, gamma_bound(2), max_xt);
  Lanes::mul(term, term, max_yt);
  Lanes::mul(product, delta_y, max_xt);
  Lanes::add(term, term, product);
  Lanes::mul(product, delta_x, max_yt);
  Lanes::add(term, term, product);
  times(delta_e, 2, term);
  // delta_t = 3 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * |inv_det|
  times(term, gamma_bound(3), max_e);
  Lanes::mul(term, term, max_zt);
  Lanes::mul(product, delta_e, max_zt);
  Lanes::add(term, term, product);
  Lanes::mul(product, delta_z, max_e);
  Lanes::add(term, term, product);
  times(delta_t, 3, term);
  abs(term, inv_det);
  Lanes::mul(delta_t, delta_t, term);
  V hit, t_max_lanes;
  Lanes::gt(hit, t, delta_t);
  Lanes::set1(t_max_lanes, t_max);
  Lanes::lt(compared, t, t_max_lanes);
  Lanes::bit_and(hit, hit, compared);
  Lanes::and_not(hit, missed, hit);
  const unsigned lanes = Lanes::mask(hit);
  if (lanes == 0) return 0;
  Lanes::store(hits.t + first_lane, t);
  Lanes::mul(product, e0, inv_det);
  Lanes::store(hits.b0 + first_lane, product);
  Lanes::mul(product, e1, inv_det);
  Lanes::store(hits.b1 + first_lane, product);
  Lanes::mul(product, e2, inv_det);
  Lanes::store(hits.b2 + first_lane, product);
  return lanes << first_lane;
}
#endif

// The two triangles of `quad`'s half `half` (lanes 2 half and 2 half + 1), at once where SSE2 is
// available; lanes as bits 2 half and 2 half + 1.
[[gnu::always_inline]] inline unsigned intersect_triangle_pair(const TriangleQuad& quad, int half,
                                                               const TriangleLanesRay& lanes_ray,
                                                               double t_max,
                                                               TriangleLaneHits& hits) {
#if defined(__SSE2__)
  return intersect_triangle_lanes<Sse2DoubleLanes>(quad, 2 * half, lanes_ray, t_max, hits);
#else
  return intersect_triangle_lanes_scalar(quad, 2 * half, 2, lanes_ray.ray, t_max, hits);
#endif
}

#if defined(__SSE2__)
// The four triangles of `quad` at once, lanes as bits 0 to 3; only where the CPU has AVX2 (the
// mesh traversal's AVX2 kernel, wide_box_kernel.h).
[[gnu::target("avx2"), gnu::flatten]] inline unsigned intersect_triangle_quad(
    const TriangleQuad& quad, const TriangleLanesRay& lanes_ray, double t_max,
    TriangleLaneHits& hits) {
  return intersect_triangle_lanes<Avx2DoubleLanes>(quad, 0, lanes_ray, t_max, hits);
}
#endif

}  // namespace tessera
