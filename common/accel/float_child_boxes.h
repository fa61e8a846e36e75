// The eight children of a wide BVH node (the mesh BVH's, wide_bvh_traverse.h) tested against a
// ray at once, in float: the boxes are stored side by side per axis and bound (structure of
// arrays), so that one AVX instruction does the work of eight scalar ones, or two SSE ones
// (part of every x86-64 CPU) the work of eight on CPUs without AVX2. The traversal picks the
// kernel once at run time (wide_box_kernel.h). Every kernel computes, per child, the same IEEE
// operations in the same order: maxps and minps (AVX's too) pick their second operand on NaN,
// as the scalar comparisons do, and nothing is fused (the AVX2 kernel is compiled without FMA,
// and -ffp-contract=off holds), so all give bit-identical results
// (tests/accel/float_child_boxes_test.cpp), and images do not depend on the CPU.
//
// Float is only used to prune: the test is CONSERVATIVE, it accepts every box that the double
// slab test intersect_bounds (common/math/ray.h) accepts, so that traversal reaches every leaf
// it reached in double and the double triangle test decides the hits. Why (Ize, "Robust BVH
// ray traversal", 2013, with u = 2^-24 float's unit roundoff):
//  - Boxes are rounded outward when converted from double (round_down_to_float for lo,
//    round_up_to_float for hi), so the float box contains the double one.
//  - The origin is rounded down and up per axis; each slab distance subtracts the one that
//    makes (bound - origin) smaller for the near plane and larger for the far plane, taking
//    the direction's sign into account (FloatBoxRay::origin_near, origin_far). The exact difference
//    of these floats therefore lies on the accepting side of the exact double difference, and
//    float subtraction keeps its sign (x - y == 0 only when x == y).
//  - Each slab distance is then a product of that difference and the reciprocal direction
//    (1 / d in double, rounded to float), with three roundings (the subtraction, the
//    reciprocal's conversion, the product; the reciprocal's double rounding and the double
//    test's own roundings add terms of order 2^-53). So a near distance is at most its exact
//    value times (1 + gamma(3)), and a far one at least its exact value times (1 - gamma(3));
//    the double test's distances are within gamma_double(4) of the same exact values. Far
//    distances are multiplied by kFloatFarScale = 1 + 2 gamma(5) (an extra rounding for that
//    product, and room for the double terms), and t_max is rounded up and multiplied by the
//    same (float_far_limit), so that whenever a double near distance is at most a double far
//    distance or t_max, the float near distance is at most the float far one or t_max.
//  - The argument is relative, so it fails where products fall below FLT_MIN (gradual
//    underflow, absolute errors up to 2^-149): the comparison gives the far end a margin of
//    kFloatTinyMargin = FLT_MIN, which covers those and changes nothing at normal magnitudes.
//    Overflow rounds a far distance to +inf, which accepts; a near distance that overflows
//    only when the true one exceeds FLT_MAX, where the far one and t_max overflow as well.
//  - A zero direction component makes the reciprocal +-inf and a distance +-inf or, with the
//    origin on a plane, NaN, which maxps/minps leave out (the NaN operand comes first): the
//    same as the double test. Since the float differences keep their sign and are on the
//    accepting side, a slab the double test keeps is kept. A reciprocal beyond FLT_MAX (a
//    direction component below 3e-39) is +-inf in float and takes the same path, on the
//    accepting side. Directions with components above 1e37 are outside this argument (their
//    reciprocals lose precision as subnormals); nothing in a scene comes near.
//  - Empty child slots (fewer than eight children) hold the empty box (lo = +inf, hi = -inf)
//    and are masked out by lo.x <= hi.x, so a ray of NaNs, which accepts every slab, still
//    never enters one.
#pragma once

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>

#include "common/math/ray.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

inline constexpr float kFloatUnitRoundoff = FLT_EPSILON * 0.5f;
inline constexpr double float_gamma_bound(int n) {
  return (n * double{kFloatUnitRoundoff}) / (1 - n * double{kFloatUnitRoundoff});
}
inline constexpr float kFloatFarScale = static_cast<float>(1 + 2 * float_gamma_bound(5));
inline constexpr float kFloatTinyMargin = FLT_MIN;

