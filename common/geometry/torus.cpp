// Ray / torus intersection (shapes.h).
//
// The torus (x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) = 0 along a ray is a quartic in
// the ray parameter. Solving it naively loses every digit for a ray from far away: the
// coefficients then hold |o|^4 terms that cancel down to the torus' size. So:
//  - the quartic is formed in a frame moved to the point of the ray's line nearest the torus'
//    centre, with a unit direction, where every term is of the torus' size; the constant term
//    (the torus function at that point) is taken in its factored form
//    ((rho - R)^2 + z^2 - r^2) ((rho + R)^2 + z^2 - r^2), which does not cancel near the tube;
//  - its roots are isolated and polished by bracketing (common/math/polynomial.h) on the
//    ray's span through the bounding box, so grazing rays get a touching root rather than
//    nothing or garbage; a ray that needs only the nearest hit stops the search there. When the
//    quartic is shown to fall through one root from the span's start to a point inside the tube
//    (quartic_first_root.h), that root is the search's first, and it is polished in that bracket
//    without the search's critical points (the same root up to the rounding of the polish; every
//    query takes it so, and their answers agree);
//  - each hit is re-projected onto the nearest generating circle of its meridian plane (the
//    circle around +R, or around -R for the inner "lemon" of a spindle torus), whose normal is
//    the torus' gradient direction; points on the axis (the horn torus' pinch, the spindle's
//    cusps), where the gradient vanishes, keep the root's point and get a finite normal;
//  - a hit closer to the ray's origin than a few times its error bound is not reported, so a
//    ray leaving the surface from offset_ray_origin() cannot find it again at t ~ 0;
//  - a shadow ray (occluded_torus) needs no hit, only proof of one: a sign change of the
//    quartic between two split points of the root search whose whole span passes the tests a
//    hit would, so it gets the nearest-hit query's answer without the polish or re-projection;
//    and cheap proofs usually spare the search: of a miss (quartic_miss_proof.h), or of a sign
//    change between a point outside the tube and one inside it (quartic_crossing_proof.h). Most
//    shadow rays leaving the torus's own surface are shown clear before the quartic is even
//    formed, from either half of the tube (leaves_the_torus_for_good, torus.h), and most rays
//    from outside that it blocks are shown blocked so (crosses_into_the_tube, torus.h).
#include "common/geometry/torus.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "common/geometry/ordered_hits.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"
#include "common/math/hypot.h"
#include "common/math/polynomial.h"
#include "common/math/quartic_crossing_proof.h"
#include "common/math/quartic_first_root.h"
#include "common/math/quartic_miss_proof.h"

