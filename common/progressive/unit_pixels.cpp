#include "common/progressive/unit_pixels.h"

namespace tessera {

std::vector<PixelCoord> expand(const UnitPixels& unit) {
  std::vector<PixelCoord> out;
  for_each_pixel(unit, [&](PixelCoord p) { out.push_back(p); });
  return out;
}

long long pixel_count(const UnitPixels& unit) {
  long long n = 0;
  for_each_run(unit, [&](PixelCoord, int count, int) { n += count; });
  return n;
}

}  // namespace tessera
