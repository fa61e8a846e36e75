// Floating-point error bounds and robust ray spawning (pbrt-v3 §3.9).
//
// Rays leaving a surface start from the hit point pushed along the geometric normal by a
// conservative bound on that point's rounding error, instead of by one fixed epsilon. The bound
// scales with the magnitude of the coordinates, so it works at 10^-4 and at 10^8 alike.
#pragma once

#include <cmath>
#include <limits>

#include "common/math/vec3.h"

namespace tessera {

inline constexpr double kMachineEpsilon = std::numeric_limits<double>::epsilon() * 0.5;

// gamma(n) bounds the relative error of n successive rounded operations.
constexpr double gamma_bound(int n) { return (n * kMachineEpsilon) / (1 - n * kMachineEpsilon); }

// Moves `p` (with per-component error bound `p_error`) off the surface with geometric normal
// `n`, to the side that `direction` points into. The result is rounded away from the surface
// so that it is strictly on that side. `min_offset` is a lower bound on the offset distance
// (SDL's epsilon keywords).
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& n,
                              const Vec3& direction, double min_offset = 0) {
  const double d = std::max(dot(abs(n), p_error), min_offset);
  Vec3 offset = n * d;
  if (dot(direction, n) < 0) offset = -offset;
  Vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0)
      po[i] = std::nextafter(po[i], std::numeric_limits<double>::infinity());
    else if (offset[i] < 0)
      po[i] = std::nextafter(po[i], -std::numeric_limits<double>::infinity());
  }
  return po;
}

}  // namespace tessera
