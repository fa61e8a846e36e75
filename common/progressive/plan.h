// The progressive plan (docs/ARCHITECTURE.md): refinement levels of anchors, then sample passes,
// each split into work units of roughly equal cost and ordered centre-out or in scanlines.
//
// Level l = 1..L (L = ceil(log2(max(W, H)))) uses blocks of side 2^(L-l). Each block stands for
// its top-left pixel, its anchor; a level traces only its new anchors, so pass 0 of every pixel
// is traced exactly once over the levels. Passes 1..P-1 are whole-image passes.
//
// A plan of a region (issue 21 §4) covers only the region's pixels: its units are the whole
// image's tiles clipped to it, so every pixel keeps its anchors, levels and passes, and the
// cost is the region's. Levels whose blocks are larger than the region are left out; the first
// level kept traces every anchor of the region at its block size.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/progressive/unit_pixels.h"

namespace tessera {

enum class UnitOrder { Centre, Scanline };
enum class PreviewMode {
  Anchor,  // blocks show their anchor's colour; costs nothing extra
  Area,    // the seeds' preview: every block of every level traces its centre, shown only while
           // the level is current; costs about a third more
};

struct PlanOptions {
  int width = 0, height = 0;
  int passes = 1;
  bool progressive = true;  // false: pass 0 is a direct whole-image pass, no levels
  UnitOrder order = UnitOrder::Centre;
  PreviewMode preview = PreviewMode::Anchor;
  long long unit_pixels = 1024;                    // target traced pixels per unit
  std::optional<PixelRect> region = std::nullopt;  // inside the image; unset: the whole image
};

// One row of the per-level table: a refinement level or a sample pass.
struct Stage {
  int level = 0;              // 1..L for a level, 0 for a pass over the image (or region)
  int pass = 0;               // the sample pass its values belong to
  int block = 1;              // block side in pixels
  bool preview_only = false;  // values are shown, never accumulated (PreviewMode::Area)
  long long blocks = 0;       // blocks in the image (or region) at this block size
  long long traced = 0;       // pixels traced by this stage
  int tile = 0;  // its units' tiles' side (multiples of it from the image's corner, clipped)
  int first_unit = 0, unit_count = 0;
};

struct WorkUnit {
  int stage = 0;
  UnitPixels pixels;
  long long cost = 0;  // traced pixels
};

struct Plan {
  int width = 0, height = 0;
  PixelRect area;               // the pixels the plan covers: the region, or the whole image
  int levels = 0;               // L, of the whole image; a region's first stages may be later
                                // levels
  std::vector<Stage> stages;    // in dispatch order
  std::vector<WorkUnit> units;  // grouped by stage, each stage's units in dispatch order
  long long total_cost = 0;
  // The side of the whole-image passes' tiles (multiples of it from the image's corner, clipped
  // to the area), the same for every such pass; 0 when the plan has none.
  int pass_tile = 0;
};

int level_count(int width, int height);
int block_side(int levels, int level);
Plan make_plan(const PlanOptions& options);
// How long a unit should take on one thread: long enough that its round trip and the
// coordinator's work per unit are small beside it, short enough to balance the load and refine
// the preview smoothly.
inline constexpr double kUnitTargetSeconds = 0.020;

// The most traced pixels a unit is cut to: pixels cheaper than kUnitTargetSeconds / 65,536
// (0.3 µs a pixel pass) get shorter units. Its result, 786 kB of floats, stays under the
// coordinator's mmap threshold (1 MB, coordinator/main.cpp), so it comes from the reused heap.
inline constexpr long long kMostUnitPixels = 65536;

// Traced pixels a unit should hold so that it renders in kUnitTargetSeconds on one thread, given a
// probe's seconds per pixel and pass. Between 256 and kMostUnitPixels; 1024 when the cost is
// unknown (0).
long long unit_pixels_for_cost(double seconds_per_pixel_pass);

// The io thread's cost a pixel pass, merge and reads included, for later jobs of the capacity
// benchmark (docs/SCALING.md): one coordinator core carries about seconds_per_pixel_pass / this
// worker threads, however many connect.
inline constexpr double kCoordinatorSecondsPerPixelPass = 6e-9;

// `plan.unit_pixels` (unit_pixels_for_cost's), made smaller where a whole pass of the plan
// would otherwise have fewer than two units for each thread the coordinator can keep busy
// (`threads` connected, at most seconds_per_pixel_pass / kCoordinatorSecondsPerPixelPass):
// the passes after the first wait for the one before, and a worker takes its threads' units
// and a prefetch at once, so a pass of a few units left most threads idle (a 512x512 job's
// wall time doubled, docs/SCALING.md). Never below 16,384 pixels, the most before
// kMostUnitPixels; unchanged when `threads` is 0.
long long unit_pixels_for_threads(const PlanOptions& plan, int threads,
                                  double seconds_per_pixel_pass);

UnitOrder parse_unit_order(const std::string& name);      // "centre"/"center"/"scanline"; throws
PreviewMode parse_preview_mode(const std::string& name);  // "anchor"/"area"; throws
const char* to_string(UnitOrder order);
const char* to_string(PreviewMode mode);

}  // namespace tessera
