#include "common/progressive/plan.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace tessera {
namespace {

long long ceil_div(long long a, long long b) { return (a + b - 1) / b; }

// The image's tiles of side `tile` (a multiple of `step`, so they stay aligned to every block)
// that meet `area`, clipped to it, in dispatch order.
std::vector<PixelRect> tiles(const PixelRect& area, int tile, UnitOrder order) {
  std::vector<PixelRect> out;
  for (int y = area.y0 / tile * tile; y < area.y1; y += tile)
    for (int x = area.x0 / tile * tile; x < area.x1; x += tile)
      out.push_back({std::max(x, area.x0), std::max(y, area.y0), std::min(x + tile, area.x1),
                     std::min(y + tile, area.y1)});
  if (order == UnitOrder::Centre) {
    // Rectangular rings around the area's centre (the seeds' "central" pattern): the ring is
    // the larger of the two axis distances; within a ring, scanline order keeps it stable.
    const double cx = (area.x0 + area.x1) / 2.0, cy = (area.y0 + area.y1) / 2.0;
    auto ring = [&](const PixelRect& r) {
      const double dx = std::abs((r.x0 + r.x1) / 2.0 - cx);
      const double dy = std::abs((r.y0 + r.y1) / 2.0 - cy);
      return std::floor(std::max(dx, dy) / tile);
    };
    std::stable_sort(out.begin(), out.end(),
                     [&](const PixelRect& a, const PixelRect& b) { return ring(a) < ring(b); });
  }
  return out;
}

void add_stage(Plan& plan, Stage stage, UnitPixels shape, double density,
               const PlanOptions& options) {
  // Tile side: a multiple of the block so no block straddles two units, sized so that a tile
  // holds about `unit_pixels` traced pixels at this stage's density.
  const double blocks_per_tile = static_cast<double>(options.unit_pixels) / density;
  const int k = std::max(1, static_cast<int>(std::sqrt(blocks_per_tile)));
  const long long side = std::min<long long>(static_cast<long long>(k) * shape.step,
                                             std::max(plan.width, plan.height));
  stage.tile = static_cast<int>(side);
  if (stage.level == 0) plan.pass_tile = stage.tile;
  stage.first_unit = static_cast<int>(plan.units.size());
  const int stage_index = static_cast<int>(plan.stages.size());
  for (const PixelRect& r : tiles(plan.area, static_cast<int>(side), options.order)) {
    shape.rect = r;
    const long long n = pixel_count(shape);
    if (n == 0) continue;
    plan.units.push_back({stage_index, shape, n});
    stage.traced += n;
  }
  stage.unit_count = static_cast<int>(plan.units.size()) - stage.first_unit;
  if (stage.unit_count == 0) return;  // a region too thin for this level's anchors
  const PixelRect& a = plan.area;
  stage.blocks = (ceil_div(a.x1, stage.block) - a.x0 / stage.block) *
                 (ceil_div(a.y1, stage.block) - a.y0 / stage.block);
  plan.total_cost += stage.traced;
  plan.stages.push_back(stage);
}

}  // namespace

int level_count(int width, int height) {
  int levels = 1;
  while ((1LL << levels) < std::max(width, height)) ++levels;
  return levels;
}

int block_side(int levels, int level) { return 1 << (levels - level); }

long long unit_pixels_for_cost(double seconds_per_pixel_pass) {
  constexpr long long kFewest = 256, kUnknown = 1024;
  if (!(seconds_per_pixel_pass > 0)) return kUnknown;
  const double pixels = kUnitTargetSeconds / seconds_per_pixel_pass;
  return pixels >= static_cast<double>(kMostUnitPixels) ? kMostUnitPixels
                                                        : std::max(kFewest, std::llround(pixels));
}

long long unit_pixels_for_threads(const PlanOptions& plan, int threads,
                                  double seconds_per_pixel_pass) {
  constexpr long long kKept = 16384;
  if (plan.unit_pixels <= kKept || threads <= 0) return plan.unit_pixels;
  const double fed =
      std::min<double>(threads, seconds_per_pixel_pass / kCoordinatorSecondsPerPixelPass);
  const long long units = std::max(1LL, std::llround(2 * fed));
  const PixelRect area = plan.region.value_or(PixelRect{0, 0, plan.width, plan.height});
  const long long pass_pixels = static_cast<long long>(area.width()) * area.height();
  return std::clamp(pass_pixels / units, kKept, plan.unit_pixels);
}

Plan make_plan(const PlanOptions& o) {
  if (o.width <= 0 || o.height <= 0 || o.passes <= 0 || o.unit_pixels <= 0)
    throw std::invalid_argument("make_plan: sizes, passes and unit size must be positive");
  Plan plan;
  plan.width = o.width;
  plan.height = o.height;
  plan.area = o.region.value_or(PixelRect{0, 0, o.width, o.height});
  const PixelRect& a = plan.area;
  if (a.x0 < 0 || a.y0 < 0 || a.x1 > o.width || a.y1 > o.height || a.width() <= 0 ||
      a.height() <= 0)
    throw std::invalid_argument("make_plan: the region must be a non-empty part of the image");
  plan.levels = o.progressive ? level_count(o.width, o.height) : 0;
  // The first level whose blocks fit the area (level 1 for the whole image); it has no coarser
  // level's anchors to leave out.
  const int first_level = std::max(1, plan.levels - level_count(a.width(), a.height()) + 1);
  for (int l = first_level; l <= plan.levels; ++l) {
    const int s = block_side(plan.levels, l);
    Stage stage;
    stage.level = l;
    stage.block = s;
    UnitPixels shape;
    shape.step = s;
    double density = 1.0;
    if (o.preview == PreviewMode::Area && l < plan.levels) {
      stage.preview_only = true;
      shape.pattern = PixelPattern::Centres;
    } else if (o.preview == PreviewMode::Anchor && l > first_level) {
      shape.exclude = 2 * s;
      density = 0.75;  // three new anchors per four blocks
    }
    add_stage(plan, stage, shape, density, o);
  }
  for (int p = plan.levels > 0 ? 1 : 0; p < o.passes; ++p) {
    Stage stage;
    stage.pass = p;
    add_stage(plan, stage, UnitPixels{}, 1.0, o);
  }
  return plan;
}

UnitOrder parse_unit_order(const std::string& name) {
  if (name == "centre" || name == "center" || name == "central") return UnitOrder::Centre;
  if (name == "scanline") return UnitOrder::Scanline;
  throw std::invalid_argument("order must be \"centre\" or \"scanline\", not \"" + name + "\"");
}

PreviewMode parse_preview_mode(const std::string& name) {
  if (name == "anchor") return PreviewMode::Anchor;
  if (name == "area") return PreviewMode::Area;
  throw std::invalid_argument("preview must be \"anchor\" or \"area\", not \"" + name + "\"");
}

const char* to_string(UnitOrder order) {
  return order == UnitOrder::Centre ? "centre" : "scanline";
}
const char* to_string(PreviewMode mode) { return mode == PreviewMode::Anchor ? "anchor" : "area"; }

}  // namespace tessera
