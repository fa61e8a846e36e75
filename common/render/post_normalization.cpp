#include "common/render/post_normalization.h"

#include <algorithm>

namespace tessera {

void post_normalize(Image& image, double brightness) {
  float highest = 0;
  for (const float v : image.rgb) highest = std::max(highest, v);
  const double scale = brightness / std::max(1.0, static_cast<double>(highest));
  for (float& v : image.rgb) v = static_cast<float>(v * scale);
}

}  // namespace tessera
