#include "common/render/frame_buffer.h"

#include <algorithm>
#include <stdexcept>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace tessera {

FrameBuffer::FrameBuffer(int width, int height) : width_(width), height_(height) { take_memory(); }

FrameBuffer FrameBuffer::deferred(int width, int height) {
  FrameBuffer frame(0, 0);
  frame.width_ = width;
  frame.height_ = height;
  return frame;
}

void FrameBuffer::take_memory() {
  const std::size_t pixels = static_cast<std::size_t>(width_) * height_;
  sums_.resize(3 * pixels);
  counts_.resize(pixels);
}

void FrameBuffer::count_by_cells(int side) {
  cell_ = side;
  cells_across_ = side > 0 ? (width_ + side - 1) / side : 0;
  const int down = side > 0 ? (height_ + side - 1) / side : 0;
  cell_counts_.assign(static_cast<std::size_t>(cells_across_) * down, 0);
}

void FrameBuffer::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0f);
  std::fill(counts_.begin(), counts_.end(), std::uint16_t{0});
  std::fill(cell_counts_.begin(), cell_counts_.end(), std::uint16_t{0});
}

void FrameBuffer::throw_full() {
  throw std::length_error("a pixel of the frame buffer has the most passes it can count");
}

namespace {

// Asks the processor to fetch the cache lines of `bytes` from `first`, at most one a `step`.
// Inlined: GCC finds a function that only prefetches free of effects and drops its calls.
[[gnu::always_inline]] inline void prefetch(const void* first, std::size_t bytes,
                                            std::size_t step) {
  for (std::size_t b = 0; b < bytes; b += std::max<std::size_t>(64, step))
    __builtin_prefetch(static_cast<const char*>(first) + b, 1);
}

// sums[j] += rgb[j] for `floats` floats, four at a time with SSE2 (in every x86-64 CPU; the
// same IEEE additions as one at a time).
void add_floats(float* sums, const float* rgb, std::size_t floats) {
  std::size_t j = 0;
#if defined(__SSE2__)
  for (; j + 4 <= floats; j += 4)
    _mm_storeu_ps(sums + j, _mm_add_ps(_mm_loadu_ps(sums + j), _mm_loadu_ps(rgb + j)));
#endif
  for (; j < floats; ++j) sums[j] += rgb[j];
}

}  // namespace

void FrameBuffer::add_unit(const UnitPixels& unit, const float* rgb) {
  const PixelRect& r = unit.rect;
  if (cell_ > 0 && unit.step == 1 && unit.exclude == 0 && unit.pattern == PixelPattern::Anchors &&
      r.x0 % cell_ == 0 && r.y0 % cell_ == 0 && r.x1 == std::min(r.x0 + cell_, width_) &&
      r.y1 == std::min(r.y0 + cell_, height_))
    return add_cell(r, rgb);
  for_each_run(unit, [&](PixelCoord first, int count, int stride) {
    add_run(first, count, stride, rgb);
    rgb += 3 * static_cast<std::size_t>(count);
  });
}

void FrameBuffer::add_cell(const PixelRect& rect, const float* rgb) {
  std::uint16_t& passes =
      cell_counts_[static_cast<std::size_t>(rect.y0 / cell_) * cells_across_ + rect.x0 / cell_];
  if (passes == kMaxPasses) throw_full();
  const auto across = static_cast<std::size_t>(rect.width());
  const std::size_t row = 3 * static_cast<std::size_t>(width_);
  for (int y = rect.y0; y < rect.y1; ++y, rgb += 3 * across) {
    float* sums = sums_.data() + 3 * idx(rect.x0, y);
    // The row two further down fetched while this one adds, as add_run does.
    if (y + 2 < rect.y1) prefetch(sums + 2 * row, 12 * across, 64);
    add_floats(sums, rgb, 3 * across);
  }
  ++passes;
}

void FrameBuffer::add_run(PixelCoord first, int count, int stride, const float* rgb) {
  const std::size_t start = idx(first.x, first.y);
  const auto step = static_cast<std::size_t>(stride);
  const auto n = static_cast<std::size_t>(count);
  std::uint16_t* counts = counts_.data() + start;
  float* sums = sums_.data() + 3 * start;
  // A unit's runs go down its tile a row of blocks at a time (for_each_run): the run two rows
  // further down is fetched while this one adds. A run is short (about 127 pixels, 1.5 kB of
  // sums, a frame buffer's row from the next), too short for the processor's own prefetcher to
  // follow, so without this every run waited for memory (MergeRuns/2048: 250 M pixel passes a
  // second without, 340 M with; docs/SCALING.md).
  if (first.y + 2 * stride < height_) {
    const std::size_t below = 2 * step * static_cast<std::size_t>(width_),
                      span = (n - 1) * step + 1;
    prefetch(sums + 3 * below, 12 * span, 12 * step);
    prefetch(counts + below, 2 * span, 2 * step);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (counts[i * step] == kMaxPasses) throw_full();
  if (step == 1) {
    add_floats(sums, rgb, 3 * n);  // a row's sums lie side by side
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) sums[3 * i * step + c] += rgb[3 * i + c];
  }
  for (std::size_t i = 0; i < n; ++i) ++counts[i * step];
}

void FrameBuffer::mean_run(PixelCoord first, int count, int stride, float* out) const {
  if (counts_.empty()) {
    std::fill_n(out, 3 * static_cast<std::size_t>(count), 0.0f);
    return;
  }
  const std::size_t start = idx(first.x, first.y);
  const auto step = static_cast<std::size_t>(stride);
  const std::uint16_t* counts = counts_.data() + start;
  const float* sums = sums_.data() + 3 * start;
  // The cells along the row, followed without a division a pixel.
  const std::uint16_t* cells =
      cell_ == 0 ? nullptr
                 : cell_counts_.data() + static_cast<std::size_t>(first.y / cell_) * cells_across_;
  int x = first.x, column = 0, column_end = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i, x += stride) {
    if (cells != nullptr && x >= column_end) {
      column = x / cell_;
      column_end = (column + 1) * cell_;
    }
    const std::uint32_t passes = counts[i * step] + (cells != nullptr ? cells[column] : 0u);
    // A float divided by a float count, rounded once, equals mean()'s double quotient rounded
    // to float: a double holds more than twice a float's digits plus two, so rounding first to
    // double and then to float cannot differ from rounding once (Figueroa, "When is double
    // rounding innocuous?", 1995). Float division is the cheaper one.
    const auto divisor = static_cast<float>(passes);  // at most 2 x 65535: exact
    for (int c = 0; c < 3; ++c)
      out[3 * i + c] = passes == 0 ? 0.0f : sums[3 * i * step + c] / divisor;
  }
}

Image FrameBuffer::resolve() const {
  Image image(width_, height_);
  // mean_run's float quotients are mean()'s rounded to float, what Image keeps.
  for (int y = 0; y < height_; ++y) mean_run({0, y}, width_, 1, &image.rgb[image.index(0, y)]);
  return image;
}

}  // namespace tessera
