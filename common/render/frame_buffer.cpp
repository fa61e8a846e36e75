#include "common/render/frame_buffer.h"

#include <stdexcept>

namespace tessera {

FrameBuffer::FrameBuffer(int width, int height)
    : width_(width),
      height_(height),
      sums_(static_cast<std::size_t>(width) * height * 3, 0.0f),
      counts_(static_cast<std::size_t>(width) * height, 0) {}

void FrameBuffer::add_pass(int x, int y, const float rgb[3]) {
  const std::size_t i = idx(x, y);
  if (counts_[i] == kMaxPasses)
    throw std::length_error("a pixel of the frame buffer has the most passes it can count");
  sums_[3 * i] += rgb[0];
  sums_[3 * i + 1] += rgb[1];
  sums_[3 * i + 2] += rgb[2];
  ++counts_[i];
}

Rgb FrameBuffer::mean(int x, int y) const {
  const std::size_t i = idx(x, y);
  if (counts_[i] == 0) return {};
  const double n = counts_[i];
  return {sums_[3 * i] / n, sums_[3 * i + 1] / n, sums_[3 * i + 2] / n};
}

Image FrameBuffer::resolve() const {
  Image image(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) image.set(x, y, mean(x, y));
  return image;
}

}  // namespace tessera
