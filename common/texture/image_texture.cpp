#include "common/texture/image_texture.h"

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

double periodic(double u) { return u - std::floor(u); }

// Texel index `i` of an axis of `size` texels: wrapped around, or clamped to the edges.
int texel_index(long long i, int size, bool clamp) {
  if (clamp) return static_cast<int>(std::clamp<long long>(i, 0, size - 1));
  const long long m = i % size;
  return static_cast<int>(m < 0 ? m + size : m);
}

// A texture coordinate in [0, 1]: its fractional part, or clamped.
double in_square(double u, bool clamp) { return clamp ? std::clamp(u, 0.0, 1.0) : periodic(u); }

}  // namespace

Rgb bilinear_lookup(const Image& image, double u, double v, bool clamp_u, bool clamp_v) {
  if (image.width <= 0 || image.height <= 0) return {};
  if (!std::isfinite(u) || !std::isfinite(v)) u = v = 0;
  const double x = in_square(u, clamp_u) * image.width - 0.5;
  const double y = (1 - in_square(v, clamp_v)) * image.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const double fx = x - x0, fy = y - y0;
  const int i0 = texel_index(static_cast<long long>(x0), image.width, clamp_u);
  const int i1 = texel_index(static_cast<long long>(x0) + 1, image.width, clamp_u);
  const int j0 = texel_index(static_cast<long long>(y0), image.height, clamp_v);
  const int j1 = texel_index(static_cast<long long>(y0) + 1, image.height, clamp_v);
  const Rgb top = image.get(i0, j0) * (1 - fx) + image.get(i1, j0) * fx;
  const Rgb bottom = image.get(i0, j1) * (1 - fx) + image.get(i1, j1) * fx;
  return top * (1 - fy) + bottom * fy;
}

}  // namespace tessera
