// Four rays' torus frames at once (torus_packet.h). Each step is torus.cpp's form_line,
// line_quartic and first_root_bracket (with quartic_first_root_bracket) for kInOrder, lane by
// lane: the same operations on the same operands in the same order. The scalar code's early returns
// become a mask: a lane is formed when it passes every test, which is when the scalar code passes
// them all; the values of lanes that fail one are computed and dropped. Where std::max / std::min /
// std::clamp pick an operand, the choice is made as they make it, NaN and signed zeros included
// (avx2_lanes.h).
#include "common/geometry/torus_packet.h"

#include <bit>
#include <cmath>
#include <limits>
#include <optional>

#include "common/geometry/avx2_lanes.h"
#include "common/math/float_error.h"

namespace tessera {

#if defined(__SSE2__)

namespace {

using namespace avx2_lanes;

// hypot_inline (hypot.h) per lane; lanes outside its ranges take std::hypot, as it does.
[[gnu::target("avx2"), gnu::always_inline]] inline V hypot_lanes(V x, V y) {
  const V abs_x = magnitude(x), abs_y = magnitude(y);
  const V ax = std_max(abs_x, abs_y), ay = std_min(abs_x, abs_y);
  const V in_range = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(ax, splat(0x1p511), _CMP_LE_OQ),
                                                 _mm256_cmp_pd(ay, splat(0x1p-459), _CMP_GE_OQ)),
                                   _mm256_cmp_pd(ay, mul(ax, splat(0x1p-54)), _CMP_GT_OQ));
  const V h = _mm256_sqrt_pd(add(mul(ax, ax), mul(ay, ay)));
  const V two = splat(2.0);
  const V near_ay = _mm256_cmp_pd(h, mul(two, ay), _CMP_LE_OQ);
  const V delta_y = sub(h, ay), delta_x = sub(h, ax);
  const V t1 = select(near_ay, mul(ax, sub(mul(two, delta_y), ax)),
                      mul(mul(two, delta_x), sub(ax, mul(two, ay))));
  const V t2 = select(near_ay, mul(sub(delta_y, mul(two, sub(ax, ay))), delta_y),
                      add(mul(sub(mul(splat(4.0), delta_x), ay), ay), mul(delta_x, delta_x)));
  V result = sub(h, divide(add(t1, t2), mul(two, h)));
  const int outside = ~_mm256_movemask_pd(in_range) & 0xf;
  if (outside != 0) [[unlikely]] {
    Lanes r = lanes_of(result);
    const Lanes xs = lanes_of(x), ys = lanes_of(y);
    for (int l = 0; l < 4; ++l)
      if (outside & (1 << l)) r.v[l] = std::hypot(xs.v[l], ys.v[l]);
    result = _mm256_load_pd(r.v);
  }
  return result;
}

// value(index[l]) in lane l.
template <class Value>
[[gnu::target("avx2"), gnu::always_inline]] inline V lanes_at(const int (&index)[4],
                                                              const Value& value) {
  return _mm256_setr_pd(value(index[0]), value(index[1]), value(index[2]), value(index[3]));
}

// The squared distance from the axis of f + u s (axis_distance2 in torus.cpp).
[[gnu::target("avx2"), gnu::always_inline]] inline V axis_distance2_lanes(V fx, V fy, V ux, V uy,
                                                                          V s) {
  const V x = add(fx, mul(ux, s)), y = add(fy, mul(uy, s));
  return add(mul(x, x), mul(y, y));
}

// narrow_to_slab (torus.cpp) for the lanes: the span [t_enter, t_exit] narrowed to the planes at
// -half and +half on one axis; `formed` loses the lanes parallel to them and outside.
[[gnu::target("avx2"), gnu::always_inline]] inline void narrow_to_slab(double o, V d, double half,
                                                                       V& t_enter, V& t_exit,
                                                                       V& formed) {
  const V zero = _mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_EQ_OQ);
  if (!(std::fabs(o) <= half)) formed = _mm256_andnot_pd(zero, formed);
  const V near_plane =
      select(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_LT_OQ), splat(half), splat(-half));
  const V t_near = divide(sub(near_plane, splat(o)), d);
  const V t_far = divide(sub(negate(near_plane), splat(o)), d);
  t_enter = select(zero, t_enter, std_max(t_enter, t_near));
  t_exit = select(zero, t_exit, std_min(t_exit, t_far));
}

