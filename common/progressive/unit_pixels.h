// The pixels of one work unit, described compactly so that a unit travels as a few integers and
// both the coordinator and the worker expand it to the same list in the same order.
#pragma once

#include <algorithm>
#include <vector>

#include "common/math/pixel_rect.h"

namespace tessera {

enum class PixelPattern {
  Anchors,  // block anchors: (x, y) multiples of `step`, minus those that are multiples of
            // `exclude` in both coordinates (the anchors of the previous, coarser level)
  Centres,  // one pixel per block of side `step`: its centre, clamped into the rectangle (the
            // seeds' preview that samples the middle of the block rather than its corner)
};

struct UnitPixels {
  PixelRect rect;  // aligned to `step` except where it is clipped by the image's edge
  int step = 1;
  int exclude = 0;  // 0: nothing excluded
  PixelPattern pattern = PixelPattern::Anchors;
  friend bool operator==(const UnitPixels&, const UnitPixels&) = default;
};

inline int first_multiple_at_or_after(int v, int step) { return (v + step - 1) / step * step; }

// Calls visit(PixelCoord) for each of the unit's pixels in scanline order, the order results
// travel in. Inline, so that the coordinator merges a result without a list of its pixels.
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

// The unit's pixels in for_each_pixel's order.
std::vector<PixelCoord> expand(const UnitPixels& unit);
long long pixel_count(const UnitPixels& unit);

// The top-left corner of the block of side `step` that pixel (x, y) stands for on display.
inline PixelCoord block_of(PixelCoord p, int step) {
  return {p.x / step * step, p.y / step * step};
}

}  // namespace tessera
