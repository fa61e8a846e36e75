// The pixels of one work unit, described compactly so that a unit travels as a few integers and
// both the coordinator and the worker expand it to the same list in the same order.
#pragma once

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

// The unit's pixels in scanline order; results travel in this order.
std::vector<PixelCoord> expand(const UnitPixels& unit);
long long pixel_count(const UnitPixels& unit);

// The top-left corner of the block of side `step` that pixel (x, y) stands for on display.
inline PixelCoord block_of(PixelCoord p, int step) {
  return {p.x / step * step, p.y / step * step};
}

}  // namespace tessera