namespace tessera {

namespace {

// The ray's span [t_near, t_far] between the planes at -half and +half on one axis (o, d: the
// origin's and direction's components), narrowing [t_enter, t_exit]; false when the ray is
// parallel to the planes and outside them. The same divisions in the same order for each sign
// of d, without a branch on it.
[[gnu::always_inline]] inline bool narrow_to_slab(double o, double d, double half, double& t_enter,
                                                  double& t_exit) {
  if (d == 0) return std::fabs(o) <= half;
  const double near_plane = d < 0 ? half : -half;
  const double t_near = (near_plane - o) / d, t_far = (-near_plane - o) / d;
  t_enter = std::max(t_enter, t_near);
  t_exit = std::min(t_exit, t_far);
  return true;
}

// Entry and exit of the ray through the box [-e, e]^2 x [-h, h]; false when it misses.
[[gnu::always_inline]] inline bool box_span(const Vec3& o, const Vec3& d, double e, double h,
                                            double& t_enter, double& t_exit) {
  t_enter = -kInfinity, t_exit = kInfinity;
  return narrow_to_slab(o.x, d.x, e, t_enter, t_exit) &&
         narrow_to_slab(o.y, d.y, e, t_enter, t_exit) &&
         narrow_to_slab(o.z, d.z, h, t_enter, t_exit) && t_enter <= t_exit;
}

// The span through the torus's bounding box, padded (kTorusBoxPad) so that it certainly holds the
// rounded surface.
[[gnu::always_inline]] inline bool padded_box_span(const Torus& torus, const Vec3& o, const Vec3& d,
                                                   double& t_enter, double& t_exit) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  return box_span(o, d, (big_r + r) * kTorusBoxPad, r * kTorusBoxPad, t_enter, t_exit);
}

// The bound a hit off the axis reports, at distance rho from it: the point's own error, or, when
// larger, the width of the band about the surface where the quartic the search forms may vanish,
// so that a ray spawned from the hit (offset_ray_origin, beyond the bound) starts outside that
// band and cannot find its own surface again at t ~ 0. The quartic's values are rounded by some
// eps (R + r)^4, the size of its terms, which near the surface is a distance of that over the
// torus function's gradient, 8 R r rho: a thin tube's band is far wider than its point's error
// (r = 0.01 R: ten times; before branch thintorus one ray in a hundred leaving such a tube, one
// in five at r = 0.001 R, found its own hit again). K is measured, not derived: from exact
// surface points moved along the normal by up to 12 eps (R + r)^4 / (R r rho), rays leaving to
// that side (a third of them grazing) found the surface at t ~ 0 from up to 0.73 of it for
// r = 0.01 R, 0.44 for r = 0.1 R, 0.37 for r = 0.25 R and 0.33 for horn and spindle, but 1.6 for
// r = 0.003 R, 3.2 for 0.001 R and 5.2 for 0.0001 R (a million rays each). K = 16 is three
// times the largest; Torus.HitBoundCoversTheQuarticsRounding fails with K = 4. Never more than
// the on-axis bound, which the shadow rays' tests take as the largest: that caps it only for r
// under 4e-8 R, or nearer the axis than 4e-8 (R + r)^3 / (R r), where roots are that
// ill-conditioned anyway.
double hit_point_error(double big_r, double r, double rho) {
  constexpr double kRoundingBand = 16;
  const double size2 = (big_r + r) * (big_r + r);
  const double band = kRoundingBand * kMachineEpsilon * size2 * size2 / (big_r * r * rho);
  return std::min(std::max(off_axis_point_error(big_r, r), band), on_axis_point_error(big_r, r));
}

// The hit at point p (computed as o' + s u): re-projected onto the surface, with its error
// bound and the gradient's direction as normal.
LocalHit surface_hit(double big_r, double r, const Vec3& p, const Vec3& u) {
  LocalHit hit;
  hit.part = 0;
  const double rho = hypot_inline(p.x, p.y);
  const double d_outer = hypot_inline(rho - big_r, p.z);  // to the circle around +R
  // The circle around -R is nearer to the tube's surface only when |d_inner - r| is the smaller
  // of the two. d_inner >= rho + R (up to hypot's ulp, which the margin covers), so on most hits
  // (every one on a ring torus) rho + R - r alone shows that it is not, and its hypot is spared.
  const bool inner_possible =
      !((rho + big_r) * (1 - 8 * kMachineEpsilon) - r > std::fabs(d_outer - r));
  const double d_inner = inner_possible ? hypot_inline(rho + big_r, p.z) : 0;
  const bool inner = inner_possible && std::fabs(d_inner - r) < std::fabs(d_outer - r);
  const double d = inner ? d_inner : d_outer;
  if (rho > 0 && d > 0 && std::isfinite(rho)) {
    const double cx = p.x / rho, cy = p.y / rho;
    // Meridian-plane offset from the circle's centre, scaled to the tube radius.
    const double a = ((inner ? rho + big_r : rho - big_r) / d) * r;
    const double b = (p.z / d) * r;
    const double rho_on = (inner ? -big_r : big_r) + a;
    hit.point = {rho_on * cx, rho_on * cy, b};
    const double e = hit_point_error(big_r, r, rho);
    hit.point_error = {e, e, e};
    // The gradient of the torus function is f(-) grad f(+) on the outer circle, where
    // f(-) > 0, and f(+) grad f(-) on the inner one, where f(+) < 0: away from the +R centre,
    // towards the -R centre.
    const double sign = inner ? -1.0 : 1.0;
    hit.normal = {sign * a * cx, sign * a * cy, sign * b};
  } else {
    // On the axis: the horn torus' pinch or a spindle torus' cusp, where the gradient vanishes
    // and the root is a multiple one, resolved only to about the square root of the rounding.
    hit.point = p;
    const double e = on_axis_point_error(big_r, r);
    hit.point_error = {e, e, e};
    hit.normal = p.z != 0 ? Vec3{0, 0, p.z > 0 ? 1.0 : -1.0} : -u;
  }
  hit.shading_normal = hit.normal;
  return hit;
}

// leaves_the_torus_for_good (torus.h) for a ray leaving the tube's outer half. Why it finds
// nothing: with a = rho - R >= 0 (rho, the origin's distance from the
// axis) and n = o - c the origin's offset from the nearest point c = R (o.x, o.y, 0) / rho of the
// core circle, of length N = hypot(a, o.z), every point c' of the core circle has
// n . c' = (a / rho) (o.xy . c'.xy) <= a R, so every point x within r of it (the whole torus, for
// any r: ring, horn and spindle, the spindle's inner lemon too) has n . x <= a R + N r, while
// n . o = a rho + o.z^2 = a R + N^2. So the torus lies behind the plane through o normal to n, at
// least kappa = N - r from it, and a ray with n . d > 0 moves away from it: at distance x along
// the ray it is kappa + x cos(theta) from the plane, cos(theta) = n . d / (N |d|), so the exact
// ray never meets the torus when kappa >= 0.
//
// The search works on the quartic formed in rounded arithmetic, though, and on a ray leaving the
// surface (kappa within rounding of zero, of either sign) it may report a root near the start,
// which is a hit only beyond x_min = 4 |point error| (leaves_the_origin). The rounding of the
// quartic's values there is some eps (R + r)^4, the size of its terms, which near the surface is
// a distance of about that over the torus function's gradient, 8 R r rho. So the ray must be
// farther than K eps (R + r)^4 / (R r rho) from the plane at x_min, and it only moves away from
// there. K is measured, not derived (a bound assembled from the search's error terms, gamma(8) S
// for Horner's rule with S several (R + r)^4 plus the coefficients' rounding, is over ten times the
// values seen and would leave a third or more of these rays to the quartic): on 71 M rays leaving
// the outer half of tori with r / R from 0.001 to 3 (of 115 M leaving their surface), under random
// transforms, offset as spawned rays are, not offset, from just behind and from up to 8 error
// bounds either side of the surface, half of them grazing, intersect_torus found a hit at values
// of that ratio up to 1.02 (r = 0.01 R) and 0.74 for the others; on 1.75 G such exits, 1.25
// (r = 0.005 R; 18 hits above 1 on half of them). K = 8 leaves room for over six times that, and
// for the rounding of the test's own terms (under a quarter of K);
// Torus.ExitProofNeverContradictsTheSearch fails with K = 0.5.
[[gnu::always_inline]] inline bool leaves_outer_half_for_good(const Torus& torus, const Vec3& o,
                                                              const Vec3& d, double len,
                                                              double rho) {
  constexpr double kRoundingMargin = 8;
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const double a = rho - big_r;
  // Beyond rho's rounding (under 2 eps rho): the exact a is positive too. NaN and overflow fail.
  if (!(a > 4 * kMachineEpsilon * rho)) return false;
  const double rho_n_dot_d = a * (o.x * d.x + o.y * d.y) + rho * o.z * d.z;
  if (!(rho_n_dot_d > 0)) return false;
  // x_min, rounded down (4 sqrt(3) = 6.93).
  const double x_min = 6.9 * off_axis_point_error(big_r, r);
  const double size2 = (big_r + r) * (big_r + r);
  // R r rho N (kappa + x_min cos(theta)) > K eps (R + r)^4 N, without N's square root:
  // N (N - r) >= (N^2 - r^2) / 2 and N <= (N^2 + r^2) / (2 r), so this, multiplied by 2 r |d|,
  // implies it.
  const double n2 = a * a + o.z * o.z;
  return big_r * r * r * (rho * (n2 - r * r) * len + 2 * x_min * rho_n_dot_d) >
         kRoundingMargin * kMachineEpsilon * size2 * size2 * (n2 + r * r) * len;
}

// leaves_the_torus_for_good for a ray leaving the tube's inner half (rho < R) away from the
// torus's plane. Why it finds nothing: the torus lies in the slab |z| <= r and outside the hole
// rho < R - w(z), w(z) = sqrt(r^2 - z^2) (ring, horn and spindle alike: the spindle's lemon has
// rho = w - R >= R - w). A ray with o.z and d.z of one sign and |o.z| < r leaves the slab for good
// at t_e = (r - |o.z|) / |d.z|. Over [0, t_e] its rho(t) is convex, so below its chord
// rho + c t, c = (rho(t_e) - rho) / t_e, and R - w(z(t)) is convex too (w concave, z linear in
// t), so above its tangent R - w0 + g t, g = |o.z| |d.z| / w0: their difference
// L(t) = (R - w0 - rho) + (g - c) t is a lower bound on the ray's horizontal gap to the tube.
// When it rises (g > c) and is positive at a distance x along the ray, the exact ray meets the
// torus nowhere beyond x (beyond t_e, should x lie there, it is out of the slab).
//
// Rounding as for the outer half: at x_min the gap must exceed K eps (R + r)^4 / (R rho w0), the
// outer half's margin on the distance to the surface turned into a horizontal gap (times r / w0,
// the tube's slope there). K is measured the same way, not derived: on 1.75 G rays leaving
// seventeen tori (r / R from 0.001 to 3, the same generator with 60 seeds), 132 M left the inner
// half with L rising; intersect_torus found a hit at values of that ratio up to 1.11 (r = 0.01 R;
// 0.72 for r >= 0.1 R), and such hits thin out fast towards it: of half of those rays, 12,601
// hits above 0.3, 615 above 0.6, 34 above 0.8, one above 1. K = 4 leaves room for 3.6 times the
// largest; Torus.ExitProofNeverContradictsTheSearch fails with K = 0.5.
[[gnu::always_inline]] inline bool leaves_inner_half_for_good(const Torus& torus, const Vec3& o,
                                                              const Vec3& d, double len,
                                                              double rho) {
  constexpr double kRoundingMargin = 4;
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const double z = std::fabs(o.z), h = r - z;
  // A ray from the outer half that its own test leaves would need L to rise by a whole tube width
  // by x_min: not tried. NaN fails.
  if (!(o.z * d.z > 0 && h > 0 && rho < big_r)) return false;
  const double w0 = std::sqrt(h * (r + z));
  const double t_e = h / std::fabs(d.z);
  const double x_e = o.x + d.x * t_e, y_e = o.y + d.y * t_e;
  // (g - c) w0 t_e.
  const double rise = z * h - (std::sqrt(x_e * x_e + y_e * y_e) - rho) * w0;
  if (!(rise > 0)) return false;
  const double x_min = 6.9 * off_axis_point_error(big_r, r);
  const double size2 = (big_r + r) * (big_r + r);
  // L(x_min / |d|) > K eps (R + r)^4 / (R rho w0), multiplied by R rho w0 t_e |d|.
  return big_r * rho * ((big_r - w0 - rho) * w0 * t_e * len + rise * x_min) >
         kRoundingMargin * kMachineEpsilon * size2 * size2 * t_e * len;
}

// leaves_the_torus_for_good, inline in the shadow rays' query.
[[gnu::always_inline]] inline bool leaves_for_good(const Torus& torus, const Vec3& o, const Vec3& d,
                                                   double len) {
  const double rho = std::sqrt(o.x * o.x + o.y * o.y);
  return leaves_outer_half_for_good(torus, o, d, len, rho) ||
         leaves_inner_half_for_good(torus, o, d, len, rho);
}

// The torus function at p, in its factored form (as the quartic's constant term).
double factored_torus_function(double big_r, double r, const Vec3& p) {
  const double rho = std::sqrt(p.x * p.x + p.y * p.y);
  return ((rho - big_r) * (rho - big_r) + p.z * p.z - r * r) *
         ((rho + big_r) * (rho + big_r) + p.z * p.z - r * r);
}

// crosses_into_the_tube (torus.h), the ray entering the padded box at t_enter. The search would
// report a root of the quartic it forms between a point where that quartic is above the crossing
// proof's bound and a later one where it is below minus it (quartic_crossing_proof.h: 139 eps S
// suffices, S = sum |c_i| m^i); here those are the box entry and a later point of the ray (where
// it crosses the torus's plane or, failing that, a point nearer the core circle), where the torus
// function must be that far from zero, with room for the difference between the two.
// The rounding margin is derived, not measured: over the padded box (half diagonal under
// sqrt(3) (R + r)) S is under 125 (R + r)^4, so the proof's bound is under 17,400 eps (R + r)^4;
// the rounding of the quartic's coefficients adds under 1,300 eps (R + r)^4, that of the torus
// function's value here under 500; the frame's line and the points computed here lie within
// 8 eps (|o| + |d| t + R + r) of the ray's, where the torus function's gradient is under
// 48 (R + r)^3. Under 20,000 eps (R + r)^3 (R + r + |o|_1 + |d|_1 t) in all, whatever the point
// of the ray, which K = 2^15 covers 1.6 times; Torus.EntryProofNeverContradictsTheSearch fails
// with K = 0.25 (and passes with 1: the bound is pessimistic).
[[gnu::always_inline]] inline bool crosses_into_tube(const Torus& torus, const Vec3& o,
                                                     const Vec3& d, double len, double t_enter,
                                                     double t_max) {
  constexpr double kRoundingMargin = 32768;
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  // The search's root lies after the box entry; it is a hit only beyond 4 sqrt(3) times the
  // largest point error from the origin (is_hit_bracket in visit_torus_hits), with room for t's
  // rounding.
  const double e = std::max(off_axis_point_error(big_r, r), on_axis_point_error(big_r, r));
  if (!(t_enter * len > 6.93 * e * (1 + 0x1p-10))) return false;
  const double size = big_r + r;
  // Far from underflow and overflow, where the relative bounds hold (and not NaN).
  if (!(size > 1e-25 && size < 1e25)) return false;
  const double o_size = std::fabs(o.x) + std::fabs(o.y) + std::fabs(o.z);
  const double d_size = std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z);
  const auto margin_at = [&](double t) {
    return kRoundingMargin * kMachineEpsilon * size * size * size * (size + o_size + d_size * t);
  };
  // Where the ray crosses the torus's plane: clearly inside the tube there, before t_max with room
  // for the root's t's rounding. (Trying where it crosses the core cylinder rho = R too settles
  // 5 % more of these rays, for more than they save.)
  if (d.z == 0) return false;
  const auto clearly_inside_at = [&](double t, double torus_function) {
    return t > t_enter && t * (1 + 0x1p-20) < t_max && torus_function < -margin_at(t);
  };
  const double t_plane = -o.z / d.z;
  const double x = o.x + d.x * t_plane, y = o.y + d.y * t_plane, rho2 = x * x + y * y;
  const double rho = std::sqrt(rho2), a = rho - big_r;
  if (!clearly_inside_at(t_plane, (a * a - r * r) * ((rho + big_r) * (rho + big_r) - r * r))) {
    // Failing that (a ray clipping the tube above or below the plane), nearer the core circle:
    // one Gauss-Newton step from the plane crossing towards the ray's nearest approach to it,
    // minimizing (rho - R)^2 + z^2 with rho linearized there (its rate k / rho). Any point of the
    // ray serves the proof; this one settles nine in ten of the blocked rays that the plane leaves
    // to the quartic (features/torus.sdl). Not tried when that linearized distance's least value,
    // a^2 d.z^2 / ((k / rho)^2 + d.z^2), is at least r^2: the step would seldom land in the tube
    // (on that scene it turns away three in four of these rays and loses one settled in a hundred).
    const double k = x * d.x + y * d.y, dz2 = d.z * d.z;
    if (!(a * a * dz2 * rho2 < r * r * (k * k + dz2 * rho2))) return false;
    const double rho_rate = k / rho;
    const double t = t_plane - a * rho_rate / (rho_rate * rho_rate + dz2);
    if (!clearly_inside_at(t, factored_torus_function(big_r, r, o + d * t))) return false;
  }
  // And clearly outside it where the ray enters the box, where the search starts.
  return factored_torus_function(big_r, r, o + d * t_enter) > margin_at(t_enter);
}

