#include "common/render/frame_buffer.h"

#include <stdexcept>

namespace tessera {

FrameBuffer::FrameBuffer(int width, int height)
    : width_(width),
      height_(height),
      sums_(static_cast<std::size_t>(width) * height * 3, 0.0f),
      counts_(static_cast<std::size_t>(width) * height, 0) {}

void FrameBuffer::throw_full() {
  throw std::length_error("a pixel of the frame buffer has the most passes it can count");
}

Image FrameBuffer::resolve() const {
  Image image(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) image.set(x, y, mean(x, y));
  return image;
}

}  // namespace tessera
