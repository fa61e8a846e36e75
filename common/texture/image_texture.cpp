#include "common/texture/image_texture.h"

#include <cmath>

namespace tessera {

namespace {

double periodic(double u) { return u - std::floor(u); }

int wrap(long long i, int size) {
  const long long m = i % size;
  return static_cast<int>(m < 0 ? m + size : m);
}

}  // namespace

Rgb bilinear_lookup(const Image& image, double u, double v) {
  if (image.width <= 0 || image.height <= 0) return {};
  if (!std::isfinite(u) || !std::isfinite(v)) u = v = 0;
  const double x = periodic(u) * image.width - 0.5;
  const double y = (1 - periodic(v)) * image.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const int i0 = wrap(static_cast<long long>(x0), image.width);
  const int i1 = wrap(static_cast<long long>(x0) + 1, image.width);
  const int j0 = wrap(static_cast<long long>(y0), image.height);
  const int j1 = wrap(static_cast<long long>(y0) + 1, image.height);
  const Rgb top = image.get(i0, j0) * (1 - fx) + image.get(i1, j0) * fx;
  const Rgb bottom = image.get(i0, j1) * (1 - fx) + image.get(i1, j1) * fx;
  return top * (1 - fy) + bottom * fy;
}

}  // namespace tessera