// The square root of the discriminant of P s^2 + 2 Q s + (f.x^2 + f.y^2 - R^2) = 0, whose roots
// (-Q -+ root) / P are where the ray (f + s u) crosses the torus' core cylinder rho = R; NaN when
// it does not.
double core_cylinder_root(const Vec3& f, double big_r, double P, double Q) {
  const double k = f.x * f.x + f.y * f.y - big_r * big_r, disc = Q * Q - P * k;
  return P > 0 && disc >= 0 ? std::sqrt(disc) : std::numeric_limits<double>::quiet_NaN();
}

// The end of a bracket [s_lo, end] of the search's first root, when quartic_first_root.h shows
// one for the stretch from the span's start to where the ray crosses the torus' plane or, failing
// that, first crosses its core cylinder: for a ray that enters the tube from outside, usually
// points deep inside it.
std::optional<double> first_root_bracket(const Polynomial& quartic, double s_lo, double s_hi,
                                         const Vec3& f, const Vec3& u, double big_r, double P,
                                         double Q) {
  const auto bracket_to = [&](double m) {
    return m > s_lo && m < s_hi ? quartic_first_root_bracket(quartic, s_lo, m) : std::nullopt;
  };
  if (u.z != 0)
    if (const std::optional<double> end = bracket_to(-f.z / u.z)) return end;
  // A NaN crossing is not in the span.
  return bracket_to((-Q - core_cylinder_root(f, big_r, P, Q)) / P);
}

