// Running means of sample passes, per pixel. Pass values are rounded to float32 before they
// are accumulated, exactly as they travel over the wire, so that the CLI and the coordinator
// compute bit-identical images from the same passes.
//
// 14 bytes a pixel at most: float32 sums and a 16-bit count, the count only once a pass is
// counted by pixel (below). The coordinator holds one per running job (docs/SERVICE.md,
// "Memory"), so the sums are float32 rather than double: over the at most
// 256 passes a job may have, a float sum of values near 1 is off by at most about 2^-24 x 256
// relative, far below what a PNG or an EXR's half floats show.
// A coordinator job's frame buffer is made without memory (deferred) and takes it at its first
// merge: a queued job holds none, and a running one takes what a finished one gave back
// (mapping_pool.h).
//
// A pixel's passes are counted in three parts: by pixel, by cell and by level tile. A
// coordinator job's whole-image passes come in units that are each one square tile of the
// image, every pixel of it one pass (make_plan's pass_tile): such a unit is counted once for
// its tile, a cell, so its merge reads and writes only the sums, 12 bytes a pixel instead of
// 14, with no per-pixel count to check and add (docs/SCALING.md). Pass 0 over the progressive
// levels likewise: a level's unit is one tile of that level (Stage::tile) and adds one pass to
// each of its anchors, the pixels whose coordinates' lowest set bit is the level's step, so it
// is counted once for its level and tile. Exact in any order: a pixel's passes are its own
// count plus its cell's plus its level tile's. The CLI counts by pixel only. The per-pixel
// counts (2 bytes a pixel, 8 MB at 2048x2048) take their memory, zeroed, only when the first
// pass counted by pixel arrives: a whole-image job's are never allocated, nor zeroed by the
// pool (docs/SCALING.md).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "common/image/image.h"
#include "common/math/pixel_rect.h"
#include "common/progressive/plan.h"
#include "common/progressive/unit_pixels.h"
#include "common/render/zeroed_allocator.h"

namespace tessera {

class FrameBuffer {
 public:
  // Passes one pixel may receive by pixel, and as many by its cell: the 16-bit counts' range.
  static constexpr std::uint32_t kMaxPasses = 65535;

  FrameBuffer(int width, int height);
  // One without memory until take_memory(); it reads as black until then.
  static FrameBuffer deferred(int width, int height);
  bool has_memory() const { return !sums_.empty(); }
  // The bytes its pixels hold: 12 a pixel with memory, 14 once a pass was counted by pixel.
  std::size_t bytes() const { return sizeof(float) * sums_.size() + 2 * counts_.size(); }
  // The sums' memory; the per-pixel counts' comes with the first pass counted by pixel. Not
  // thread-safe, nor is that first pass: one thread calls it before any pass is added (the
  // CLI's threads each add passes to a tile's buffer of their own, made with its memory).
  void take_memory();
  // Counts add_unit's units that are exactly one of `plan`'s tiles (multiples of its side from
  // the corner, clipped only by the image's edges) once for the tile: the whole-image passes'
  // (Plan::pass_tile, cells) and each accumulated level's (Stage::tile). Before any pass is
  // added; without it every pass is counted by pixel.
  void count_by_units(const Plan& plan);
  // Forgets every pass, keeping the memory: a buffer reused for one tile after another
  // (render_image's threads) zeroes its 14 bytes a pixel instead of allocating them again.
  void clear();
  int width() const { return width_; }
  int height() const { return height_; }

