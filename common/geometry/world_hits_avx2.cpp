// Four hits to world space at once (world_hits_avx2.h). Each step is instance.cpp's
// FullTransforms::world_point (Affine::apply_point, Affine::point_error, round_trip_error) or
// DiagonalTransforms::world_point (DiagonalAffine's, diagonal_round_trip_error) and world_normals
// (to_object's transpose, normalize_or) or the instance's face normals, for four lanes, lane by
// lane the same operations on the same operands in the same order. A lane whose diagonal products
// are not the full ones (same_as_full), or whose shading normal is not its normal (a smooth
// mesh's), takes to_world_hit alone.
#include "common/geometry/world_hits_avx2.h"

#if defined(__SSE2__)  // the whole file: x86-64's AVX2

#include <immintrin.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <limits>

#include "common/geometry/avx2_lanes.h"
#include "common/math/float_error.h"

namespace tessera {
namespace {

using namespace avx2_lanes;

// WorldHit's point, point_error, normal and shading_normal are twelve doubles in a row: each
// lane's block is stored as three vectors.
constexpr std::size_t kBlock = offsetof(WorldHit, point);
static_assert(offsetof(WorldHit, point_error) == kBlock + 3 * sizeof(double) &&
              offsetof(WorldHit, normal) == kBlock + 6 * sizeof(double) &&
              offsetof(WorldHit, shading_normal) == kBlock + 9 * sizeof(double));

// Four vectors, each of four doubles.
struct Quad {
  V v0, v1, v2, v3;
};

// Vectors r0..r3 of four values each become four vectors of the first, second, third and fourth
// values of all. (Vectors in named variables, not arrays: GCC kept arrays of them on the stack.)
[[gnu::target("avx2"), gnu::always_inline]] inline Quad transpose(V r0, V r1, V r2, V r3) {
  const V t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
  const V t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
  return {_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
          _mm256_permute2f128_pd(t0, t2, 0x31), _mm256_permute2f128_pd(t1, t3, 0x31)};
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

// The lanes' `member`s, a vector for each component, read a double at a time. Not as 32-byte
// blocks transposed (`torworld`'s first form): the shapes write their LocalHits a member at a
// time just before, and a load that spans several of those stores cannot take its data from them
// (store forwarding fails) and waits for them to reach the cache. Read as blocks, the floor's
// lanes took as long as a lane at a time; read so, the tori render in about 0.99 of that time
// (docs/PERFORMANCE.md, `floorpkt`).
[[gnu::target("avx2"), gnu::always_inline]] inline Vec3Lanes member_lanes(
    const LocalHit* const from[4], Vec3 LocalHit::*member) {
  const Vec3 &v0 = from[0]->*member, &v1 = from[1]->*member, &v2 = from[2]->*member,
             &v3 = from[3]->*member;
  return {_mm256_set_pd(v3.x, v2.x, v1.x, v0.x), _mm256_set_pd(v3.y, v2.y, v1.y, v0.y),
          _mm256_set_pd(v3.z, v2.z, v1.z, v0.z)};
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

// A lane's points (the world point and its error bound).
struct PointLanes {
  Vec3Lanes point, error;
};

// FullTransforms::world_point.
[[gnu::target("avx2"), gnu::always_inline]] inline PointLanes full_world_points(
    const Instance& instance, const Vec3Lanes& point, const Vec3Lanes& point_error) {
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
  return {world,
          {add(error.x, mul(terms.x, gamma11)), add(error.y, mul(terms.y, gamma11)),
           add(error.z, mul(terms.z, gamma11))}};
}

// One component of DiagonalTransforms::world_point: DiagonalAffine::apply_point and point_error
// of to_world, then diagonal_round_trip_error (instance.cpp) of |point| + error; c the component.
[[gnu::target("avx2"), gnu::always_inline]] inline void diagonal_world_component(
    const Instance::Diagonal& diagonal, int c, V p, V p_error, V& world, V& error) {
  const double scale = diagonal.to_world.scale[c], offset = diagonal.to_world.offset[c];
  world = add(mul(splat(scale), p), splat(offset));
  error = add(
      mul(add(magnitude(mul(splat(scale), p)), splat(std::fabs(offset))), splat(gamma_bound(3))),
      mul(mul(splat(std::fabs(scale)), p_error), splat(gamma_bound(3) + 1)));
  const V object_term =
      add(mul(splat(std::fabs(diagonal.to_object.scale[c])), add(magnitude(world), error)),
          splat(std::fabs(diagonal.to_object.offset[c])));
  const V term = add(mul(splat(std::fabs(scale)), object_term), splat(std::fabs(offset)));
  error = add(error, mul(term, splat(gamma_bound(11))));
}

// The lanes where same_as_full(a, b) (diagonal_affine.h) fails, as a compare's mask: the
// product of a's components times the product of b's, in the same order, not in (0, inf).
[[gnu::target("avx2"), gnu::always_inline]] inline V not_same_as_full(const Vec3Lanes& a,
                                                                      const Vec3Lanes& b) {
  const V product = magnitude(mul(mul(mul(a.x, a.y), a.z), mul(mul(b.x, b.y), b.z)));
  return _mm256_or_pd(
      _mm256_cmp_pd(product, _mm256_setzero_pd(), _CMP_NGT_UQ),
      _mm256_cmp_pd(product, splat(std::numeric_limits<double>::infinity()), _CMP_NLT_UQ));
}

// normalize_or(n, {}) with {0, 0, 1} for a normal without a usable length (zero, subnormal or
// not finite; the ordered compares fail on NaN), as world_normals (instance.cpp) takes it.
[[gnu::target("avx2"), gnu::always_inline]] inline Vec3Lanes unit_normals(const Vec3Lanes& n) {
  const V length = _mm256_sqrt_pd(add(add(mul(n.x, n.x), mul(n.y, n.y)), mul(n.z, n.z)));
  const V usable = _mm256_and_pd(
      _mm256_cmp_pd(length, splat(1e-300), _CMP_GT_OQ),
      _mm256_cmp_pd(length, splat(std::numeric_limits<double>::infinity()), _CMP_LT_OQ));
  return {unit_or(n.x, length, usable, 0), unit_or(n.y, length, usable, 0),
          unit_or(n.z, length, usable, 1)};
}

// Lane L of a Quad's vectors.
template <int L>
[[gnu::target("avx2"), gnu::always_inline]] inline V lane(const Quad& q) {
  if constexpr (L == 0) return q.v0;
  if constexpr (L == 1) return q.v1;
  if constexpr (L == 2) return q.v2;
  return q.v3;
}

// Lane L's hit, when L is in `lanes`, from its twelve doubles (lane L of out0, out1, out2: point,
// point_error, normal, shading normal) as to_world_hit writes it; with face normals only the
// first six are taken and the normals are the face's. A lane in `alone_lanes` (a diagonal product
// that is not the full one) or with a shading normal of its own (a smooth mesh's) takes
// to_world_hit itself.
template <bool kFaceNormals, int L>
[[gnu::target("avx2"), gnu::always_inline]] inline void store_lane(
    const Instance& instance, const LocalHit locals[4], WorldHit* const hits[4], unsigned lanes,
    int alone_lanes, const Quad& out0, const Quad& out1, const Quad& out2) {
  if (((lanes >> L) & 1u) == 0) return;
  const LocalHit& local = locals[L];
  WorldHit& hit = *hits[L];
  if (((alone_lanes >> L) & 1) != 0 ||
      (!kFaceNormals && !same_bits(local.shading_normal, local.normal))) [[unlikely]] {
    to_world_hit(instance, local, hit);
    return;
  }
  auto* to = reinterpret_cast<double*>(reinterpret_cast<std::byte*>(&hit) + kBlock);
  _mm256_storeu_pd(to, lane<L>(out0));
  _mm256_storeu_pd(to + 4, lane<L>(out1));
  if constexpr (kFaceNormals) {
    hit.normal = (*instance.face_normals)[local.part];
    hit.shading_normal = hit.normal;
  } else {
    _mm256_storeu_pd(to + 8, lane<L>(out2));
  }
  hit.t = local.t;
  hit.object_point = local.point;
  hit.part = local.part;
  hit.object = instance.object;
}

// to_world_hits_avx2 for one kind of instance (its transforms diagonal or full, with face
// normals or without), each kind its own code: tested in the loop, the kinds cost the tori's
// calls some 50 instructions more.
template <bool kDiagonal, bool kFaceNormals>
[[gnu::target("avx2"), gnu::always_inline]] inline void world_hits(const Instance& instance,
                                                                   const LocalHit locals[4],
                                                                   unsigned lanes,
                                                                   WorldHit* const hits[4]) {
  // Lanes outside `lanes` repeat the first one's hit (computed, not used): an unhit lane's
  // LocalHit was never written.
  const int first = std::countr_zero(lanes);
  const auto local = [&](int l) { return &locals[(lanes >> l) & 1u ? l : first]; };
  const LocalHit* const from[4] = {local(0), local(1), local(2), local(3)};
  const Vec3Lanes point = member_lanes(from, &LocalHit::point);
  const Vec3Lanes point_error = member_lanes(from, &LocalHit::point_error);

  // The world points, and the lanes whose diagonal products are not the full ones.
  PointLanes world;
  V alone = _mm256_setzero_pd();
  if constexpr (kDiagonal) {
    diagonal_world_component(*instance.diagonal, 0, point.x, point_error.x, world.point.x,
                             world.error.x);
    diagonal_world_component(*instance.diagonal, 1, point.y, point_error.y, world.point.y,
                             world.error.y);
    diagonal_world_component(*instance.diagonal, 2, point.z, point_error.z, world.point.z,
                             world.error.z);
    alone = not_same_as_full(world.point, world.error);
  } else {
    world = full_world_points(instance, point, point_error);
  }

  // world_normals: the local normal through to_object's transpose (a diagonal's is itself), then
  // unit. Not needed with face normals.
  Vec3Lanes world_normal{};
  if constexpr (!kFaceNormals) {
    const Vec3Lanes normal = member_lanes(from, &LocalHit::normal);
    if constexpr (kDiagonal) {
      const DiagonalAffine& o = instance.diagonal->to_object;
      const Vec3Lanes n{mul(splat(o.scale.x), normal.x), mul(splat(o.scale.y), normal.y),
                        mul(splat(o.scale.z), normal.z)};
      alone = _mm256_or_pd(alone, not_same_as_full(n, {splat(1), splat(1), splat(1)}));
      world_normal = unit_normals(n);
    } else {
      const Affine& o = instance.to_object;
      world_normal = unit_normals({combine(o.m[0][0], o.m[1][0], o.m[2][0], normal),
                                   combine(o.m[0][1], o.m[1][1], o.m[2][1], normal),
                                   combine(o.m[0][2], o.m[1][2], o.m[2][2], normal)});
    }
  }

  // Back to each lane's twelve doubles; the shading normal is the normal.
  const Quad out0 = transpose(world.point.x, world.point.y, world.point.z, world.error.x);
  const Quad out1 = transpose(world.error.y, world.error.z, world_normal.x, world_normal.y);
  const Quad out2 = transpose(world_normal.z, world_normal.x, world_normal.y, world_normal.z);
  const int alone_lanes = _mm256_movemask_pd(alone);
  store_lane<kFaceNormals, 0>(instance, locals, hits, lanes, alone_lanes, out0, out1, out2);
  store_lane<kFaceNormals, 1>(instance, locals, hits, lanes, alone_lanes, out0, out1, out2);
  store_lane<kFaceNormals, 2>(instance, locals, hits, lanes, alone_lanes, out0, out1, out2);
  store_lane<kFaceNormals, 3>(instance, locals, hits, lanes, alone_lanes, out0, out1, out2);
}

}  // namespace

[[gnu::target("avx2")]] void to_world_hits_avx2(const Instance& instance, const LocalHit locals[4],
                                                unsigned lanes, WorldHit* const hits[4]) {
  if (instance.diagonal) {
    if (instance.face_normals) return world_hits<true, true>(instance, locals, lanes, hits);
    return world_hits<true, false>(instance, locals, lanes, hits);
  }
  if (instance.face_normals) return world_hits<false, true>(instance, locals, lanes, hits);
  world_hits<false, false>(instance, locals, lanes, hits);
}

}  // namespace tessera

#endif