// Whether a shadow ray is shown blocked without the search (quartic_crossing_proof.h): the
// quartic clearly changes sign between two points a < b of its span whose stretch, widened by the
// proof's slack, passes the tests of a hit (stretch_is_hit), so that the search would report a
// hit there if it had not at an earlier root. For a ray from outside (from_outside: the quartic
// clearly positive at the span's start), the points tried for the inside of the tube are where the
// ray crosses the torus' plane and its core cylinder (rho = R), usually deep in the tube, then the
// span's quarter points; for a ray leaving the surface (its start within rounding of zero), most
// often into the tube and out of its far side, the quarter points in order.
template <class StretchIsHit>
bool proven_blocked(const QuarticSignProof& signs, bool from_outside, double s_lo, double s_hi,
                    const Vec3& f, const Vec3& u, double big_r, double P, double Q,
                    const StretchIsHit& stretch_is_hit) {
  // No root lies before s_lo: the slack is not needed there.
  const auto crossing_hits = [&](double a, double b) {
    return stretch_is_hit(std::max(a - signs.slack(), s_lo), b + signs.slack());
  };
  const double w = (s_hi - s_lo) / 4;
  const double quarter_points[3] = {s_lo + w, s_lo + 2 * w, s_lo + 3 * w};
  if (from_outside) {
    const auto inside_at = [&](double s) {
      return s > s_lo && s < s_hi && signs.clearly_negative(s) && crossing_hits(s_lo, s);
    };
    if (u.z != 0 && inside_at(-f.z / u.z)) return true;
    const double root = core_cylinder_root(f, big_r, P, Q);
    if (inside_at((-Q - root) / P) || inside_at((-Q + root) / P)) return true;
    return inside_at(quarter_points[0]) || inside_at(quarter_points[1]) ||
           inside_at(quarter_points[2]);
  }
  // The first quarter point with a clear sign, and a later one with the other.
  int first_sign = 0;
  double first = 0;
  for (const double s : quarter_points) {
    const int sign = signs.clearly_positive(s) ? 1 : signs.clearly_negative(s) ? -1 : 0;
    if (first_sign == 0) {
      first_sign = sign;
      first = s;
    } else if (sign == -first_sign) {
      return crossing_hits(first, s);
    }
  }
  return false;
}

