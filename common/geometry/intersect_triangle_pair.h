// Two triangles of a mesh leaf tested against one ray at once: the watertight test of
// triangle.h with SSE2 doubles, one triangle per lane (the layout: triangle_pair.h). SSE2 is part
// of every x86-64 CPU, so a build has one path and nothing is chosen at run time; other CPUs run
// the scalar test once per lane. Each lane computes exactly the IEEE operations of the scalar test
// in the same order (nothing is fused: the build forbids contraction; maxpd(b, a) is
// std::max(a, b), NaN included), so both paths give bit-identical hits
// (tests/geometry/triangle_pair_test.cpp).
#pragma once

#include <limits>

#include "common/geometry/triangle.h"
#include "common/geometry/triangle_pair.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

// The hits of both lanes (meaningful only for the lanes reported hit).
struct TrianglePairHits {
  alignas(16) double t[2];
  alignas(16) double b0[2];
  alignas(16) double b1[2];
  alignas(16) double b2[2];
  TriangleHit lane(int i) const { return {t[i], b0[i], b1[i], b2[i]}; }
};

// The scalar test of triangle.h once per lane. Returns the lanes hit with t in (0, t_max) as bits
// (1: lane 0, 2: lane 1).
inline unsigned intersect_triangle_pair_scalar(const TrianglePair& pair, const TriangleRay& ray,
                                               double t_max, TrianglePairHits& hits) {
  unsigned lanes = 0;
  for (int lane = 0; lane < 2; ++lane) {
    TriangleHit h;
    if (!intersect_triangle(pair_corner(pair, 0, lane), pair_corner(pair, 1, lane),
                            pair_corner(pair, 2, lane), ray, t_max, h))
      continue;
    hits.t[lane] = h.t;
    hits.b0[lane] = h.b0;
    hits.b1[lane] = h.b1;
    hits.b2[lane] = h.b2;
    lanes |= 1u << lane;
  }
  return lanes;
}

// A ray prepared for pair tests: the triangle test's ray, and where SSE2 is available its
// permuted origin and shear broadcast to both lanes, once per ray rather than once per pair.
struct TrianglePairRay {
  TriangleRay ray;
#if defined(__SSE2__)
  __m128d ox, oy, oz;  // the origin's components kx, ky, kz
  __m128d sx, sy, sz;
#endif
};

inline TrianglePairRay prepare_triangle_pair_ray(const Ray& ray) {
  TrianglePairRay r;
  r.ray = prepare_triangle_ray(ray);
#if defined(__SSE2__)
  const Vec3 origin = permute_axes(ray.origin, r.ray.kx, r.ray.ky, r.ray.kz);
  r.ox = _mm_set1_pd(origin.x);
  r.oy = _mm_set1_pd(origin.y);
  r.oz = _mm_set1_pd(origin.z);
  r.sx = _mm_set1_pd(r.ray.sx);
  r.sy = _mm_set1_pd(r.ray.sy);
  r.sz = _mm_set1_pd(r.ray.sz);
#endif
  return r;
}

