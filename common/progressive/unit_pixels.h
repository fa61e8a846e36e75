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

// Calls visit_run(first, count, stride) for the unit's pixels in scanline order, the order
// results travel in, as runs along a row: pixels first, first + (stride, 0), ... (count of
// them; the stride is the step, or twice it on a row that leaves out every other anchor). Runs let
// the coordinator merge a row at a time (FrameBuffer::add_run) instead of a pixel at a time;
// inline, so that it needs no list of the unit's pixels.
template <typename VisitRun>
void for_each_run(const UnitPixels& u, VisitRun&& visit_run) {
  const PixelRect& r = u.rect;
  if (u.step <= 0 || r.width() <= 0 || r.height() <= 0) return;
  const int x_start = first_multiple_at_or_after(r.x0, u.step);
  const int y_start = first_multiple_at_or_after(r.y0, u.step);
  if (x_start >= r.x1) return;
  const int across = (r.x1 - 1 - x_start) / u.step + 1;  // block columns in the rectangle
  for (int by = y_start; by < r.y1; by += u.step) {
    if (u.pattern == PixelPattern::Centres) {
      // Centres step with the blocks, except a last one clamped into the rectangle.
      const int cy = std::min(by + u.step / 2, r.y1 - 1);
      const int last_x = x_start + (across - 1) * u.step;
      const int unclamped = last_x + u.step / 2 < r.x1 ? across : across - 1;
      if (unclamped > 0) visit_run(PixelCoord{x_start + u.step / 2, cy}, unclamped, u.step);
      if (unclamped < across) visit_run(PixelCoord{r.x1 - 1, cy}, 1, u.step);
    } else if (u.exclude <= 0 || by % u.exclude != 0) {
      visit_run(PixelCoord{x_start, by}, across, u.step);
    } else if (u.exclude == 2 * u.step) {
      // Every other anchor is the coarser level's (make_plan's levels): the rest are one run,
      // two blocks apart, rather than a run of one pixel between each two excluded ones (a
      // call of FrameBuffer::add_run a pixel on half the rows of a plan's finest level).
      const int first = x_start % u.exclude == 0 ? x_start + u.step : x_start;
      if (first < r.x1)
        visit_run(PixelCoord{first, by}, (r.x1 - 1 - first) / u.exclude + 1, u.exclude);
    } else {
      // A row of the coarser level's anchors: the runs between its excluded columns.
      int bx = x_start;
      for (int excluded = first_multiple_at_or_after(x_start, u.exclude); bx < r.x1;
           excluded += u.exclude) {
        const int end = std::min(excluded, r.x1);
        if (end > bx) visit_run(PixelCoord{bx, by}, (end - 1 - bx) / u.step + 1, u.step);
        bx = first_multiple_at_or_after(excluded + 1, u.step);
      }
    }
  }
}

// The same pixels one at a time: visit(PixelCoord).
template <typename Visit>
void for_each_pixel(const UnitPixels& u, Visit&& visit) {
  for_each_run(u, [&](PixelCoord first, int count, int stride) {
    for (int i = 0; i < count; ++i) visit(PixelCoord{first.x + i * stride, first.y});
  });
}

// The unit's pixels in for_each_pixel's order.
std::vector<PixelCoord> expand(const UnitPixels& unit);
long long pixel_count(const UnitPixels& unit);

// The top-left corner of the block of side `step` that pixel (x, y) stands for on display.
inline PixelCoord block_of(PixelCoord p, int step) {
  return {p.x / step * step, p.y / step * step};
}

}  // namespace tessera