// next_up (float_error.h) per lane, for lanes that are positive or +infinity (NaN lanes stay NaN;
// others are not asked for): the bit pattern one step up, unless infinite.
[[gnu::target("avx2"), gnu::always_inline]] inline V next_up_positive(V x) {
  const V stepped =
      _mm256_castsi256_pd(_mm256_add_epi64(_mm256_castpd_si256(x), _mm256_set1_epi64x(1)));
  return select(_mm256_cmp_pd(x, splat(kInfinity), _CMP_LT_OQ), stepped, x);
}

// keep_left_half (quartic_first_root.cpp) per lane.
[[gnu::target("avx2"), gnu::always_inline]] inline void keep_left_half(V b[5]) {
  const V half = splat(0.5);
  const V b01 = mul(half, add(b[0], b[1])), b12 = mul(half, add(b[1], b[2])),
          b23 = mul(half, add(b[2], b[3])), b34 = mul(half, add(b[3], b[4]));
  const V b012 = mul(half, add(b01, b12)), b123 = mul(half, add(b12, b23)),
          b234 = mul(half, add(b23, b34));
  const V b0123 = mul(half, add(b012, b123)), b1234 = mul(half, add(b123, b234));
  b[1] = b01;
  b[2] = b012;
  b[3] = b0123;
  b[4] = mul(half, add(b0123, b1234));
}

// quartic_first_root_bracket(p, lo, m) (quartic_first_root.cpp) for the lanes in `asked` (a
// compare's mask), c the quartics' coefficients: the answer's lanes where it shows a bracket,
// whose ends are written into `end` (its other lanes kept). The scalar code's early returns are
// masks; its halvings stop when no lane is left open.
[[gnu::target("avx2"), gnu::always_inline]] inline V quartic_first_root_bracket_lanes(const V c[5],
                                                                                      V lo, V m,
                                                                                      V asked,
                                                                                      V& end) {
  const V zero = _mm256_setzero_pd();
  V open = _mm256_and_pd(asked, _mm256_cmp_pd(c[4], zero, _CMP_NEQ_UQ));
  open = _mm256_and_pd(open, _mm256_cmp_pd(lo, m, _CMP_LT_OQ));
  // quartic_value_pass and (f1).
  V q[5];
  q[4] = c[4];
  q[3] = add(c[3], mul(lo, q[4]));
  q[2] = add(c[2], mul(lo, q[3]));
  q[1] = add(c[1], mul(lo, q[2]));
  q[0] = add(c[0], mul(lo, q[1]));
  open = _mm256_and_pd(open, _mm256_cmp_pd(q[0], zero, _CMP_GT_OQ));
  // finish_taylor_shift.
  q[3] = add(q[3], mul(lo, q[4]));
  q[2] = add(q[2], mul(lo, q[3]));
  q[1] = add(q[1], mul(lo, q[2]));
  q[3] = add(q[3], mul(lo, q[4]));
  q[2] = add(q[2], mul(lo, q[3]));
  q[3] = add(q[3], mul(lo, q[4]));
  const V width = sub(m, lo);
  const V largest = add(magnitude(lo), next_up_positive(width));
  // quartic_error_scale.
  const V s = add(mul(add(mul(add(mul(add(mul(magnitude(c[4]), largest), magnitude(c[3])), largest),
                                  magnitude(c[2])),
                              largest),
                          magnitude(c[1])),
                      largest),
                  magnitude(c[0]));
  open = _mm256_and_pd(open, _mm256_and_pd(_mm256_cmp_pd(s, splat(1e-100), _CMP_GT_OQ),
                                           _mm256_cmp_pd(s, splat(1e100), _CMP_LT_OQ)));
  open = _mm256_and_pd(open, _mm256_cmp_pd(magnitude(largest), splat(kInfinity), _CMP_LT_OQ));
  V found = zero;
  if (_mm256_movemask_pd(open) == 0) return found;
  const V low = negate(mul(splat(gamma_bound(128)), s));  // -margin
  // bernstein_over.
  V w = width;
  const V w2 = mul(w, w);
  const V a1 = mul(q[1], w), a2 = mul(q[2], w2), a3 = mul(q[3], mul(w2, w)),
          a4 = mul(q[4], mul(w2, w2));
  V b[5] = {q[0], add(q[0], mul(a1, splat(0.25))),
            add(add(q[0], mul(a1, splat(0.5))), mul(a2, splat(1.0 / 6))),
            add(add(add(q[0], mul(a1, splat(0.75))), mul(a2, splat(0.5))), mul(a3, splat(0.25))),
            add(add(add(add(q[0], a1), a2), a3), a4)};
  for (int halvings = 0;; ++halvings) {
    open = _mm256_and_pd(open, _mm256_cmp_pd(b[4], low, _CMP_LT_OQ));  // (f3)
    V falls = _mm256_cmp_pd(sub(b[1], b[0]), low, _CMP_LT_OQ);         // (f2)
    for (int i = 1; i < 4; ++i)
      falls = _mm256_and_pd(falls, _mm256_cmp_pd(sub(b[i + 1], b[i]), low, _CMP_LT_OQ));
    const V shown = _mm256_and_pd(open, falls);
    end = select(shown, halvings == 0 ? m : add(lo, w), end);
    found = _mm256_or_pd(found, shown);
    open = _mm256_andnot_pd(shown, open);
    if (halvings == 3 || _mm256_movemask_pd(open) == 0) return found;
    keep_left_half(b);
    w = mul(w, splat(0.5));
  }
}