// What a search for the ray's hits is for: every hit, in order (the nearest hit is the first);
// or only whether there is one, which a sign change of the quartic between two split points of
// the root search well inside the accepted span shows without polishing the root or
// re-projecting it.
enum class HitSearch { kInOrder, kAnyHit };

// What form_line found: the ray misses, is blocked (kAnyHit), or its quartic is to be formed.
enum class FrameAnswer { kMiss, kBlocked, kFormed };

// The ray's line in the quartic's frame (TorusLine), unless it is shown to miss or (kAnyHit) to
// be blocked before the quartic is formed. torus_frames_avx2 (torus_packet.cpp) takes the kInOrder
// steps for four rays at once. Kept apart from the quartic, which the root search takes by
// reference, so that the line's values stay in registers.
[[gnu::always_inline]] inline FrameAnswer form_line(const Torus& torus, const Vec3& o,
                                                    const Vec3& d, double t_max, HitSearch search,
                                                    TorusLine& line) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const double dd = dot(d, d);
  // A finite positive |d|^2 shows d finite (an infinite or NaN component makes the sum of squares
  // infinite or NaN), so d's components are not tested one by one.
  if (!is_finite(o) || !(dd > 0) || !std::isfinite(dd) || !(t_max > 0)) return FrameAnswer::kMiss;

  // |d|, which the shadow rays' exit proofs need before the box; the other queries take it after
  // the box, which a sixth of their calls miss (features/torus.sdl).
  double len = search == HitSearch::kAnyHit ? std::sqrt(dd) : 0;
  // Most shadow rays that form the quartic leave the torus's own surface, outwards, only for the
  // miss proof to show it root-free; shown here before the box, which they all pass.
  if (search == HitSearch::kAnyHit && leaves_for_good(torus, o, d, len)) return FrameAnswer::kMiss;

  double t_enter = 0, t_exit = 0;
  if (!padded_box_span(torus, o, d, t_enter, t_exit)) return FrameAnswer::kMiss;
  if (search != HitSearch::kAnyHit) len = std::sqrt(dd);
  const double t_lo = std::max(t_enter, 0.0), t_hi = std::min(t_exit, t_max);
  if (!(t_lo < t_hi)) return FrameAnswer::kMiss;
  // Most shadow rays from outside the box that form the quartic are blocked, the ray crossing the
  // torus's plane deep inside the tube or clipping it near the core circle: shown from the
  // geometry, without the quartic.
  if (search == HitSearch::kAnyHit && crosses_into_tube(torus, o, d, len, t_enter, t_max))
    return FrameAnswer::kBlocked;

  // The frame: origin at the line's point nearest the centre, unit direction; s = (t - t0) |d|.
  const Vec3 u = d / len;
  const double t0 = -dot(o, d) / dd;
  const Vec3 f = o + d * t0;

  const double s_lo = (t_lo - t0) * len, s_hi = (t_hi - t0) * len;

  // The tube lies between the cylinders of radius R - r and R + r about the axis. A ray that
  // stays outside the outer one, or (ring tori) inside the inner one, over its span through
  // the box misses; the squared distance from the axis is convex along the ray, so its least
  // value over the span is at the clamped vertex and its greatest at an end.
  const double P = u.x * u.x + u.y * u.y, Q = f.x * u.x + f.y * u.y;
  const auto axis_distance2 = [&](double s) {
    const double x = f.x + u.x * s, y = f.y + u.y * s;
    return x * x + y * y;
  };
  const double pad2 = kTorusBoxPad * kTorusBoxPad;
  const double s_nearest = P > 0 ? std::clamp(-Q / P, s_lo, s_hi) : s_lo;
  if (axis_distance2(s_nearest) > (big_r + r) * (big_r + r) * pad2) return FrameAnswer::kMiss;
  if (big_r > r &&
      std::max(axis_distance2(s_lo), axis_distance2(s_hi)) < (big_r - r) * (big_r - r) / pad2)
    return FrameAnswer::kMiss;

  // A, B as in the quartic (line_quartic).
  const double A = dot(u, u), B = 2 * dot(f, u), f2 = dot(f, f);
  // The torus also lies in the ball of radius R + r about its centre: F >= (|p|^2 - (R + r)^2)
  // (|p|^2 - (R - r)^2), since rho <= |p|, so a ray that stays outside it, padded as the
  // cylinders are, misses. |f + s u|^2 = A s^2 + B s + |f|^2 has its vertex at s ~ 0 (B is
  // rounding), so over the span it is at least |f|^2 + A s_c^2 - |B| max |s|, s_c the span's
  // point nearest 0. It turns away half the camera rays that the cylinders leave and that miss
  // (features/torus.sdl), by the box's corners; shadow rays, mostly leaving the torus, not.
  if (search == HitSearch::kInOrder) {
    const double s_c = std::clamp(0.0, s_lo, s_hi);
    if (f2 + A * s_c * s_c - std::fabs(B) * std::max(-s_lo, s_hi) >
        (big_r + r) * (big_r + r) * pad2)
      return FrameAnswer::kMiss;
  }
  line = {u, f, len, t0, s_lo, s_hi, P, Q};
  return FrameAnswer::kFormed;
}

