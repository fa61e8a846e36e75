// Two triangles of a mesh leaf tested against one ray at once: the watertight test of
// triangle.h with SSE2 doubles, one triangle per lane. SSE2 is part of every x86-64 CPU, so a
// build has one path and nothing is chosen at run time; other CPUs run the scalar test once per
// lane. Each lane computes exactly the IEEE operations of the scalar test in the same order
// (nothing is fused: the build forbids contraction; maxpd(b, a) is std::max(a, b), NaN included),
// so both paths give bit-identical hits (tests/geometry/triangle_pair_test.cpp).
#pragma once

#include <cstdint>
#include <limits>

#include "common/geometry/triangle.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

// Two triangles' corners, structure of arrays: corner[c][axis][lane], so that one load brings a
// coordinate of both. A lane whose corners are NaN is never hit (its determinant is not finite):
// it stands for degenerate triangles and pads leaves of odd size.
struct alignas(16) TrianglePair {
  double corner[3][3][2];
};

inline Vec3 pair_corner(const TrianglePair& pair, int c, int lane) {
  return {pair.corner[c][0][lane], pair.corner[c][1][lane], pair.corner[c][2][lane]};
}

inline void set_pair_corner(TrianglePair& pair, int c, int lane, const Vec3& p) {
  pair.corner[c][0][lane] = p.x;
  pair.corner[c][1][lane] = p.y;
  pair.corner[c][2][lane] = p.z;
}

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

// The same, both lanes at once where SSE2 is available. Always inline, as the scalar test: a
// caller that ignores the hits (shadow rays) lets the compiler drop them.
[[gnu::always_inline]] inline unsigned intersect_triangle_pair(const TrianglePair& pair,
                                                               const TriangleRay& ray, double t_max,
                                                               TrianglePairHits& hits) {
#if defined(__SSE2__)
  if (!ray.usable) return 0;
  const double origin[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const int kx = ray.kx, ky = ray.ky, kz = ray.kz;
  const __m128d ox = _mm_set1_pd(origin[kx]), oy = _mm_set1_pd(origin[ky]),
                oz = _mm_set1_pd(origin[kz]);
  const __m128d sx = _mm_set1_pd(ray.sx), sy = _mm_set1_pd(ray.sy), sz = _mm_set1_pd(ray.sz);
  // Translate, permute (p - o, then its components kx, ky, kz, as the scalar test) and shear.
  __m128d qx[3], qy[3], qz[3];
  for (int c = 0; c < 3; ++c) {
    qx[c] = _mm_sub_pd(_mm_load_pd(pair.corner[c][kx]), ox);
    qy[c] = _mm_sub_pd(_mm_load_pd(pair.corner[c][ky]), oy);
    qz[c] = _mm_sub_pd(_mm_load_pd(pair.corner[c][kz]), oz);
    qx[c] = _mm_add_pd(qx[c], _mm_mul_pd(sx, qz[c]));
    qy[c] = _mm_add_pd(qy[c], _mm_mul_pd(sy, qz[c]));
  }
  const __m128d e0 = _mm_sub_pd(_mm_mul_pd(qx[1], qy[2]), _mm_mul_pd(qy[1], qx[2]));
  const __m128d e1 = _mm_sub_pd(_mm_mul_pd(qx[2], qy[0]), _mm_mul_pd(qy[2], qx[0]));
  const __m128d e2 = _mm_sub_pd(_mm_mul_pd(qx[0], qy[1]), _mm_mul_pd(qy[0], qx[1]));
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

  for (int c = 0; c < 3; ++c) qz[c] = _mm_mul_pd(qz[c], sz);
  const __m128d t_scaled =
      _mm_add_pd(_mm_add_pd(_mm_mul_pd(e0, qz[0]), _mm_mul_pd(e1, qz[1])), _mm_mul_pd(e2, qz[2]));
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
  const auto max_abs = [&](const __m128d v[3]) {
    return _mm_max_pd(abs(v[2]), _mm_max_pd(abs(v[1]), abs(v[0])));
  };
  const __m128d e[3] = {e0, e1, e2};
  const __m128d max_zt = max_abs(qz), max_xt = max_abs(qx), max_yt = max_abs(qy);
  const __m128d max_e = max_abs(e);
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
  return intersect_triangle_pair_scalar(pair, ray, t_max, hits);
#endif
}

}  // namespace tessera
