#include "common/progressive/unit_pixels.h"

#include <algorithm>

namespace tessera {
namespace {

int first_multiple_at_or_after(int v, int step) { return (v + step - 1) / step * step; }

template <typename Visit>
void for_each_pixel(const UnitPixels& u, Visit&& visit) {
  const PixelRect& r = u.rect;
  if (u.step <= 0 || r.width() <= 0 || r.height() <= 0) return;
  const int x_start = first_multiple_at_or_after(r.x0, u.step);
  const int y_start = first_multiple_at_or_after(r.y0, u.step);
  for (int by = y_start; by < r.y1; by += u.step) {
    for (int bx = x_start; bx < r.x1; bx += u.step) {
      if (u.pattern == PixelPattern::Centres) {
        visit(PixelCoord{std::min(bx + u.step / 2, r.x1 - 1), std::min(by + u.step / 2, r.y1 - 1)});
      } else if (u.exclude <= 0 || bx % u.exclude != 0 || by % u.exclude != 0) {
        visit(PixelCoord{bx, by});
      }
    }
  }
}

}  // namespace

std::vector<PixelCoord> expand(const UnitPixels& unit) {
  std::vector<PixelCoord> out;
  for_each_pixel(unit, [&](PixelCoord p) { out.push_back(p); });
  return out;
}

long long pixel_count(const UnitPixels& unit) {
  long long n = 0;
  for_each_pixel(unit, [&](PixelCoord) { ++n; });
  return n;
}

}  // namespace tessera