  // Adds one pass's value for pixel (x, y). Passes may arrive in any order: the sum of the
  // same values in a different order may differ in the last bit, so callers add passes of a
  // pixel in pass order (the scheduler guarantees it; the CLI renders them in order). Throws
  // std::length_error beyond kMaxPasses passes.
  // Inline, with mean(): the coordinator calls both for every pixel it merges.
  void add_pass(int x, int y, const float rgb[3]) {
    const std::size_t i = idx(x, y);
    if (counts_.empty()) take_counts();
    if (counts_[i] == kMaxPasses) throw_full();
    sums_[3 * i] += rgb[0];
    sums_[3 * i + 1] += rgb[1];
    sums_[3 * i + 2] += rgb[2];
    ++counts_[i];
  }
  // The same for a run of `count` pixels along row first.y, `stride` apart (for_each_run), the
  // passes' values 3 floats a pixel in a row. Throws std::length_error, adding nothing, when
  // one of them has kMaxPasses passes already. Both need the memory (has_memory()).
  void add_run(PixelCoord first, int count, int stride, const float* rgb);
  // One pass for each of a unit's pixels, 3 floats a pixel in for_each_run's order: counted by
  // tile when the unit is one (count_by_units), else by pixel (add_run). Throws
  // std::length_error beyond kMaxPasses: a tile then adds nothing, a unit counted by pixel
  // stops at the run with the full pixel (add_run).
  void add_unit(const UnitPixels& unit, const float* rgb);
  std::uint32_t passes_at(int x, int y) const {
    return (counts_.empty() ? 0u : counts_[idx(x, y)]) + cells_.at(x, y) + level_passes(x, y);
  }
  // The mean of the passes added so far (black where none).
  Rgb mean(int x, int y) const {
    const std::uint32_t passes = passes_at(x, y);
    if (passes == 0) return {};
    const std::size_t i = idx(x, y);
    const double n = passes;
    return {sums_[3 * i] / n, sums_[3 * i + 1] / n, sums_[3 * i + 2] / n};
  }
  // mean() of a run's pixels rounded to float, 3 a pixel into `out`: what the coordinator shows
  // of each pass (the tile records' 8-bit values).
  void mean_run(PixelCoord first, int count, int stride, float* out) const;
  Image resolve() const;

 private:
  // Passes counted once for a tile of side `side`, tile by tile, row by row (a few hundred).
  struct TileCounts {
    int side = 0, across = 0;  // side 0: no tiles, nothing counted by them
    std::vector<std::uint16_t> counts;
    void assign(int tile_side, int width, int height);
    // Whether `rect` is exactly one tile, clipped only by the image's edges.
    bool is_tile(const PixelRect& rect, int width, int height) const;
    std::uint16_t& of(int x, int y) {
      return counts[static_cast<std::size_t>(y / side) * across + x / side];
    }
    // Row y's counts; nullptr without tiles.
    const std::uint16_t* row(int y) const {
      return side == 0 ? nullptr : counts.data() + static_cast<std::size_t>(y / side) * across;
    }
    std::uint32_t at(int x, int y) const { return side == 0 ? 0 : row(y)[x / side]; }
  };
  std::size_t idx(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
  // The level whose anchor (x, y) is, as log2 of its step: the lowest set bit of x | y, or the
  // coarsest level's for its anchors.
  int level_of(int x, int y) const {
    return std::min(std::countr_zero(static_cast<unsigned>(x | y)), coarsest_level_);
  }
  std::uint32_t level_passes(int x, int y) const {
    return levels_.empty() ? 0 : levels_[level_of(x, y)].at(x, y);
  }
  // The tile counts that count `unit` once, or nullptr when its pixels are counted by pixel.
  TileCounts* counted_by_tile(const UnitPixels& unit);
  // Adds one pass to each of the unit's pixels, 3 floats a pixel, without counting it.
  void add_sums(const UnitPixels& unit, const float* rgb);
  void add_run_sums(PixelCoord first, int count, int stride, const float* rgb);
  // The per-pixel counts' memory, zeroed (ZeroedAllocator: from the pool at 2 MB and more).
  void take_counts();
  [[noreturn]] static void throw_full();
  int width_, height_;
  // Empty until take_memory() when deferred.
  std::vector<float, ZeroedAllocator<float>> sums_;  // 3 per pixel
  // By pixel; empty, every count 0, until the first pass counted by pixel (take_counts).
  std::vector<std::uint16_t, ZeroedAllocator<std::uint16_t>> counts_;
  TileCounts cells_;                // whole-image passes
  std::vector<TileCounts> levels_;  // pass 0 over the levels, by log2 of their step
  int coarsest_level_ = 0;          // log2 of the coarsest accumulated level's step
};

}  // namespace tessera
