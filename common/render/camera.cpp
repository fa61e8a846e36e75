#include <cmath>
#include <numbers>

#include "common/render/prepared_scene.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
  const auto twice = [](double v) { return Twice{{v, v}}; };
  width2_ = twice(width_);
  height2_ = twice(height_);
  aspect2_ = twice(aspect_);
  tan_half2_ = twice(tan_half_);
  for (int a = 0; a < 3; ++a) {
    forward2_[a] = twice(frame_.forward[a]);
    right2_[a] = twice(frame_.right[a]);
    up2_[a] = twice(frame_.up[a]);
  }
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

void ImageRays::directions_through(const double (&px)[4], const double (&py)[4],
                                   Vec3 (&out)[4]) const {
#if defined(__SSE2__)
  const auto load = [](const Twice& v) { return _mm_load_pd(v.lane); };
  const __m128d one = _mm_set1_pd(1), two = _mm_set1_pd(2);
  const __m128d width = load(width2_), height = load(height2_);
  const __m128d aspect = load(aspect2_), tan_half = load(tan_half2_);
  struct Lanes {
    __m128d x, y, z;
  };
  const auto lanes = [&](const Twice(&v)[3]) { return Lanes{load(v[0]), load(v[1]), load(v[2])}; };
  const Lanes forward = lanes(forward2_), right = lanes(right2_), up = lanes(up2_);
  // Points k and k + 1; lane j is direction_through(px[k + j], py[k + j]), operation by
  // operation.
  const auto pair = [&](int k) {
    const __m128d x = _mm_loadu_pd(px + k), y = _mm_loadu_pd(py + k);
    const __m128d sx = _mm_mul_pd(
        _mm_mul_pd(_mm_sub_pd(_mm_div_pd(_mm_mul_pd(two, x), width), one), aspect), tan_half);
    const __m128d sy =
        _mm_mul_pd(_mm_sub_pd(one, _mm_div_pd(_mm_mul_pd(two, y), height)), tan_half);
    // One axis of forward + right * sx + up * sy.
    const auto along = [&](__m128d forward_a, __m128d right_a, __m128d up_a) {
      return _mm_add_pd(_mm_add_pd(forward_a, _mm_mul_pd(right_a, sx)), _mm_mul_pd(up_a, sy));
    };
    const __m128d dx = along(forward.x, right.x, up.x), dy = along(forward.y, right.y, up.y),
                  dz = along(forward.z, right.z, up.z);
    const __m128d norm = _mm_sqrt_pd(
        _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz)));
    const __m128d ux = _mm_div_pd(dx, norm), uy = _mm_div_pd(dy, norm), uz = _mm_div_pd(dz, norm);
    _mm_storel_pd(&out[k].x, ux);
    _mm_storel_pd(&out[k].y, uy);
    _mm_storel_pd(&out[k].z, uz);
    _mm_storeh_pd(&out[k + 1].x, ux);
    _mm_storeh_pd(&out[k + 1].y, uy);
    _mm_storeh_pd(&out[k + 1].z, uz);
  };
  pair(0);
  pair(2);
#else
  for (int k = 0; k < 4; ++k) out[k] = direction_through(px[k], py[k]);
#endif
}

}  // namespace tessera
