#include <cmath>
#include <numbers>

#include "common/render/prepared_scene.h"

namespace tessera {

Ray CameraFrame::ray_through(double px, double py, int width, int height) const {
  return ImageRays(*this, width, height).through(px, py);
}

ImageRays::ImageRays(const CameraFrame& frame, int width, int height)
    : frame_(frame),
      width_(width),
      height_(height),
      aspect_(static_cast<double>(width) / height),
      tan_half_(frame.tan_half_height) {
  if (frame.angle_on_smaller_side && width < height)
    tan_half_ *= static_cast<double>(height) / width;
}

Ray ImageRays::through(double px, double py) const {
  return Ray{frame_.eye, direction_through(px, py), 0};
}

Vec3 ImageRays::direction_through(double px, double py) const {
  const double sx = (2 * px / width_ - 1) * aspect_ * tan_half_;
  const double sy = (1 - 2 * py / height_) * tan_half_;
  const Vec3 d = frame_.forward + frame_.right * sx + frame_.up * sy;
  return d / length(d);
}

}  // namespace tessera
