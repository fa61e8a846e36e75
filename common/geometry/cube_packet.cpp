// Four rays' cube tests at once (cube_packet.h). Each step is cube.cpp's narrow_to_slab,
// slab_span and nearest_face lane by lane: the same operations on the same operands. The scalar
// code's early returns become a mask: a lane hits when it passes every test, which is when the
// scalar code passes them all; the values of lanes that fail one are computed and dropped (a lane
// parallel to a slab divides by zero, which the mask then ignores, as the scalar code never
// divides). Faces are carried as doubles (small integers, exact).
#include "common/geometry/cube_packet.h"

#include <bit>
#include <cmath>

#include "common/geometry/avx2_lanes.h"
#include "common/geometry/cube_face_hit.h"
#include "common/math/ray.h"

namespace tessera {

#if defined(__SSE2__)

namespace {

using namespace avx2_lanes;

// The predicate is a template argument: _mm256_cmp_pd needs it as an immediate, which an
// ordinary argument is only once inlined (not in unoptimized builds).
template <int predicate>
[[gnu::target("avx2"), gnu::always_inline]] inline V compare(V a, V b) {
  return _mm256_cmp_pd(a, b, predicate);
}
[[gnu::target("avx2"), gnu::always_inline]] inline V all_of(V a, V b) {
  return _mm256_and_pd(a, b);
}

// The span of the four lanes through the cube's slabs (SlabSpan a lane).
struct SlabSpans {
  V t_enter, t_exit, enter_face, exit_face;
  V live;  // the lanes whose slab_span is still true
};

// narrow_to_slab for the lanes' direction components d along `axis`, the origin's component o.
[[gnu::target("avx2"), gnu::always_inline]] inline void narrow_to_slabs(double o, V d, int axis,
                                                                        SlabSpans& span) {
  const V parallel = compare<_CMP_EQ_OQ>(d, splat(0));
  // A parallel lane's answer: whether the origin is inside the slab; the span stays.
  const V inside = (o >= -1 && o <= 1) ? parallel : splat(0);
  const V t_lo = divide(splat(-1 - o), d);
  const V t_hi = divide(splat(1 - o), d);
  const V rising = compare<_CMP_GT_OQ>(d, splat(0));
  const V t_near = select(rising, t_lo, t_hi);
  const V t_far = select(rising, t_hi, t_lo);
  const V crossing = _mm256_andnot_pd(parallel, compare<_CMP_GT_OQ>(t_far, splat(0)));
  const V low_face = splat(2 * axis), high_face = splat(2 * axis + 1);
  const V enters = _mm256_andnot_pd(parallel, compare<_CMP_GT_OQ>(t_near, span.t_enter));
  span.t_enter = select(enters, t_near, span.t_enter);
  span.enter_face = select(enters, select(rising, low_face, high_face), span.enter_face);
  const V exits = _mm256_andnot_pd(parallel, compare<_CMP_LT_OQ>(t_far, span.t_exit));
  span.t_exit = select(exits, t_far, span.t_exit);
  span.exit_face = select(exits, select(rising, high_face, low_face), span.exit_face);
  span.live = all_of(span.live, _mm256_or_pd(inside, crossing));
}

[[gnu::target("avx2"), gnu::always_inline]] inline V finite(V a) {
  return compare<_CMP_LT_OQ>(magnitude(a), splat(kInfinity));
}

}  // namespace

[[gnu::target("avx2")]] unsigned intersect_cube_packet_avx2(const Vec3& origin,
                                                            const Vec3 directions[4],
                                                            unsigned lanes, const double t_max[4],
                                                            LocalHit hits[4]) {
  if (!is_finite(origin)) return 0;
  const V dx = _mm256_setr_pd(directions[0].x, directions[1].x, directions[2].x, directions[3].x);
  const V dy = _mm256_setr_pd(directions[0].y, directions[1].y, directions[2].y, directions[3].y);
  const V dz = _mm256_setr_pd(directions[0].z, directions[1].z, directions[2].z, directions[3].z);
  SlabSpans span{splat(-kInfinity), splat(kInfinity), splat(-1), splat(-1),
                 all_of(all_of(finite(dx), finite(dy)), finite(dz))};
  narrow_to_slabs(origin.x, dx, 0, span);
  narrow_to_slabs(origin.y, dy, 1, span);
  narrow_to_slabs(origin.z, dz, 2, span);
  span.live = all_of(span.live, compare<_CMP_LE_OQ>(span.t_enter, span.t_exit));
  // nearest_face: the entry when it is ahead and a slab bounds it, else the exit.
  const V zero = splat(0);
  const V enter_ahead =
      all_of(compare<_CMP_GT_OQ>(span.t_enter, zero), compare<_CMP_GE_OQ>(span.enter_face, zero));
  const V exit_ahead =
      all_of(compare<_CMP_GT_OQ>(span.t_exit, zero), compare<_CMP_GE_OQ>(span.exit_face, zero));
  const V t = select(enter_ahead, span.t_enter, span.t_exit);
  const V face = select(enter_ahead, span.enter_face, span.exit_face);
  const V hit = all_of(all_of(span.live, _mm256_or_pd(enter_ahead, exit_ahead)),
                       compare<_CMP_LT_OQ>(t, _mm256_loadu_pd(t_max)));
  alignas(32) double ts[4], faces[4];
  _mm256_store_pd(ts, t);
  _mm256_store_pd(faces, face);
  const unsigned hit_lanes = static_cast<unsigned>(_mm256_movemask_pd(hit)) & lanes;
  for (unsigned m = hit_lanes; m != 0; m &= m - 1) {
    const int l = std::countr_zero(m);
    cube_detail::face_hit(origin, directions[l], ts[l], static_cast<int>(faces[l]), hits[l]);
  }
  return hit_lanes;
}

#endif

}  // namespace tessera
