#include "common/render/frame_buffer.h"

#include <algorithm>
#include <array>
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
}

void FrameBuffer::take_counts() { counts_.resize(static_cast<std::size_t>(width_) * height_); }

void FrameBuffer::TileCounts::assign(int tile_side, int width, int height) {
  side = tile_side;
  across = (width + side - 1) / side;
  counts.assign(static_cast<std::size_t>(across) * ((height + side - 1) / side), 0);
}

bool FrameBuffer::TileCounts::is_tile(const PixelRect& r, int width, int height) const {
  return side > 0 && r.x0 % side == 0 && r.y0 % side == 0 && r.x1 == std::min(r.x0 + side, width) &&
         r.y1 == std::min(r.y0 + side, height);
}

void FrameBuffer::count_by_units(const Plan& plan) {
  if (plan.pass_tile > 0) cells_.assign(plan.pass_tile, width_, height_);
  for (const Stage& stage : plan.stages) {
    if (stage.level == 0 || stage.preview_only) continue;
    const int level = std::countr_zero(static_cast<unsigned>(stage.block));
    if (levels_.size() <= static_cast<std::size_t>(level)) levels_.resize(level + 1);
    levels_[level].assign(stage.tile, width_, height_);
    coarsest_level_ = std::max(coarsest_level_, level);
  }
}

void FrameBuffer::clear() {
  std::fill(sums_.begin(), sums_.end(), 0.0f);
  std::fill(counts_.begin(), counts_.end(), std::uint16_t{0});
  std::fill(cells_.counts.begin(), cells_.counts.end(), std::uint16_t{0});
  for (TileCounts& level : levels_) std::fill(level.counts.begin(), level.counts.end(), 0);
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

FrameBuffer::TileCounts* FrameBuffer::counted_by_tile(const UnitPixels& unit) {
  if (unit.pattern != PixelPattern::Anchors) return nullptr;
  if (unit.step == 1 && unit.exclude == 0 && cells_.is_tile(unit.rect, width_, height_))
    return &cells_;
  // A level's unit: its anchors of its step, leaving out the next coarser level's (none at the
  // coarsest), so that it covers every pixel of its tile that level_of() gives its level.
  if (!std::has_single_bit(static_cast<unsigned>(unit.step))) return nullptr;
  const int level = std::countr_zero(static_cast<unsigned>(unit.step));
  if (static_cast<std::size_t>(level) >= levels_.size() ||
      unit.exclude != (level == coarsest_level_ ? 0 : 2 * unit.step) ||
      !levels_[level].is_tile(unit.rect, width_, height_))
    return nullptr;
  return &levels_[level];
}

void FrameBuffer::add_unit(const UnitPixels& unit, const float* rgb) {
  if (TileCounts* tiles = counted_by_tile(unit)) {
    std::uint16_t& passes = tiles->of(unit.rect.x0, unit.rect.y0);
    if (passes == kMaxPasses) throw_full();
    add_sums(unit, rgb);
    ++passes;
    return;
  }
  for_each_run(unit, [&](PixelCoord first, int count, int stride) {
    add_run(first, count, stride, rgb);
    rgb += 3 * static_cast<std::size_t>(count);
  });
}

void FrameBuffer::add_sums(const UnitPixels& unit, const float* rgb) {
  for_each_run(unit, [&](PixelCoord first, int count, int stride) {
    add_run_sums(first, count, stride, rgb);
    rgb += 3 * static_cast<std::size_t>(count);
  });
}

// A unit's runs go down its tile a row of blocks at a time (for_each_run): the run two rows
// further down is fetched while this one adds. A run is short (about 127 pixels, 1.5 kB of
// sums, a frame buffer's row from the next), too short for the processor's own prefetcher to
// follow, so without this every run waited for memory (MergeRuns/2048: 250 M pixel passes a
// second without, 340 M with; docs/SCALING.md).
void FrameBuffer::add_run_sums(PixelCoord first, int count, int stride, const float* rgb) {
  const auto step = static_cast<std::size_t>(stride);
  const auto n = static_cast<std::size_t>(count);
  float* sums = sums_.data() + 3 * idx(first.x, first.y);
  if (first.y + 2 * stride < height_)
    prefetch(sums + 6 * step * static_cast<std::size_t>(width_), 12 * ((n - 1) * step + 1),
             12 * step);
  if (step == 1) {
    add_floats(sums, rgb, 3 * n);  // a row's sums lie side by side
  } else {
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) sums[3 * i * step + c] += rgb[3 * i + c];
  }
}

void FrameBuffer::add_run(PixelCoord first, int count, int stride, const float* rgb) {
  const auto step = static_cast<std::size_t>(stride);
  const auto n = static_cast<std::size_t>(count);
  if (counts_.empty()) take_counts();
  std::uint16_t* counts = counts_.data() + idx(first.x, first.y);
  if (first.y + 2 * stride < height_)  // as add_run_sums fetches the sums
    prefetch(counts + 2 * step * static_cast<std::size_t>(width_), 2 * ((n - 1) * step + 1),
             2 * step);
  for (std::size_t i = 0; i < n; ++i)
    if (counts[i * step] == kMaxPasses) throw_full();
  add_run_sums(first, count, stride, rgb);
  for (std::size_t i = 0; i < n; ++i) ++counts[i * step];
}

namespace {

// One row of tile counts followed along the row, without a division a pixel.
class TilesAlongRow {
 public:
  TilesAlongRow() = default;  // no tiles: no passes anywhere
  TilesAlongRow(const std::uint16_t* row, int side) : row_(row), side_(side) {}
  // Pixels x in increasing order.
  std::uint32_t at(int x) {
    if (row_ == nullptr) return 0;
    if (x >= end_) {
      column_ = x / side_;
      end_ = (column_ + 1) * side_;
    }
    return row_[column_];
  }

 private:
  const std::uint16_t* row_ = nullptr;
  int side_ = 0, column_ = 0, end_ = 0;
};

}  // namespace

void FrameBuffer::mean_run(PixelCoord first, int count, int stride, float* out) const {
  if (sums_.empty()) {
    std::fill_n(out, 3 * static_cast<std::size_t>(count), 0.0f);
    return;
  }
  const std::size_t start = idx(first.x, first.y);
  const auto step = static_cast<std::size_t>(stride);
  // nullptr while no pass has been counted by pixel (take_counts).
  const std::uint16_t* counts = counts_.empty() ? nullptr : counts_.data() + start;
  const float* sums = sums_.data() + 3 * start;
  TilesAlongRow cells(cells_.row(first.y), cells_.side);
  std::array<TilesAlongRow, 32> levels;  // by level_of()
  for (std::size_t l = 0; l < levels_.size(); ++l)
    levels[l] = TilesAlongRow(levels_[l].row(first.y), levels_[l].side);
  int x = first.x;
  for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i, x += stride) {
    const std::uint32_t passes = (counts == nullptr ? 0u : counts[i * step]) + cells.at(x) +
                                 (levels_.empty() ? 0u : levels[level_of(x, first.y)].at(x));
    // A float divided by a float count, rounded once, equals mean()'s double quotient rounded
    // to float: a double holds more than twice a float's digits plus two, so rounding first to
    // double and then to float cannot differ from rounding once (Figueroa, "When is double
    // rounding innocuous?", 1995). Float division is the cheaper one.
    const auto divisor = static_cast<float>(passes);  // at most 3 x 65535: exact
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
