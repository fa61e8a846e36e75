// Four hits to world space at once (world_hits_avx2.h). Each step is instance.cpp's
// FullTransforms::world_point (Affine::apply_point, Affine::point_error, round_trip_error) and
// world_normals (Affine::apply_transpose of to_object, normalize_or) for four lanes, lane by lane
// the same operations on the same operands in the same order. A hit whose shading normal is not
// its normal (a smooth mesh's) takes to_world_hit alone.
#include "common/geometry/world_hits_avx2.h"

#if defined(__SSE2__)  // the whole file: x86-64's AVX2

#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>

#include "common/math/float_error.h"

namespace tessera {
namespace {

using V = __m256d;

// LocalHit's point, point_error, normal and shading_normal, and WorldHit's same four members,
// are twelve doubles in a row at the same offset: each lane's block moves as three vectors.
constexpr std::size_t kBlock = offsetof(LocalHit, point);
static_assert(offsetof(LocalHit, point_error) == kBlock + 3 * sizeof(double) &&
              offsetof(LocalHit, normal) == kBlock + 6 * sizeof(double) &&
              offsetof(LocalHit, shading_normal) == kBlock + 9 * sizeof(double));
static_assert(offsetof(WorldHit, point) == kBlock &&
              offsetof(WorldHit, point_error) == kBlock + 3 * sizeof(double) &&
              offsetof(WorldHit, normal) == kBlock + 6 * sizeof(double) &&
              offsetof(WorldHit, shading_normal) == kBlock + 9 * sizeof(double));

// Four vectors, each of four doubles.
struct Quad {
  V v0, v1, v2, v3;
};

// Vectors r0..r3 of a lane's four values each become four vectors of one value for every lane,
// and back. (Vectors in named variables, not arrays: GCC kept arrays of them on the stack.)
[[gnu::target("avx2"), gnu::always_inline]] inline Quad transpose(V r0, V r1, V r2, V r3) {
  const V t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
  const V t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
  return {_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
          _mm256_permute2f128_pd(t0, t2, 0x31), _mm256_permute2f128_pd(t1, t3, 0x31)};
}

// The k-th four of the twelve doubles from kBlock on.
[[gnu::target("avx2"), gnu::always_inline]] inline V load_block(const LocalHit& local, int k) {
  return _mm256_loadu_pd(
      reinterpret_cast<const double*>(reinterpret_cast<const std::byte*>(&local) + kBlock) + 4 * k);
}
[[gnu::target("avx2"), gnu::always_inline]] inline Quad load_blocks(const LocalHit* const from[4],
                                                                    int k) {
  return transpose(load_block(*from[0], k), load_block(*from[1], k), load_block(*from[2], k),
                   load_block(*from[3], k));
}

[[gnu::target("avx2"), gnu::always_inline]] inline V splat(double x) { return _mm256_set1_pd(x); }
[[gnu::target("avx2"), gnu::always_inline]] inline V add(V a, V b) { return _mm256_add_pd(a, b); }
[[gnu::target("avx2"), gnu::always_inline]] inline V mul(V a, V b) { return _mm256_mul_pd(a, b); }
[[gnu::target("avx2"), gnu::always_inline]] inline V magnitude(V a) {
  return _mm256_andnot_pd(splat(-0.0), a);
}

// A vector of lanes for each component.
struct Vec3Lanes {
  V x, y, z;
};

// The sum a0 v.x + a1 v.y + a2 v.z, left to right, as Affine's rows and columns add.
[[gnu::target("avx2"), gnu::always_inline]] inline V combine(double a0, double a1, double a2,
                                                             const Vec3Lanes& v) {
  return add(add(mul(splat(a0), v.x), mul(splat(a1), v.y)), mul(splat(a2), v.z));
}

// Row r of |lin(a)| v + |t(a)|: instance.cpp's abs_linear plus abs_translation. (Functions, not
// lambdas: a lambda does not take its enclosing function's target.)
[[gnu::target("avx2"), gnu::always_inline]] inline V abs_affine_row(const Affine& a, int r,
                                                                    const Vec3Lanes& v) {
  return add(combine(std::fabs(a.m[r][0]), std::fabs(a.m[r][1]), std::fabs(a.m[r][2]), v),
             splat(std::fabs(a.m[r][3])));
}
[[gnu::target("avx2"), gnu::always_inline]] inline Vec3Lanes abs_affine(const Affine& a,
                                                                        const Vec3Lanes& v) {
  return {abs_affine_row(a, 0, v), abs_affine_row(a, 1, v), abs_affine_row(a, 2, v)};
}

// Row r of Affine::apply_point.
[[gnu::target("avx2"), gnu::always_inline]] inline V point_row(const Affine& a, int r,
                                                               const Vec3Lanes& p) {
  return add(combine(a.m[r][0], a.m[r][1], a.m[r][2], p), splat(a.m[r][3]));
}

// Affine::row_error.
[[gnu::target("avx2"), gnu::always_inline]] inline V row_error(const Affine& a, int r,
                                                               const Vec3Lanes& p,
                                                               const Vec3Lanes& p_error) {
  const V size =
      add(add(add(magnitude(mul(splat(a.m[r][0]), p.x)), magnitude(mul(splat(a.m[r][1]), p.y))),
              magnitude(mul(splat(a.m[r][2]), p.z))),
          splat(std::fabs(a.m[r][3])));
  const V carried =
      combine(std::fabs(a.m[r][0]), std::fabs(a.m[r][1]), std::fabs(a.m[r][2]), p_error);
  return add(mul(splat(gamma_bound(3)), size), mul(splat(gamma_bound(3) + 1), carried));
}

// c / length where `usable`, else `fallback`.
[[gnu::target("avx2"), gnu::always_inline]] inline V unit_or(V c, V length, V usable,
                                                             double fallback) {
  return _mm256_blendv_pd(splat(fallback), _mm256_div_pd(c, length), usable);
}

// A lane's hit from its twelve doubles, as to_world_hit writes it; a hit whose shading normal is
// not its normal takes to_world_hit itself.
[[gnu::target("avx2"), gnu::always_inline]] inline void store_lane(const Instance& instance,
                                                                   const LocalHit& local,
                                                                   WorldHit& hit, V v0, V v1,
                                                                   V v2) {
  if (!same_bits(local.shading_normal, local.normal)) [[unlikely]] {
    to_world_hit(instance, local, hit);
    return;
  }
  auto* to = reinterpret_cast<double*>(reinterpret_cast<std::byte*>(&hit) + kBlock);
  _mm256_storeu_pd(to, v0);
  _mm256_storeu_pd(to + 4, v1);
  _mm256_storeu_pd(to + 8, v2);
  hit.t = local.t;
  hit.object_point = local.point;
  hit.part = local.part;
  hit.object = instance.object;
}

}  // namespace

[[gnu::target("avx2")]] void to_world_hits_avx2(const Instance& instance, const LocalHit locals[4],
                                                unsigned lanes, WorldHit* const hits[4]) {
  // Lanes outside `lanes` repeat the first one's hit (computed, not used): an unhit lane's
  // LocalHit was never written.
  const int first = std::countr_zero(lanes);
  const auto local = [&](int l) { return &locals[(lanes >> l) & 1u ? l : first]; };
  const LocalHit* const from[4] = {local(0), local(1), local(2), local(3)};
  const Quad in0 = load_blocks(from, 0), in1 = load_blocks(from, 1), in2 = load_blocks(from, 2);
  const Vec3Lanes point{in0.v0, in0.v1, in0.v2};
  const Vec3Lanes point_error{in0.v3, in1.v0, in1.v1};
  const Vec3Lanes normal{in1.v2, in1.v3, in2.v0};

  // FullTransforms::world_point.
  const Affine& w = instance.to_world;
  const Vec3Lanes world{point_row(w, 0, point), point_row(w, 1, point), point_row(w, 2, point)};
  const Vec3Lanes error{row_error(w, 0, point, point_error), row_error(w, 1, point, point_error),
                        row_error(w, 2, point, point_error)};
  // round_trip_error of |point| + error.
  const Vec3Lanes object_terms = abs_affine(
      instance.to_object, {add(magnitude(world.x), error.x), add(magnitude(world.y), error.y),
                           add(magnitude(world.z), error.z)});
  const Vec3Lanes terms = abs_affine(w, object_terms);
  const V gamma11 = splat(gamma_bound(11));
  const Vec3Lanes world_error{add(error.x, mul(terms.x, gamma11)),
                              add(error.y, mul(terms.y, gamma11)),
                              add(error.z, mul(terms.z, gamma11))};

  // world_normals: to_object's transpose, then normalize_or with {0, 0, 1} for a normal without
  // a usable length (zero, subnormal or not finite; the ordered compares fail on NaN).
  const Affine& o = instance.to_object;
  const Vec3Lanes n{combine(o.m[0][0], o.m[1][0], o.m[2][0], normal),
                    combine(o.m[0][1], o.m[1][1], o.m[2][1], normal),
                    combine(o.m[0][2], o.m[1][2], o.m[2][2], normal)};
  const V length = _mm256_sqrt_pd(add(add(mul(n.x, n.x), mul(n.y, n.y)), mul(n.z, n.z)));
  const V usable = _mm256_and_pd(
      _mm256_cmp_pd(length, splat(1e-300), _CMP_GT_OQ),
      _mm256_cmp_pd(length, splat(std::numeric_limits<double>::infinity()), _CMP_LT_OQ));
  const Vec3Lanes world_normal{unit_or(n.x, length, usable, 0), unit_or(n.y, length, usable, 0),
                               unit_or(n.z, length, usable, 1)};

  // Back to each lane's twelve doubles; the shading normal is the normal.
  const Quad out0 = transpose(world.x, world.y, world.z, world_error.x);
  const Quad out1 = transpose(world_error.y, world_error.z, world_normal.x, world_normal.y);
  const Quad out2 = transpose(world_normal.z, world_normal.x, world_normal.y, world_normal.z);
  if (lanes & 1u) store_lane(instance, locals[0], *hits[0], out0.v0, out1.v0, out2.v0);
  if (lanes & 2u) store_lane(instance, locals[1], *hits[1], out0.v1, out1.v1, out2.v1);
  if (lanes & 4u) store_lane(instance, locals[2], *hits[2], out0.v2, out1.v2, out2.v2);
  if (lanes & 8u) store_lane(instance, locals[3], *hits[3], out0.v3, out1.v3, out2.v3);
}

}  // namespace tessera

#endif