// F(f + s u) = (A s^2 + B s + C)^2 - 4 R^2 (P s^2 + 2 Q s + S), the ray's quartic in s. A, B and
// C as form_line computes them (where the compiler shares them).
[[gnu::always_inline]] inline Polynomial line_quartic(const Torus& torus, const TorusLine& line) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const Vec3 u = line.u, f = line.f;
  const double P = line.P, Q = line.Q;
  const double big_r2 = big_r * big_r;
  const double A = dot(u, u), B = 2 * dot(f, u), f2 = dot(f, f), C = f2 + big_r2 - r * r;
  const double rho = hypot_inline(f.x, f.y);
  Polynomial quartic;
  quartic.degree = 4;
  quartic.c[4] = A * A;
  quartic.c[3] = 2 * A * B;
  quartic.c[2] = B * B + 2 * A * C - 4 * big_r2 * P;
  quartic.c[1] = 2 * B * C - 8 * big_r2 * Q;
  quartic.c[0] = ((rho - big_r) * (rho - big_r) + f.z * f.z - r * r) *
                 ((rho + big_r) * (rho + big_r) + f.z * f.z - r * r);
  return quartic;
}

// Whether a hit at t with error bound point_error lies beyond a few error bounds of the line's
// origin: else it is the surface the ray is leaving.
[[gnu::always_inline]] inline bool leaves_the_origin(const TorusLine& line, double t,
                                                     const Vec3& point_error) {
  return t * line.len > 4 * length(point_error);
}

