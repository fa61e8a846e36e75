#include <cmath>
#include <numbers>

#include "common/render/prepared_scene.h"

namespace tessera {

Ray CameraFrame::ray_through(double px, double py, int width, int height) const {
  const double aspect = static_cast<double>(width) / height;
  double tan_half = tan_half_height;
  if (angle_on_smaller_side && width < height) tan_half *= static_cast<double>(height) / width;
  const double sx = (2 * px / width - 1) * aspect * tan_half;
  const double sy = (1 - 2 * py / height) * tan_half;
  const Vec3 d = forward + right * sx + up * sy;
  return Ray{eye, d / length(d), 0};
}

}  // namespace tessera