// The next float towards +inf (-inf) from f, for f not NaN and not already +inf (-inf): a step
// of one in the bit pattern, away from zero or towards it by the sign (std::nextafter is a
// library call, and these run for every ray). Without branches on the sign: whether a ray's
// origin rounds up or down is a coin toss, and branches on it were a tenth of the mispredicted
// branches of a mesh render (callgrind's model).
inline std::uint32_t float_step_up_bits(float f) {
  auto bits = std::bit_cast<std::uint32_t>(f);
  bits = (bits << 1) == 0 ? 0 : bits;  // -0 steps as +0, to FLT_TRUE_MIN
  return (bits >> 31) == 0 ? bits + 1 : bits - 1;
}
inline float float_step_up(float f) { return std::bit_cast<float>(float_step_up_bits(f)); }
inline float float_step_down(float f) {
  return std::bit_cast<float>(float_step_up_bits(-f) ^ 0x80000000u);
}

// The float with bits `yes` where `pick`, else the one with bits `no`, by masks: compilers turn
// a ternary into a branch, which mispredicts here half of the time.
inline float select_float_bits(bool pick, std::uint32_t yes, std::uint32_t no) {
  const std::uint32_t mask = 0u - static_cast<std::uint32_t>(pick);
  return std::bit_cast<float>(no ^ ((no ^ yes) & mask));
}

// The nearest float at or below (above) x; +-inf beyond float's range.
inline float round_down_to_float(double x) {
  const float f = static_cast<float>(x);
  return select_float_bits(static_cast<double>(f) > x,
                           std::bit_cast<std::uint32_t>(float_step_down(f)),
                           std::bit_cast<std::uint32_t>(f));
}
inline float round_up_to_float(double x) {
  const float f = static_cast<float>(x);
  return select_float_bits(static_cast<double>(f) < x, float_step_up_bits(f),
                           std::bit_cast<std::uint32_t>(f));
}

// The float limit that stands for the double t_max in the test (see the argument above).
inline float float_far_limit(double t_max) {
  return round_up_to_float(t_max * static_cast<double>(kFloatFarScale));
}

// Children a wide node holds (Embree's eight-wide nodes: one AVX register of floats).
inline constexpr int kWideChildren = 8;

// The limits a box test compares a child's entry distance with: `far` is float_far_limit(t_max)
// and `entry_max` far + kFloatTinyMargin in every lane, the SIMD kernels' form. Made when t_max
// changes, not at every node step (an addition and a broadcast a step, docs/PERFORMANCE.md "The
// wide traversal's own instructions").
struct FloatBoxLimit {
  alignas(32) float entry_max[kWideChildren];
  float far;
  explicit FloatBoxLimit(float far_limit) : far(far_limit) {
    for (float& e : entry_max) e = far_limit + kFloatTinyMargin;
  }
};

struct alignas(32) FloatChildBoxes {
  float bound[3][2][kWideChildren];  // [axis][0 lo, 1 hi][child]
};

// Empty slots; set_float_child_box fills slot `c` with `box`, rounded outward.
inline FloatChildBoxes empty_float_child_boxes() {
  FloatChildBoxes boxes;
  for (auto& axis : boxes.bound)
    for (int c = 0; c < kWideChildren; ++c) axis[0][c] = INFINITY, axis[1][c] = -INFINITY;
  return boxes;
}
inline void set_float_child_box(FloatChildBoxes& boxes, int c, const Bounds3& box) {
  for (int a = 0; a < 3; ++a) {
    boxes.bound[a][0][c] = round_down_to_float(box.lo[a]);
    boxes.bound[a][1][c] = round_up_to_float(box.hi[a]);
  }
}

// The per-ray constants of the test, each repeated once per child so that a step loads them
// instead of broadcasting them again.
struct FloatBoxRay {
  // Subtracted from the near plane: the origin rounded towards it; from the far plane: rounded
  // away from it.
  alignas(32) float origin_near[3][kWideChildren];
  alignas(32) float origin_far[3][kWideChildren];
  alignas(32) float inv_dir[3][kWideChildren];
  int near_side[3];  // 0 (lo) where the direction is forward (1 / d >= 0), else 1 (hi)