// The hit at the root s of the line's quartic, at t: re-projected onto the surface, or nullopt
// when it is the surface the ray is leaving.
[[gnu::always_inline]] inline std::optional<LocalHit> reprojected_hit(const Torus& torus,
                                                                      const TorusLine& line,
                                                                      double s, double t) {
  LocalHit hit = surface_hit(torus.torus_radius, torus.tube_radius, line.f + line.u * s, line.u);
  if (!leaves_the_origin(line, t, hit.point_error)) return std::nullopt;
  hit.t = t;
  return hit;
}

// The roots of the frame's quartic with t in (0, t_max), ascending, as in visit_torus_hits, each
// handed to take as reproject(s, t) makes it (reprojected_hit, or the packet path's TorusRoot);
// a root it answers with nullopt is not a hit. known_end, when not null, is first_root_bracket's
// answer for the frame, already found (the packet path's); else it is found here when the search
// needs it.
template <class Reproject, class Take>
[[gnu::always_inline]] inline bool visit_frame_hits(const Torus& torus, const TorusLine& line,
                                                    const Polynomial& quartic, double t_max,
                                                    HitSearch search,
                                                    const std::optional<double>* known_end,
                                                    const Reproject& reproject, const Take& take) {
  const double big_r = torus.torus_radius, r = torus.tube_radius;
  const Vec3 u = line.u, f = line.f;
  const double len = line.len, t0 = line.t0, s_lo = line.s_lo, s_hi = line.s_hi;
  const double P = line.P, Q = line.Q;
  const auto t_at = [&](double s) { return t0 + s / len; };
  // The hit at the root s, or nullopt when it is not one: outside (0, t_max), or as reproject
  // answers.
  const auto hit_at = [&](double s) -> decltype(reproject(s, s)) {
    const double t = t_at(s);
    if (!(t > 0 && t < t_max)) return std::nullopt;
    return reproject(s, t);
  };
  // Most rays that form the quartic and hit enter the tube from outside, where the search's first
  // root is usually bracketed without its critical points (first_root_bracket) and polished in
  // that bracket: the search's root up to the rounding of the polish. Every query takes the first
  // root this way when it can, so that the nearest hit, the crossings and the shadow rays' answer
  // come from the same arithmetic; the search then passes over its own first root. Returns false
  // when take ended the search there.
  bool first_root_taken = false;
  const auto take_bracketed_first_root = [&] {
    const std::optional<double> end =
        known_end ? *known_end : first_root_bracket(quartic, s_lo, s_hi, f, u, big_r, P, Q);
    if (!end) return true;
    const auto hit = hit_at(polished_root(quartic, s_lo, *end));
    if (!hit) return true;  // to the search, which may take its own polish of the root
    first_root_taken = true;
    return take(*hit, false);
  };
  const auto at_root = [&](const PolynomialRoot& root) {
    if (std::exchange(first_root_taken, false)) return true;
    const auto hit = hit_at(root.x);
    return !hit || take(*hit, root.touching);
  };
  if (search == HitSearch::kInOrder) {
    if (!take_bracketed_first_root()) return false;
    return visit_real_roots(quartic, s_lo, s_hi, at_root);
  }

  // The root polished in [a, b] would have t in [t_at(a), t_at(b)], every rounded operation
  // being monotone, and an error bound no larger than the larger of surface_hit's: when both
  // ends pass at_root's tests, so does the root. Otherwise the root is polished and tested.
  const double e = std::max(off_axis_point_error(big_r, r), on_axis_point_error(big_r, r));
  const Vec3 largest_point_error{e, e, e};
  const auto is_hit_bracket = [&](double a, double b) {
    const double t_a = t_at(a);
    return t_a > 0 && t_at(b) < t_max && leaves_the_origin(line, t_a, largest_point_error);
  };

  // Shown here when it is easy, each for less than half the cost of the search: a miss (with its
  // answer; not for the nearest hit: most of those rays hit, and the proof's cost outweighed the
  // searches it spared), or a hit, where the search would compute critical points up to the
  // first sign change to say so. Which is tried first depends on where the ray starts: most rays
  // from outside the tube that form the quartic are blocked (on features/torus.sdl, the floor's
  // rays in a torus's shadow: three in four are shown so), and for a ray starting on its surface,
  // within rounding of it, the miss proof first costs less, its failures being the cheaper.
  const QuarticSignProof signs(quartic, s_lo, s_hi);
  const bool from_outside = signs.clearly_positive(s_lo);
  if (!from_outside && quartic_proven_root_free(quartic, s_lo, s_hi)) return true;
  if (proven_blocked(signs, from_outside, s_lo, s_hi, f, u, big_r, P, Q, is_hit_bracket))
    return false;
  if (from_outside && quartic_proven_root_free(quartic, s_lo, s_hi)) return true;

  if (!take_bracketed_first_root()) return false;
  return visit_real_roots(quartic, s_lo, s_hi, at_root, is_hit_bracket);
}

