#include "common/scene/sky_gradient.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include "common/math/portable_math.h"

namespace tessera {
namespace {

// The colour at `angle` of `colours` given at 0 and at each of `angles`: linear between two
// of them, the last beyond the last angle.
Rgb along(const std::vector<double>& angles, const std::vector<Rgb>& colours, double angle) {
  for (std::size_t i = 0; i < angles.size(); ++i) {
    if (angle > angles[i]) continue;
    const double start = i == 0 ? 0 : angles[i - 1];
    const double f = angles[i] > start ? (angle - start) / (angles[i] - start) : 1;
    return colours[i] * (1 - f) + colours[i + 1] * f;
  }
  return colours.back();
}

}  // namespace

Rgb SkyGradient::colour(const Vec3& d) const {
  const double from_up = tessera::acos(std::clamp(dot(d, up), -1.0, 1.0));
  const double from_down = std::numbers::pi - from_up;
  if (!ground_angles.empty() && from_down <= ground_angles.back())
    return along(ground_angles, ground_colours, from_down);
  return along(sky_angles, sky_colours, from_up);
}

}  // namespace tessera