// The lanes where m lies in (s_lo, s_hi) (first_root_bracket's bracket_to).
[[gnu::target("avx2"), gnu::always_inline]] inline V in_span(V m, V s_lo, V s_hi) {
  return _mm256_and_pd(_mm256_cmp_pd(m, s_lo, _CMP_GT_OQ), _mm256_cmp_pd(m, s_hi, _CMP_LT_OQ));
}

}  // namespace

[[gnu::target("avx2")]] unsigned torus_frames_avx2(const Torus& torus, const Vec3& o,
                                                   const Vec3 directions[4], const double t_max[4],
                                                   TorusFrame frames[4]) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  if (!is_finite(o)) return 0;
  const V dx = _mm256_setr_pd(directions[0].x, directions[1].x, directions[2].x, directions[3].x);
  const V dy = _mm256_setr_pd(directions[0].y, directions[1].y, directions[2].y, directions[3].y);
  const V dz = _mm256_setr_pd(directions[0].z, directions[1].z, directions[2].z, directions[3].z);
  const V limit = _mm256_loadu_pd(t_max);
  const V inf = splat(kInfinity);
  const V dd = add(add(mul(dx, dx), mul(dy, dy)), mul(dz, dz));
  // is_finite(d), dd > 0 and finite, t_max > 0.
  V formed = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(magnitude(dx), inf, _CMP_LT_OQ),
                                         _mm256_cmp_pd(magnitude(dy), inf, _CMP_LT_OQ)),
                           _mm256_cmp_pd(magnitude(dz), inf, _CMP_LT_OQ));
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(dd, _mm256_setzero_pd(), _CMP_GT_OQ));
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(dd, inf, _CMP_LT_OQ));
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(limit, _mm256_setzero_pd(), _CMP_GT_OQ));

  // padded_box_span.
  V t_enter = splat(-kInfinity), t_exit = inf;
  narrow_to_slab(o.x, dx, (big_r + r) * kTorusBoxPad, t_enter, t_exit, formed);
  narrow_to_slab(o.y, dy, (big_r + r) * kTorusBoxPad, t_enter, t_exit, formed);
  narrow_to_slab(o.z, dz, r * kTorusBoxPad, t_enter, t_exit, formed);
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(t_enter, t_exit, _CMP_LE_OQ));
  const V len = _mm256_sqrt_pd(dd);
  const V t_lo = std_max(t_enter, _mm256_setzero_pd()), t_hi = std_min(t_exit, limit);
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(t_lo, t_hi, _CMP_LT_OQ));

  // The frame.
  const V ux = divide(dx, len), uy = divide(dy, len), uz = divide(dz, len);
  const V ox = splat(o.x), oy = splat(o.y), oz = splat(o.z);
  const V t0 = divide(negate(add(add(mul(ox, dx), mul(oy, dy)), mul(oz, dz))), dd);
  const V fx = add(ox, mul(dx, t0)), fy = add(oy, mul(dy, t0)), fz = add(oz, mul(dz, t0));
  const V s_lo = mul(sub(t_lo, t0), len), s_hi = mul(sub(t_hi, t0), len);

  // The cylinders.
  const V P = add(mul(ux, ux), mul(uy, uy)), Q = add(mul(fx, ux), mul(fy, uy));
  const double pad2 = kTorusBoxPad * kTorusBoxPad;
  const double outer2 = (big_r + r) * (big_r + r) * pad2;
  const V s_nearest = select(_mm256_cmp_pd(P, _mm256_setzero_pd(), _CMP_GT_OQ),
                             std_clamp(divide(negate(Q), P), s_lo, s_hi), s_lo);
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(axis_distance2_lanes(fx, fy, ux, uy, s_nearest),
                                               splat(outer2), _CMP_NGT_UQ));
  if (big_r > r) {
    const V farthest = std_max(axis_distance2_lanes(fx, fy, ux, uy, s_lo),
                               axis_distance2_lanes(fx, fy, ux, uy, s_hi));
    formed = _mm256_and_pd(
        formed, _mm256_cmp_pd(farthest, splat((big_r - r) * (big_r - r) / pad2), _CMP_NLT_UQ));
  }

  // The ball.
  const V A = add(add(mul(ux, ux), mul(uy, uy)), mul(uz, uz));
  const V B = mul(splat(2.0), add(add(mul(fx, ux), mul(fy, uy)), mul(fz, uz)));
  const V f2 = add(add(mul(fx, fx), mul(fy, fy)), mul(fz, fz));
  const V s_c = std_clamp(_mm256_setzero_pd(), s_lo, s_hi);
  const V ball =
      sub(add(f2, mul(mul(A, s_c), s_c)), mul(magnitude(B), std_max(negate(s_lo), s_hi)));
  formed = _mm256_and_pd(formed, _mm256_cmp_pd(ball, splat(outer2), _CMP_NGT_UQ));
  const unsigned formed_lanes = static_cast<unsigned>(_mm256_movemask_pd(formed));
  if (formed_lanes == 0) return 0;

  // The quartic.
  const double big_r2 = big_r * big_r;
  const V C = sub(add(f2, splat(big_r2)), splat(r * r));
  const V rho = hypot_lanes(fx, fy);
  const V two_a = mul(splat(2.0), A);
  const V fz2 = mul(fz, fz);
  const V rho_minus = sub(rho, splat(big_r)), rho_plus = add(rho, splat(big_r));
  const V c[5] = {mul(sub(add(mul(rho_minus, rho_minus), fz2), splat(r * r)),
                      sub(add(mul(rho_plus, rho_plus), fz2), splat(r * r))),
                  sub(mul(mul(splat(2.0), B), C), mul(splat(8 * big_r2), Q)),
                  sub(add(mul(B, B), mul(two_a, C)), mul(splat(4 * big_r2), P)), mul(two_a, B),
                  mul(A, A)};

  // first_root_bracket (torus.cpp): from the span's start to where the ray crosses the torus's
  // plane, or failing that, first crosses its core cylinder (core_cylinder_root), when in the span.
  const V zero = _mm256_setzero_pd();
  V end = zero;
  const V plane = divide(negate(fz), uz);
  V bracketed = quartic_first_root_bracket_lanes(
      c, s_lo, plane,
      _mm256_and_pd(_mm256_and_pd(formed, _mm256_cmp_pd(uz, zero, _CMP_NEQ_UQ)),
                    in_span(plane, s_lo, s_hi)),
      end);
  const V rest = _mm256_andnot_pd(bracketed, formed);
  if (_mm256_movemask_pd(rest) != 0) {
    const V k = sub(add(mul(fx, fx), mul(fy, fy)), splat(big_r2));
    const V disc = sub(mul(Q, Q), mul(P, k));
    const V crosses =
        _mm256_and_pd(_mm256_cmp_pd(P, zero, _CMP_GT_OQ), _mm256_cmp_pd(disc, zero, _CMP_GE_OQ));
    const V root =
        select(crosses, _mm256_sqrt_pd(disc), splat(std::numeric_limits<double>::quiet_NaN()));
    const V cylinder = divide(sub(negate(Q), root), P);
    bracketed = _mm256_or_pd(
        bracketed, quartic_first_root_bracket_lanes(
                       c, s_lo, cylinder, _mm256_and_pd(rest, in_span(cylinder, s_lo, s_hi)), end));
  }
  const unsigned bracketed_lanes = static_cast<unsigned>(_mm256_movemask_pd(bracketed));
  const Lanes ends = lanes_of(end);

  const Lanes c0 = lanes_of(c[0]), c1 = lanes_of(c[1]), c2 = lanes_of(c[2]), c3 = lanes_of(c[3]),
              c4 = lanes_of(c[4]);
  const Lanes ux_ = lanes_of(ux), uy_ = lanes_of(uy), uz_ = lanes_of(uz);
  const Lanes fx_ = lanes_of(fx), fy_ = lanes_of(fy), fz_ = lanes_of(fz);
  const Lanes len_ = lanes_of(len), t0_ = lanes_of(t0), s_lo_ = lanes_of(s_lo),
              s_hi_ = lanes_of(s_hi), P_ = lanes_of(P), Q_ = lanes_of(Q);
  for (unsigned m = formed_lanes; m != 0; m &= m - 1) {
    const int l = std::countr_zero(m);
    TorusFrame& frame = frames[l];
    frame.line = {{ux_.v[l], uy_.v[l], uz_.v[l]},
                  {fx_.v[l], fy_.v[l], fz_.v[l]},
                  len_.v[l],
                  t0_.v[l],
                  s_lo_.v[l],
                  s_hi_.v[l],
                  P_.v[l],
                  Q_.v[l]};
    frame.quartic = Polynomial{{c0.v[l], c1.v[l], c2.v[l], c3.v[l], c4.v[l]}, 4};
    frame.first_root_end =
        (bracketed_lanes >> l) & 1u ? std::optional<double>(ends.v[l]) : std::nullopt;
  }
  return formed_lanes;
}

