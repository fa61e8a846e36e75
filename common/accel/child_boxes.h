// Both children of a BVH node tested against a ray at once: the two boxes are stored side by
// side per axis and bound (structure of arrays), so that one SSE2 instruction (part of every
// x86-64 CPU, so there is no other path to choose at run time) does the work of two scalar
// ones. The operations are those of intersect_bounds (common/math/ray.h), in the same order:
// maxpd and minpd pick their second operand on NaN, as intersect_bounds' comparisons do, and
// nothing is fused, so both give bit-identical results (tests/accel/child_boxes_test.cpp).
#pragma once

#include <cstdint>

#include "common/math/ray.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

struct alignas(16) ChildBoxes {
  double bound[3][2][2];  // [axis][0 lo, 1 hi][child]
};

// The per-ray constants of the test.
struct BoxRay {
  // The ray's own origin, not a copy: a ray spawned off a surface has just had its origin
  // written a component at a time, and copying it reads two components at once, which waits
  // for those stores to reach the cache (store forwarding fails; 9 % of a shadow feeler's
  // traversal). The lanes below read one component each.
  const Vec3& origin;
  Vec3 inv_dir;
  int near_side[3];  // 0 (lo) where the direction is forward (inv_dir >= 0), else 1 (hi)
#if defined(__SSE2__)
  // origin and inv_dir per axis, in both lanes: made once per ray rather than at every node,
  // where they cost a round trip through the stack (some 15 instructions a node).
  __m128d origin_lanes[3];
  __m128d inv_dir_lanes[3];
#endif

  explicit BoxRay(const Ray& ray) : origin(ray.origin) {
#if defined(__SSE2__)
    // x and y inverted by one divpd, whose lanes round as divsd does: the same quotients for
    // one division's latency less (the divisions start each ray's traversal, which waits on
    // them). GCC loads x and y together; unlike the origin's, that load did not measure slower
    // than two (forced by an empty asm: 1.5 % more CPU time for the demo).
    const __m128d inv_xy = _mm_div_pd(_mm_set1_pd(1), _mm_set_pd(ray.direction.y, ray.direction.x));
    inv_dir_lanes[0] = _mm_unpacklo_pd(inv_xy, inv_xy);
    inv_dir_lanes[1] = _mm_unpackhi_pd(inv_xy, inv_xy);
    inv_dir = {_mm_cvtsd_f64(inv_xy), _mm_cvtsd_f64(inv_dir_lanes[1]), 1 / ray.direction.z};
    inv_dir_lanes[2] = _mm_set1_pd(inv_dir.z);
    origin_lanes[0] = _mm_set1_pd(origin.x);
    origin_lanes[1] = _mm_set1_pd(origin.y);
    origin_lanes[2] = _mm_set1_pd(origin.z);
#else
    inv_dir = {1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
#endif
    for (int a = 0; a < 3; ++a) near_side[a] = inv_dir[a] >= 0 ? 0 : 1;
  }
};

inline ChildBoxes make_child_boxes(const Bounds3& first, const Bounds3& second) {
  ChildBoxes boxes;
  for (int a = 0; a < 3; ++a) {
    boxes.bound[a][0][0] = first.lo[a];
    boxes.bound[a][1][0] = first.hi[a];
    boxes.bound[a][0][1] = second.lo[a];
    boxes.bound[a][1][1] = second.hi[a];
  }
  return boxes;
}

// Bit c of the result is set when the ray [0, t_max] meets child c's box; entry[c] receives
// where it enters (as t_entry of intersect_bounds).
[[gnu::always_inline]] inline unsigned intersect_child_boxes(const ChildBoxes& boxes,
                                                             const BoxRay& ray, double t_max,
                                                             double entry[2]) {
#if defined(__SSE2__)
  constexpr double kFarScale = 1 + 2 * gamma_bound(3);
  __m128d t0 = _mm_setzero_pd(), t1 = _mm_set1_pd(t_max);
  const __m128d far_scale = _mm_set1_pd(kFarScale);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const __m128d o = ray.origin_lanes[a], inv = ray.inv_dir_lanes[a];
    const int near = ray.near_side[a];
    const __m128d t_near = _mm_mul_pd(_mm_sub_pd(_mm_load_pd(boxes.bound[a][near]), o), inv);
    const __m128d t_far = _mm_mul_pd(
        _mm_mul_pd(_mm_sub_pd(_mm_load_pd(boxes.bound[a][1 - near]), o), inv), far_scale);
    t0 = _mm_max_pd(t_near, t0);  // t_near > t0 ? t_near : t0
    t1 = _mm_min_pd(t_far, t1);   // t_far < t1 ? t_far : t1
  }
  _mm_storeu_pd(entry, t0);
  return static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(t0, t1)));
#else
  unsigned hits = 0;
  for (int c = 0; c < 2; ++c) {
    Bounds3 box;
    for (int a = 0; a < 3; ++a) box.lo[a] = boxes.bound[a][0][c], box.hi[a] = boxes.bound[a][1][c];
    hits |= (intersect_bounds(box, ray.origin, ray.inv_dir, t_max, entry[c]) ? 1u : 0u) << c;
  }
  return hits;
#endif
}

}  // namespace tessera