// The same, both lanes at once where SSE2 is available. Always inline, as the scalar test: a
// caller that ignores the hits (shadow rays) lets the compiler drop them.
[[gnu::always_inline]] inline unsigned intersect_triangle_pair(const TrianglePair& pair,
                                                               const TrianglePairRay& pair_ray,
                                                               double t_max,
                                                               TrianglePairHits& hits) {
#if defined(__SSE2__)
  const TriangleRay& ray = pair_ray.ray;
  if (!ray.usable) return 0;
  // Translate, permute (p - o, then its components kx, ky, kz, as the scalar test) and shear.
  struct Corner {
    __m128d x, y, z;
  };
  const auto transform = [&](const double(&p)[3][2]) {
    Corner q{_mm_sub_pd(_mm_load_pd(p[ray.kx]), pair_ray.ox),
             _mm_sub_pd(_mm_load_pd(p[ray.ky]), pair_ray.oy),
             _mm_sub_pd(_mm_load_pd(p[ray.kz]), pair_ray.oz)};
    q.x = _mm_add_pd(q.x, _mm_mul_pd(pair_ray.sx, q.z));
    q.y = _mm_add_pd(q.y, _mm_mul_pd(pair_ray.sy, q.z));
    return q;
  };
  Corner q0 = transform(pair.corner[0]), q1 = transform(pair.corner[1]),
         q2 = transform(pair.corner[2]);
  const __m128d e0 = _mm_sub_pd(_mm_mul_pd(q1.x, q2.y), _mm_mul_pd(q1.y, q2.x));
  const __m128d e1 = _mm_sub_pd(_mm_mul_pd(q2.x, q0.y), _mm_mul_pd(q2.y, q0.x));
  const __m128d e2 = _mm_sub_pd(_mm_mul_pd(q0.x, q1.y), _mm_mul_pd(q0.y, q1.x));
  const __m128d zero = _mm_setzero_pd();
  const __m128d some_negative =
      _mm_or_pd(_mm_or_pd(_mm_cmplt_pd(e0, zero), _mm_cmplt_pd(e1, zero)), _mm_cmplt_pd(e2, zero));
  const __m128d some_positive =
      _mm_or_pd(_mm_or_pd(_mm_cmpgt_pd(e0, zero), _mm_cmpgt_pd(e1, zero)), _mm_cmpgt_pd(e2, zero));
  const __m128d det = _mm_add_pd(_mm_add_pd(e0, e1), e2);
  const __m128d abs_bits = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffff));
  const auto abs = [&](__m128d v) { return _mm_and_pd(v, abs_bits); };
  // Missed: mixed signs, a zero determinant or one that is not finite (NaN or infinite).
  __m128d missed = _mm_or_pd(
      _mm_and_pd(some_negative, some_positive),
      _mm_or_pd(_mm_cmpeq_pd(det, zero),
                _mm_cmpnlt_pd(abs(det), _mm_set1_pd(std::numeric_limits<double>::infinity()))));
  if (_mm_movemask_pd(missed) == 3) return 0;

  q0.z = _mm_mul_pd(q0.z, pair_ray.sz);
  q1.z = _mm_mul_pd(q1.z, pair_ray.sz);
  q2.z = _mm_mul_pd(q2.z, pair_ray.sz);
  const __m128d t_scaled =
      _mm_add_pd(_mm_add_pd(_mm_mul_pd(e0, q0.z), _mm_mul_pd(e1, q1.z)), _mm_mul_pd(e2, q2.z));
  const __m128d t_max_det = _mm_mul_pd(_mm_set1_pd(t_max), det);
  const __m128d out_negative =
      _mm_and_pd(_mm_cmplt_pd(det, zero),
                 _mm_or_pd(_mm_cmpge_pd(t_scaled, zero), _mm_cmplt_pd(t_scaled, t_max_det)));
  const __m128d out_positive =
      _mm_and_pd(_mm_cmpgt_pd(det, zero),
                 _mm_or_pd(_mm_cmple_pd(t_scaled, zero), _mm_cmpgt_pd(t_scaled, t_max_det)));
  missed = _mm_or_pd(missed, _mm_or_pd(out_negative, out_positive));
  if (_mm_movemask_pd(missed) == 3) return 0;

  const __m128d inv_det = _mm_div_pd(_mm_set1_pd(1.0), det);
  const __m128d t = _mm_mul_pd(t_scaled, inv_det);
  // max_component(abs(a, b, c)) is std::max({a, b, c}): m = a, then m = m < x ? x : m, which
  // maxpd(x, m) computes, NaN included.
  const auto max_abs = [&](__m128d a, __m128d b, __m128d c) {
    return _mm_max_pd(abs(c), _mm_max_pd(abs(b), abs(a)));
  };
  const __m128d max_zt = max_abs(q0.z, q1.z, q2.z), max_xt = max_abs(q0.x, q1.x, q2.x),
                max_yt = max_abs(q0.y, q1.y, q2.y);
  const __m128d max_e = max_abs(e0, e1, e2);
  const auto times = [](double k, __m128d v) { return _mm_mul_pd(_mm_set1_pd(k), v); };
  const __m128d delta_z = times(gamma_bound(3), max_zt);
  const __m128d delta_x = times(gamma_bound(5), _mm_add_pd(max_xt, max_zt));
  const __m128d delta_y = times(gamma_bound(5), _mm_add_pd(max_yt, max_zt));
  const __m128d delta_e =
      times(2, _mm_add_pd(_mm_add_pd(_mm_mul_pd(times(gamma_bound(2), max_xt), max_yt),
                                     _mm_mul_pd(delta_y, max_xt)),
                          _mm_mul_pd(delta_x, max_yt)));
  const __m128d delta_t =
      _mm_mul_pd(times(3, _mm_add_pd(_mm_add_pd(_mm_mul_pd(times(gamma_bound(3), max_e), max_zt),
                                                _mm_mul_pd(delta_e, max_zt)),
                                     _mm_mul_pd(delta_z, max_e))),
                 abs(inv_det));
  const __m128d hit = _mm_andnot_pd(
      missed, _mm_and_pd(_mm_cmpgt_pd(t, delta_t), _mm_cmplt_pd(t, _mm_set1_pd(t_max))));
  const auto lanes = static_cast<unsigned>(_mm_movemask_pd(hit));
  if (lanes == 0) return 0;
  _mm_store_pd(hits.t, t);
  _mm_store_pd(hits.b0, _mm_mul_pd(e0, inv_det));
  _mm_store_pd(hits.b1, _mm_mul_pd(e1, inv_det));
  _mm_store_pd(hits.b2, _mm_mul_pd(e2, inv_det));
  return lanes;
#else
  return intersect_triangle_pair_scalar(pair, pair_ray.ray, t_max, hits);
#endif
}

}  // namespace tessera