  FloatBoxRay() = default;  // filled by set_float_box_ray_sse2 or _avx2
  // Axis by axis (set_float_box_ray_per_axis): the reference, and the scalar kernel's.
  explicit FloatBoxRay(const Ray& ray);
};

// Fills `r` from `ray` one axis at a time: the reference (and the path of CPUs without SSE2).
inline void set_float_box_ray_per_axis(FloatBoxRay& r, const Ray& ray) {
  for (int a = 0; a < 3; ++a) {
    const double inv = 1 / ray.direction[a];
    const bool forward = inv >= 0;
    const auto down = std::bit_cast<std::uint32_t>(round_down_to_float(ray.origin[a]));
    const auto up = std::bit_cast<std::uint32_t>(round_up_to_float(ray.origin[a]));
    r.near_side[a] = forward ? 0 : 1;
    // Forward, the near plane is lo and (lo - origin) is smaller with the origin rounded up;
    // backward, it is hi and (hi - origin) * inv is smaller with (hi - origin) larger.
    const float near_origin = select_float_bits(forward, up, down);
    const float far_origin = select_float_bits(forward, down, up);
    for (int c = 0; c < kWideChildren; ++c) {
      r.inv_dir[a][c] = static_cast<float>(inv);
      r.origin_near[a][c] = near_origin;
      r.origin_far[a][c] = far_origin;
    }
  }
}

#if defined(__SSE2__)
// float_step_up_bits in each of four lanes: (bits << 1) == 0 clears -0 to +0, then the sign
// (bits >> 31, arithmetic: 0 or -1) or'ed with 1 is the step, +1 or -1.
[[gnu::always_inline]] inline __m128i float_step_up_bits_sse2(__m128i bits) {
  const __m128i zero = _mm_cmpeq_epi32(_mm_slli_epi32(bits, 1), _mm_setzero_si128());
  bits = _mm_andnot_si128(zero, bits);
  return _mm_add_epi32(bits, _mm_or_si128(_mm_srai_epi32(bits, 31), _mm_set1_epi32(1)));
}

// `yes` where the lanes of `mask` are set, else `no`.
[[gnu::always_inline]] inline __m128i select_bits_sse2(__m128i mask, __m128i yes, __m128i no) {
  return _mm_or_si128(_mm_and_si128(mask, yes), _mm_andnot_si128(mask, no));
}

// The 32-bit lanes 0 and 1 of `r` from the 64-bit lanes of `a`, 2 and 3 from `b`'s: the double
// compares' all-ones or all-zeros masks, narrowed.
[[gnu::always_inline]] inline __m128i narrow_masks_sse2(__m128d a, __m128d b) {
  return _mm_castps_si128(
      _mm_shuffle_ps(_mm_castpd_ps(a), _mm_castpd_ps(b), _MM_SHUFFLE(2, 0, 2, 0)));
}

// The per-axis values of a FloatBoxRay, x, y and z in lanes 0 to 2 (see float_box_ray_axes).
struct FloatBoxRayAxes {
  alignas(16) float inv_dir[4];
  alignas(16) float origin_near[4];
  alignas(16) float origin_far[4];
  int forward_bits;  // bit a set where the direction is forward along axis a
};