[[gnu::target("avx2")]] void torus_root_hits_avx2(const Torus& torus, const TorusFrame frames[4],
                                                  const TorusRoot roots[4], unsigned lanes,
                                                  LocalHit hits[4]) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  // Lanes outside `lanes` repeat the first one's (computed, not stored).
  const int first = std::countr_zero(lanes);
  const int i0 = lanes & 1u ? 0 : first, i1 = (lanes >> 1) & 1u ? 1 : first,
            i2 = (lanes >> 2) & 1u ? 2 : first, i3 = (lanes >> 3) & 1u ? 3 : first;
  const int index[4] = {i0, i1, i2, i3};
  const V ux = lanes_at(index, [&](int l) { return frames[l].line.u.x; });
  const V uy = lanes_at(index, [&](int l) { return frames[l].line.u.y; });
  const V uz = lanes_at(index, [&](int l) { return frames[l].line.u.z; });
  const V fx = lanes_at(index, [&](int l) { return frames[l].line.f.x; });
  const V fy = lanes_at(index, [&](int l) { return frames[l].line.f.y; });
  const V fz = lanes_at(index, [&](int l) { return frames[l].line.f.z; });
  const V s = lanes_at(index, [&](int l) { return roots[l].s; });
  // surface_hit at p = f + u s.
  const V px = add(fx, mul(ux, s)), py = add(fy, mul(uy, s)), pz = add(fz, mul(uz, s));
  const V rho = hypot_lanes(px, py);
  const V d_outer = hypot_lanes(sub(rho, splat(big_r)), pz);
  const V outer_gap = magnitude(sub(d_outer, splat(r)));
  const V inner_possible =
      _mm256_cmp_pd(sub(mul(add(rho, splat(big_r)), splat(1 - 8 * kMachineEpsilon)), splat(r)),
                    outer_gap, _CMP_NGT_UQ);
  V d_inner = _mm256_setzero_pd();
  if (_mm256_movemask_pd(inner_possible) != 0)
    d_inner = select(inner_possible, hypot_lanes(add(rho, splat(big_r)), pz), d_inner);
  const V inner = _mm256_and_pd(
      inner_possible, _mm256_cmp_pd(magnitude(sub(d_inner, splat(r))), outer_gap, _CMP_LT_OQ));
  const V d = select(inner, d_inner, d_outer);
  const V zero = _mm256_setzero_pd();
  // rho > 0 (so not NaN) and finite, d > 0.
  const V off_axis = _mm256_and_pd(
      _mm256_and_pd(_mm256_cmp_pd(rho, zero, _CMP_GT_OQ), _mm256_cmp_pd(d, zero, _CMP_GT_OQ)),
      _mm256_cmp_pd(rho, splat(kInfinity), _CMP_LT_OQ));
  const V cx = divide(px, rho), cy = divide(py, rho);
  const V a =
      mul(divide(select(inner, add(rho, splat(big_r)), sub(rho, splat(big_r))), d), splat(r));
  const V b = mul(divide(pz, d), splat(r));
  const V rho_on = add(select(inner, splat(-big_r), splat(big_r)), a);
  // hit_point_error.
  const double size2 = (big_r + r) * (big_r + r);
  const V band = divide(splat(16 * kMachineEpsilon * size2 * size2), mul(splat(big_r * r), rho));
  const V e = std_min(std_max(splat(off_axis_point_error(big_r, r)), band),
                      splat(on_axis_point_error(big_r, r)));
  const V sign_a = mul(select(inner, splat(-1.0), splat(1.0)), a);
  const V sign_b = mul(select(inner, splat(-1.0), splat(1.0)), b);
  const Lanes point_x = lanes_of(mul(rho_on, cx)), point_y = lanes_of(mul(rho_on, cy)),
              point_z = lanes_of(b), error = lanes_of(e), normal_x = lanes_of(mul(sign_a, cx)),
              normal_y = lanes_of(mul(sign_a, cy)), normal_z = lanes_of(sign_b);
  const unsigned on_axis = lanes & ~static_cast<unsigned>(_mm256_movemask_pd(off_axis));
  for (unsigned m = lanes & ~on_axis; m != 0; m &= m - 1) {
    const int l = std::countr_zero(m);
    LocalHit& hit = hits[l];
    hit.t = roots[l].t;
    hit.point = {point_x.v[l], point_y.v[l], point_z.v[l]};
    hit.point_error = {error.v[l], error.v[l], error.v[l]};
    hit.normal = {normal_x.v[l], normal_y.v[l], normal_z.v[l]};
    hit.shading_normal = hit.normal;
    hit.part = 0;
  }
  for (unsigned m = on_axis; m != 0; m &= m - 1) {
    const int l = std::countr_zero(m);
    hits[l] = torus_root_hit(torus, frames[l].line, roots[l]);
  }
}

unsigned intersect_torus_packet_avx2(const Torus& torus, const Vec3& origin,
                                     const Vec3 directions[4], unsigned lanes,
                                     const double t_max[4], LocalHit hits[4]) {
  TorusFrame frames[kTorusPacketLanes];
  TorusRoot roots[kTorusPacketLanes];
  unsigned hit_lanes = 0;
  for (unsigned m = torus_frames_avx2(torus, origin, directions, t_max, frames) & lanes; m != 0;
       m &= m - 1) {
    const int l = std::countr_zero(m);
    if (nearest_torus_root(torus, frames[l], t_max[l], roots[l])) hit_lanes |= 1u << l;
  }
  // The hits after all the searches, four lanes at once.
  if (hit_lanes != 0) torus_root_hits_avx2(torus, frames, roots, hit_lanes, hits);
  return hit_lanes;
}

#endif

}  // namespace tessera
