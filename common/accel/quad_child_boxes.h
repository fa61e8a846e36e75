// Four children of a scene BVH node tested against a ray at once, in double with AVX2: the boxes
// side by side per axis and bound, as in child_boxes.h, four to a 256-bit vector. Each box's
// lane does the operations of intersect_child_boxes' SSE2 lanes (and so of intersect_bounds) in
// the same order, without fusing (target "avx2" does not enable FMA), so a box's answer and
// entry distance are the pair test's bit for bit; the boxes are double, so a ray leaving a
// surface does not re-enter its object's box, which sank the float scene nodes
// (docs/PERFORMANCE.md "Four-wide float nodes: tried and reverted").
#pragma once

#include <cmath>

#include "common/accel/child_boxes.h"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace tessera {

inline constexpr int kQuadChildren = 4;

struct alignas(32) QuadChildBoxes {
  double bound[3][2][kQuadChildren];  // [axis][0 lo, 1 hi][child]; empty slots: lo +inf, hi -inf
};

inline QuadChildBoxes empty_quad_child_boxes() {
  QuadChildBoxes boxes;
  for (auto& axis : boxes.bound)
    for (int c = 0; c < kQuadChildren; ++c) axis[0][c] = INFINITY, axis[1][c] = -INFINITY;
  return boxes;
}

inline void set_quad_child_box(QuadChildBoxes& boxes, int child, const Bounds3& box) {
  for (int a = 0; a < 3; ++a) boxes.bound[a][0][child] = box.lo[a], boxes.bound[a][1][child] = box.hi[a];
}

#if defined(__x86_64__)
// Bit c of the result is set when the ray [0, t_max] meets child c's box; entry[c] receives
// where it enters. An empty slot's near distance is +inf and its far -inf (or NaN), a miss.
[[gnu::always_inline, gnu::target("avx2")]] inline unsigned intersect_quad_child_boxes_avx2(
    const QuadChildBoxes& boxes, const BoxRay& ray, double t_max, double entry[kQuadChildren]) {
  constexpr double kFarScale = 1 + 2 * gamma_bound(3);
  __m256d t0 = _mm256_setzero_pd(), t1 = _mm256_set1_pd(t_max);
  const __m256d far_scale = _mm256_set1_pd(kFarScale);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const __m256d o = _mm256_set1_pd(ray.origin[a]), inv = _mm256_set1_pd(ray.inv_dir[a]);
    const int near = ray.near_side[a];
    const __m256d t_near = _mm256_mul_pd(_mm256_sub_pd(_mm256_load_pd(boxes.bound[a][near]), o), inv);
    const __m256d t_far = _mm256_mul_pd(
        _mm256_mul_pd(_mm256_sub_pd(_mm256_load_pd(boxes.bound[a][1 - near]), o), inv), far_scale);
    t0 = _mm256_max_pd(t_near, t0);  // t_near > t0 ? t_near : t0
    t1 = _mm256_min_pd(t_far, t1);   // t_far < t1 ? t_far : t1
  }
  _mm256_storeu_pd(entry, t0);
  return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(t0, t1, _CMP_LE_OS)));
}
#endif

}  // namespace tessera
