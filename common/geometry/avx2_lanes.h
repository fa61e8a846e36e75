// Four doubles a ymm register, and the operations the AVX2 packet paths (torus_packet.cpp,
// cube_packet.cpp) write their scalar code's steps with, lane by lane the same IEEE operations
// (no FMA: the build has -ffp-contract=off). Each needs AVX2 at run time
// (wide_box_kernel_supported); the functions carry the target attribute, so callers compile
// without -mavx2.
#pragma once

#if defined(__SSE2__)
#include <immintrin.h>

namespace tessera::avx2_lanes {

using V = __m256d;

[[gnu::target("avx2"), gnu::always_inline]] inline V splat(double x) { return _mm256_set1_pd(x); }
[[gnu::target("avx2"), gnu::always_inline]] inline V add(V a, V b) { return _mm256_add_pd(a, b); }
[[gnu::target("avx2"), gnu::always_inline]] inline V sub(V a, V b) { return _mm256_sub_pd(a, b); }
[[gnu::target("avx2"), gnu::always_inline]] inline V mul(V a, V b) { return _mm256_mul_pd(a, b); }
[[gnu::target("avx2"), gnu::always_inline]] inline V divide(V a, V b) {
  return _mm256_div_pd(a, b);
}
[[gnu::target("avx2"), gnu::always_inline]] inline V negate(V a) {
  return _mm256_xor_pd(a, splat(-0.0));
}
[[gnu::target("avx2"), gnu::always_inline]] inline V magnitude(V a) {
  return _mm256_andnot_pd(splat(-0.0), a);
}
// std::max(a, b) and std::min(a, b), which pick an operand as the standard library does, NaN and
// signed zeros included: std::max(a, b) is (a < b ? b : a), which is _mm256_max_pd(b, a) (its
// second operand when the compare is false or unordered), and std::min(a, b), (b < a ? b : a), is
// _mm256_min_pd(b, a).
[[gnu::target("avx2"), gnu::always_inline]] inline V std_max(V a, V b) {
  return _mm256_max_pd(b, a);
}
[[gnu::target("avx2"), gnu::always_inline]] inline V std_min(V a, V b) {
  return _mm256_min_pd(b, a);
}
// c ? a : b per lane, c a compare's all-ones or all-zeros lanes.
[[gnu::target("avx2"), gnu::always_inline]] inline V select(V c, V a, V b) {
  return _mm256_blendv_pd(b, a, c);
}
// std::clamp(v, lo, hi): v < lo ? lo : (hi < v ? hi : v).
[[gnu::target("avx2"), gnu::always_inline]] inline V std_clamp(V v, V lo, V hi) {
  return select(_mm256_cmp_pd(v, lo, _CMP_LT_OQ), lo,
                select(_mm256_cmp_pd(hi, v, _CMP_LT_OQ), hi, v));
}

// The components of a vector of lanes, a lane each.
struct Lanes {
  alignas(32) double v[4];
};
[[gnu::target("avx2"), gnu::always_inline]] inline Lanes lanes_of(V a) {
  Lanes out;
  _mm256_store_pd(out.v, a);
  return out;
}

}  // namespace tessera::avx2_lanes

#endif