// set_float_box_ray_per_axis's operations for x, y and z in the lanes of SSE2 vectors (a fourth
// lane repeats z; axis by axis, this was 9 % of an incoherent mesh ray's instructions, see
// docs/PERFORMANCE.md "Where an incoherent ray's time goes on Intel"): the division and conversions
// are the same IEEE operations (cvtpd2ps and cvtsd2ss round alike; (double)f > x is cmpltpd(x, f),
// false with a NaN as the scalar compare), the steps and selections the same integer operations, so
// the results are bit-identical.
[[gnu::always_inline]] inline FloatBoxRayAxes float_box_ray_axes(const Ray& ray) {
  const __m128d origin_xy = _mm_set_pd(ray.origin.y, ray.origin.x);
  const __m128d origin_z = _mm_set1_pd(ray.origin.z);
  const __m128d one = _mm_set1_pd(1.0);
  const __m128d inv_xy = _mm_div_pd(one, _mm_set_pd(ray.direction.y, ray.direction.x));
  const __m128d inv_z = _mm_div_pd(one, _mm_set1_pd(ray.direction.z));
  const __m128 f = _mm_movelh_ps(_mm_cvtpd_ps(origin_xy), _mm_cvtpd_ps(origin_z));
  const __m128d f_xy = _mm_cvtps_pd(f), f_z = _mm_cvtps_pd(_mm_movehl_ps(f, f));
  const __m128i f_bits = _mm_castps_si128(f);
  const __m128i sign = _mm_set1_epi32(static_cast<int>(0x80000000u));
  // round_down_to_float: f stepped down (-(step up of -f)) where (double)f > x, else f.
  const __m128i down = select_bits_sse2(
      narrow_masks_sse2(_mm_cmplt_pd(origin_xy, f_xy), _mm_cmplt_pd(origin_z, f_z)),
      _mm_xor_si128(float_step_up_bits_sse2(_mm_xor_si128(f_bits, sign)), sign), f_bits);
  // round_up_to_float: f stepped up where (double)f < x, else f.
  const __m128i up = select_bits_sse2(
      narrow_masks_sse2(_mm_cmplt_pd(f_xy, origin_xy), _mm_cmplt_pd(f_z, origin_z)),
      float_step_up_bits_sse2(f_bits), f_bits);
  const __m128d zero = _mm_setzero_pd();
  const __m128i forward = narrow_masks_sse2(_mm_cmpge_pd(inv_xy, zero), _mm_cmpge_pd(inv_z, zero));
  FloatBoxRayAxes axes;
  _mm_store_ps(axes.inv_dir, _mm_movelh_ps(_mm_cvtpd_ps(inv_xy), _mm_cvtpd_ps(inv_z)));
  _mm_store_ps(axes.origin_near, _mm_castsi128_ps(select_bits_sse2(forward, up, down)));
  _mm_store_ps(axes.origin_far, _mm_castsi128_ps(select_bits_sse2(forward, down, up)));
  axes.forward_bits = _mm_movemask_ps(_mm_castsi128_ps(forward));
  return axes;
}
#endif

inline FloatBoxRay::FloatBoxRay(const Ray& ray) { set_float_box_ray_per_axis(*this, ray); }

// Bit c of the result is set when the ray [0, t_max] may meet child c's box (every box the
// double test accepts, and some more); entry[c] receives its float entry distance, which is at
// most float_far_limit of any t_max for which the double test accepts the box (so a later,
// smaller t_max may skip it). `limit` is FloatBoxLimit(float_far_limit(t_max)). One child at a
// time: the path of CPUs without SSE, and the reference the SIMD kernels are tested against.
inline unsigned intersect_float_child_boxes_scalar(const FloatChildBoxes& boxes,
                                                   const FloatBoxRay& ray,
                                                   const FloatBoxLimit& limit,
                                                   float entry[kWideChildren]) {
  unsigned hits = 0;
  for (int c = 0; c < kWideChildren; ++c) {
    float t0 = 0, t1 = limit.far;
    for (int a = 0; a < 3; ++a) {
      const int near = ray.near_side[a];
      const float t_near = (boxes.bound[a][near][c] - ray.origin_near[a][c]) * ray.inv_dir[a][c];
      const float t_far =
          (boxes.bound[a][1 - near][c] - ray.origin_far[a][c]) * ray.inv_dir[a][c] * kFloatFarScale;
      t0 = t_near > t0 ? t_near : t0;
      t1 = t_far < t1 ? t_far : t1;
    }
    entry[c] = t0;
    const bool hit = t0 <= t1 + kFloatTinyMargin && boxes.bound[0][0][c] <= boxes.bound[0][1][c];
    hits |= (hit ? 1u : 0u) << c;
  }
  return hits;
}