// The roots of the ray's quartic with t in (0, t_max), ascending, as hits handed to
// take(hit, touching) until it returns false: the search stops there, so a caller that needs
// only the first hit pays only for it. Returns false when the search was ended: by take, or
// (kAnyHit) at a root proven to be a hit that take was not given.
template <class Take>
[[gnu::always_inline]] inline bool visit_torus_hits(const Torus& torus, const Ray& ray,
                                                    double t_max, HitSearch search,
                                                    const Take& take) {
  TorusLine line;
  switch (form_line(torus, ray.origin, ray.direction, t_max, search, line)) {
    case FrameAnswer::kMiss:
      return true;
    case FrameAnswer::kBlocked:
      return false;
    case FrameAnswer::kFormed:
      break;
  }
  return visit_frame_hits(
      torus, line, line_quartic(torus, line), t_max, search, nullptr,
      [&](double s, double t) { return reprojected_hit(torus, line, s, t); }, take);
}

}  // namespace

bool leaves_the_torus_for_good(const Torus& torus, const Ray& ray) {
  return leaves_for_good(torus, ray.origin, ray.direction, length(ray.direction));
}

bool torus_frame(const Torus& torus, const Vec3& origin, const Vec3& direction, double t_max,
                 TorusFrame& frame) {
  if (form_line(torus, origin, direction, t_max, HitSearch::kInOrder, frame.line) !=
      FrameAnswer::kFormed)
    return false;
  frame.quartic = line_quartic(torus, frame.line);
  const TorusLine& line = frame.line;
  frame.first_root_end = first_root_bracket(frame.quartic, line.s_lo, line.s_hi, line.f, line.u,
                                            torus.torus_radius, line.P, line.Q);
  return true;
}

bool nearest_torus_root(const Torus& torus, const TorusFrame& frame, double t_max,
                        TorusRoot& root) {
  const TorusLine& line = frame.line;
  // A root this far from the origin is taken without its re-projection: hit_point_error is at
  // most the larger of the two bounds, and every rounded operation of leaves_the_origin being
  // monotone, its hit leaves the origin whatever its own bound. Nearer ones are re-projected here
  // to be tested (and again by torus_root_hit).
  const double e = std::max(off_axis_point_error(torus.torus_radius, torus.tube_radius),
                            on_axis_point_error(torus.torus_radius, torus.tube_radius));
  const Vec3 largest_point_error{e, e, e};
  bool found = false;
  visit_frame_hits(
      torus, line, frame.quartic, t_max, HitSearch::kInOrder, &frame.first_root_end,
      [&](double s, double t) -> std::optional<TorusRoot> {
        if (!leaves_the_origin(line, t, largest_point_error) && !reprojected_hit(torus, line, s, t))
          return std::nullopt;
        return TorusRoot{s, t};
      },
      [&](const TorusRoot& nearest, bool) {
        root = nearest;
        found = true;
        return false;
      });
  return found;
}

LocalHit torus_root_hit(const Torus& torus, const TorusLine& line, const TorusRoot& root) {
  LocalHit hit =
      surface_hit(torus.torus_radius, torus.tube_radius, line.f + line.u * root.s, line.u);
  hit.t = root.t;
  return hit;
}

bool nearest_torus_hit(const Torus& torus, const TorusFrame& frame, double t_max, LocalHit& hit) {
  TorusRoot root;
  if (!nearest_torus_root(torus, frame, t_max, root)) return false;
  hit = torus_root_hit(torus, frame.line, root);
  return true;
}

bool intersect_torus(const Torus& torus, const Ray& ray, double t_max, LocalHit& hit) {
  return nearest_ordered_hit(
      [&](const auto& take) { visit_torus_hits(torus, ray, t_max, HitSearch::kInOrder, take); },
      hit);
}

bool crosses_into_the_tube(const Torus& torus, const Ray& ray, double t_max) {
  double t_enter = 0, t_exit = 0;
  return is_finite(ray.origin) && is_finite(ray.direction) &&
         padded_box_span(torus, ray.origin, ray.direction, t_enter, t_exit) &&
         crosses_into_tube(torus, ray.origin, ray.direction, length(ray.direction), t_enter, t_max);
}

bool occluded_torus(const Torus& torus, const Ray& ray, double t_max) {
  const auto any_hit_ends_the_search = [](const LocalHit&, bool) { return false; };
  return !visit_torus_hits(torus, ray, t_max, HitSearch::kAnyHit, any_hit_ends_the_search);
}

std::vector<LocalHit> torus_crossings(const Torus& torus, const Ray& ray, double t_max) {
  return ordered_crossings(
      [&](const auto& take) { visit_torus_hits(torus, ray, t_max, HitSearch::kInOrder, take); });
}

}  // namespace tessera
