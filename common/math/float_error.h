// Floating-point error bounds and robust ray spawning (pbrt-v3 §3.9).
//
// Rays leaving a surface start from the hit point pushed along the geometric normal by a
// conservative bound on that point's rounding error, instead of by one fixed epsilon. The bound
// scales with the magnitude of the coordinates, so it works at 10^-4 and at 10^8 alike.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/math/vec3.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

inline constexpr double kMachineEpsilon = std::numeric_limits<double>::epsilon() * 0.5;

// gamma(n) bounds the relative error of n successive rounded operations.
constexpr double gamma_bound(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

// The next double above x (std::nextafter(x, +infinity)), and below it, without the library
// call: rays are spawned millions of times a second, three components each, and libm's
// nextafter cost 3 % of a render. The same value as std::nextafter for every input
// (tests/math/float_error_test.cpp): the bit pattern of a finite non-zero double, read as an
// integer, moves one step away from zero (or towards it) per representable value.
// Without a branch on the sign: one step is +1 for a positive pattern and -1 for a negative one
// (the sign bit, spread by the arithmetic shift, or 1), and x + 0 turns -0 into +0, whose
// successor is denorm_min (every other x, NaN included, is its own sum with +0).
inline double next_up(double x) {
  if (!(x < std::numeric_limits<double>::infinity())) return x;  // +infinity or NaN
  const auto bits = std::bit_cast<std::int64_t>(x + 0.0);
  return std::bit_cast<double>(bits + ((bits >> 63) | 1));
}
inline double next_down(double x) { return -next_up(-x); }

// How far rays leave a surface with geometric normal `n` at a point with per-component error
// bound `p_error`: n times the larger of that bound's extent along n and `min_offset` (SDL's
// epsilon keywords). The same for every ray leaving the point, whatever its direction, so that
// a hit's shadow feelers (one per light) take it once.
inline Vec3 surface_offset(const Vec3& p_error, const Vec3& n, double min_offset = 0) {
  return n * std::max(dot(abs(n), p_error), min_offset);
}

// `moved` one representable value further in the direction of `by`'s sign: next_up(moved) for
// by > 0, next_down(moved) for by < 0, and `moved` itself for a zero or NaN `by`; bit for bit
// (tests/math/float_error_test.cpp). Without a branch: the sign of a spawned ray's offset
// components changes from one hit and light to the next, and the branches on it were some 15 % of
// the lighting loop's mispredictions (callgrind's branch simulator). Down is up for the negated
// value (next_down(x) = -next_up(-x)), and a negation flips the sign bit, so one integer step
// serves both; a select on the bits keeps `moved` where next_up would (an infinite or NaN value)
// or where no step is asked for.
inline double step_away(double moved, double by) {
  const auto flip = static_cast<std::uint64_t>(by < 0) << 63;
  const double up = std::bit_cast<double>(std::bit_cast<std::uint64_t>(moved) ^ flip);
  const auto bits = std::bit_cast<std::int64_t>(up + 0.0);
  const auto stepped = std::bit_cast<std::uint64_t>(bits + ((bits >> 63) | 1)) ^ flip;
  const bool steps = (by > 0) | (by < 0);
  const bool finite_up = up < std::numeric_limits<double>::infinity();
  const std::uint64_t keep = -static_cast<std::uint64_t>(steps & finite_up);
  const auto same = std::bit_cast<std::uint64_t>(moved);
  return std::bit_cast<double>(same ^ ((same ^ stepped) & keep));
}

#if defined(__SSE2__)
// step_away on two lanes, in SSE2 registers: the result stays in the floating-point registers,
// so that offset_ray_origin_by stores x and y as one pair (below). The sign of up + 0 (never -0)
// is that of its bits for every lane the select keeps, so a compare gives the step's sign.
inline __m128d step_away(__m128d moved, __m128d by) {
  const __m128d zero = _mm_setzero_pd();
  const __m128d flip = _mm_and_pd(_mm_cmplt_pd(by, zero), _mm_set1_pd(-0.0));
  const __m128d up = _mm_xor_pd(moved, flip);
  const __m128d up0 = _mm_add_pd(up, zero);
  const __m128i step = _mm_or_si128(_mm_castpd_si128(_mm_cmplt_pd(up0, zero)), _mm_set1_epi64x(1));
  const __m128d stepped =
      _mm_xor_pd(_mm_castsi128_pd(_mm_add_epi64(_mm_castpd_si128(up0), step)), flip);
  const __m128d steps = _mm_or_pd(_mm_cmplt_pd(by, zero), _mm_cmpgt_pd(by, zero));
  const __m128d finite_up = _mm_cmplt_pd(up, _mm_set1_pd(std::numeric_limits<double>::infinity()));
  const __m128d keep = _mm_and_pd(steps, finite_up);
  return _mm_or_pd(_mm_and_pd(keep, stepped), _mm_andnot_pd(keep, moved));
}
#endif

// Moves `p` by its surface's `offset` (surface_offset) to the side of the surface, with
// geometric normal `n`, that `direction` points into. The result is rounded away from the
// surface so that it is strictly on that side.
// x and y are built as one pair, z whole (not written into a Vec3 by index): the spawned ray is
// read back two components at a time, and a load that spans separately stored components waits
// for them to reach the cache (a store-forwarding stall, some 13 % of the lighting loop's time).
inline Vec3 offset_ray_origin_by(const Vec3& p, Vec3 offset, const Vec3& n, const Vec3& direction) {
  if (dot(direction, n) < 0) offset = -offset;
  const Vec3 po = p + offset;
#if defined(__SSE2__)
  const __m128d xy = step_away(_mm_set_pd(po.y, po.x), _mm_set_pd(offset.y, offset.x));
  Vec3 moved;
  _mm_storeu_pd(&moved.x, xy);
  moved.z = step_away(po.z, offset.z);
  return moved;
#else
  return {step_away(po.x, offset.x), step_away(po.y, offset.y), step_away(po.z, offset.z)};
#endif
}

// Moves `p` (with per-component error bound `p_error`) off the surface with geometric normal
// `n`, to the side that `direction` points into: the two steps above at once.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& n,
                              const Vec3& direction, double min_offset = 0) {
  return offset_ray_origin_by(p, surface_offset(p_error, n, min_offset), n, direction);
}

}  // namespace tessera