#if defined(__SSE2__)
// The SIMD kernels: one algorithm (intersect_float_child_boxes_lanes) over `Lanes` children at
// once, with the vector operations of SSE2 (4 lanes) or AVX2 (8). The operations take and give
// vectors by reference: an AVX vector passed by value through a function compiled without AVX
// changes the ABI, and the algorithm is compiled for the baseline, to be inlined whole
// (gnu::flatten) into functions compiled for AVX2.
struct Sse2Lanes {
  using V = __m128;
  [[gnu::always_inline]] static void set1(V& r, float x) { r = _mm_set1_ps(x); }
  [[gnu::always_inline]] static void load(V& r, const float* p) { r = _mm_loadu_ps(p); }
  [[gnu::always_inline]] static void store(float* p, const V& a) { _mm_storeu_ps(p, a); }
  [[gnu::always_inline]] static void sub(V& r, const V& a, const V& b) { r = _mm_sub_ps(a, b); }
  [[gnu::always_inline]] static void mul(V& r, const V& a, const V& b) { r = _mm_mul_ps(a, b); }
  [[gnu::always_inline]] static void add(V& r, const V& a, const V& b) { r = _mm_add_ps(a, b); }
  [[gnu::always_inline]] static void max(V& r, const V& a, const V& b) { r = _mm_max_ps(a, b); }
  [[gnu::always_inline]] static void min(V& r, const V& a, const V& b) { r = _mm_min_ps(a, b); }
  // Bit c set where a[c] <= b[c] (false with a NaN).
  [[gnu::always_inline]] static unsigned le_mask(const V& a, const V& b) {
    return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(a, b)));
  }
  // Bit c set where !(a[c] < b[c]) (true with a NaN).
  [[gnu::always_inline]] static unsigned not_lt_mask(const V& a, const V& b) {
    return static_cast<unsigned>(_mm_movemask_ps(_mm_cmpnlt_ps(a, b)));
  }
};

// No FMA: the "avx2" target does not enable it.
struct Avx2Lanes {
  using V = __m256;
  [[gnu::target("avx2")]] static void set1(V& r, float x) { r = _mm256_set1_ps(x); }
  [[gnu::target("avx2")]] static void load(V& r, const float* p) { r = _mm256_loadu_ps(p); }
  [[gnu::target("avx2")]] static void store(float* p, const V& a) { _mm256_storeu_ps(p, a); }
  [[gnu::target("avx2")]] static void sub(V& r, const V& a, const V& b) { r = _mm256_sub_ps(a, b); }
  [[gnu::target("avx2")]] static void mul(V& r, const V& a, const V& b) { r = _mm256_mul_ps(a, b); }
  [[gnu::target("avx2")]] static void add(V& r, const V& a, const V& b) { r = _mm256_add_ps(a, b); }
  [[gnu::target("avx2")]] static void max(V& r, const V& a, const V& b) { r = _mm256_max_ps(a, b); }
  [[gnu::target("avx2")]] static void min(V& r, const V& a, const V& b) { r = _mm256_min_ps(a, b); }
  // _CMP_LE_OS is cmpleps's predicate.
  [[gnu::target("avx2")]] static unsigned le_mask(const V& a, const V& b) {
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OS)));
  }
  // _CMP_NLT_US is cmpnltps's predicate.
  [[gnu::target("avx2")]] static unsigned not_lt_mask(const V& a, const V& b) {
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_NLT_US)));
  }
};

// Fills `r` from float_box_ray_axes, each value repeated with the stores of `Lanes`: the first
// node step loads them with that width, and a load wider than the store before it cannot take
// its value from the store buffer (it waits until the store is written).
template <typename Lanes>
[[gnu::always_inline]] inline void set_float_box_ray_lanes(FloatBoxRay& r, const Ray& ray) {
  using V = typename Lanes::V;
  const FloatBoxRayAxes axes = float_box_ray_axes(ray);
  const auto fill = [](float* to, float value) {
    V v;
    Lanes::set1(v, value);
    for (int c = 0; c < kWideChildren; c += static_cast<int>(sizeof(V) / sizeof(float)))
      Lanes::store(to + c, v);
  };
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    fill(r.inv_dir[a], axes.inv_dir[a]);
    fill(r.origin_near[a], axes.origin_near[a]);
    fill(r.origin_far[a], axes.origin_far[a]);
    r.near_side[a] = 1 - ((axes.forward_bits >> a) & 1);
  }
}

