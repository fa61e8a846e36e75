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

// Moves `p` by its surface's `offset` (surface_offset) to the side of the surface, with
// geometric normal `n`, that `direction` points into. The result is rounded away from the
// surface so that it is strictly on that side.
// Each component is built whole (not written into a Vec3 by index): the spawned ray is read back
// two components at a time, and a load that spans separately stored components waits for them
// to reach the cache (a store-forwarding stall, some 13 % of the lighting loop's time).
inline Vec3 offset_ray_origin_by(const Vec3& p, Vec3 offset, const Vec3& n, const Vec3& direction) {
  if (dot(direction, n) < 0) offset = -offset;
  const Vec3 po = p + offset;
  const auto away = [](double moved, double by) {
    return by > 0 ? next_up(moved) : (by < 0 ? next_down(moved) : moved);
  };
  return {away(po.x, offset.x), away(po.y, offset.y), away(po.z, offset.z)};
}

// Moves `p` (with per-component error bound `p_error`) off the surface with geometric normal
// `n`, to the side that `direction` points into: the two steps above at once.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& n,
                              const Vec3& direction, double min_offset = 0) {
  return offset_ray_origin_by(p, surface_offset(p_error, n, min_offset), n, direction);
}

}  // namespace tessera