// intersect_float_child_boxes_scalar's results for the children from `first` on, as many as a
// vector holds, in bits 0 up of the result and entry[0] up. maxps(a, b) is a > b ? a : b, NaN
// included, as the scalar comparison, so entry is made by the same operations. The far side is
// not: the scalar test's t1 + margin, with t1 the minimum of far_limit and the far distances that
// are not NaN (minps(t_far, t1) leaves a NaN t_far out; a NaN far_limit gives NaN), is compared
// as each of its terms plus the margin: float addition is monotonic, so (min of terms) + margin
// is the min of (term + margin), and t0 (never NaN: it starts at 0 and maxps leaves NaNs out) is
// at most that when it is at most far_limit + margin and not above any far distance + margin, a
// NaN one passing (cmpnltps). The same bits; each axis's compare waits for its own distance only,
// not for a chain of three minima and an addition, the node step's longest latency (four cycles
// a step shorter, docs/PERFORMANCE.md "The incoherent ray's stalls").
template <typename Lanes>
inline unsigned intersect_float_child_boxes_lanes(const FloatChildBoxes& boxes,
                                                  const FloatBoxRay& ray,
                                                  const FloatBoxLimit& far_limit, int first,
                                                  float* entry) {
  using V = typename Lanes::V;
  V t0, far_scale, margin, bound, origin, inv, t_near, t_far[3];
  Lanes::set1(t0, 0.0f);
  Lanes::set1(far_scale, kFloatFarScale);
  Lanes::set1(margin, kFloatTinyMargin);
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const int near = ray.near_side[a];
    Lanes::load(inv, ray.inv_dir[a]);
    Lanes::load(bound, &boxes.bound[a][near][first]);
    Lanes::load(origin, ray.origin_near[a]);
    Lanes::sub(t_near, bound, origin);
    Lanes::mul(t_near, t_near, inv);
    Lanes::load(bound, &boxes.bound[a][1 - near][first]);
    Lanes::load(origin, ray.origin_far[a]);
    Lanes::sub(t_far[a], bound, origin);
    Lanes::mul(t_far[a], t_far[a], inv);
    Lanes::mul(t_far[a], t_far[a], far_scale);
    Lanes::add(t_far[a], t_far[a], margin);
    Lanes::max(t0, t_near, t0);
  }
  Lanes::store(entry, t0);
  V limit, lo_x, hi_x;
  Lanes::load(limit, far_limit.entry_max);
  Lanes::load(lo_x, &boxes.bound[0][0][first]);
  Lanes::load(hi_x, &boxes.bound[0][1][first]);
  return Lanes::le_mask(t0, limit) & Lanes::not_lt_mask(t_far[0], t0) &
         Lanes::not_lt_mask(t_far[1], t0) & Lanes::not_lt_mask(t_far[2], t0) &
         Lanes::le_mask(lo_x, hi_x);
}

// The kernel of CPUs without AVX2: the children in two halves of four.
[[gnu::flatten]] inline unsigned intersect_float_child_boxes_sse2(const FloatChildBoxes& boxes,
                                                                  const FloatBoxRay& ray,
                                                                  const FloatBoxLimit& far_limit,
                                                                  float entry[kWideChildren]) {
  return intersect_float_child_boxes_lanes<Sse2Lanes>(boxes, ray, far_limit, 0, entry) |
         intersect_float_child_boxes_lanes<Sse2Lanes>(boxes, ray, far_limit, 4, entry + 4) << 4;
}

// The ray's constants for the SSE2 kernel and the AVX2 one (with 256-bit stores).
[[gnu::flatten]] inline void set_float_box_ray_sse2(FloatBoxRay& r, const Ray& ray) {
  set_float_box_ray_lanes<Sse2Lanes>(r, ray);
}
[[gnu::target("avx2"), gnu::flatten]] inline void set_float_box_ray_avx2(FloatBoxRay& r,
                                                                         const Ray& ray) {
  set_float_box_ray_lanes<Avx2Lanes>(r, ray);
}

// Eight children in one go; only where the CPU has AVX2 (wide_box_kernel.h).
[[gnu::target("avx2"), gnu::flatten]] inline unsigned intersect_float_child_boxes_avx2(
    const FloatChildBoxes& boxes, const FloatBoxRay& ray, const FloatBoxLimit& far_limit,
    float entry[kWideChildren]) {
  return intersect_float_child_boxes_lanes<Avx2Lanes>(boxes, ray, far_limit, 0, entry);
}
#endif

}  // namespace tessera
