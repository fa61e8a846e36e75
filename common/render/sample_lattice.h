// The regular samples of neighbouring pixels (§4.4) meet: a pixel's corners and edge midpoints
// are its neighbours' corners and edge midpoints too. All of them lie on the lattice of half
// pixels, so a rectangle of pixels needs (2w + 1)(2h + 1) lattice points, not 9wh samples.
// Where a sample's value depends on its position alone (samples_depend_on_position_only), each
// point is traced once and shared by the pixels whose grids meet there: the 3x3 grid then costs
// a little over 4 rays a pixel and the 5-point one a little over 2, and every pixel's value is
// the same, bit for bit, as when it traces its own samples (the same rays, added in the same
// order).
#pragma once

#include <cstdint>
#include <vector>

#include "common/math/pixel_rect.h"
#include "common/progressive/plan.h"
#include "common/render/effects.h"
#include "common/render/pixel_samples.h"
#include "common/scene/rgb.h"
#include "common/settings/render_settings.h"

namespace tessera {

// Whether a camera sample's value is a function of its position in the image alone: no jitter,
// and no effect that draws random numbers (keyed by pixel and sample) or a time per sample.
// `effects` are the render's (render_effects).
inline bool samples_depend_on_position_only(const EffectSet& effects,
                                            const RenderSettings& settings) {
  return !settings.stochastic && !effects.has(Effect::MotionBlur) &&
         !effects.has(Effect::SurfaceRoughness) && !effects.has(Effect::Gloss) &&
         !effects.has(Effect::Translucency) && !effects.has(Effect::SoftShadows);
}

// Whether render_pixels shares the samples of `pixels` pixels whose bounds hold `bounds_area`:
// with more than one sample a pixel, where they fill at least half their bounds (a unit of
// sparse anchors shares no sample and would only pay for the lattice's memory).
inline bool worth_a_lattice(long long pixels, long long bounds_area, int aa) {
  return aa > 1 && 2 * pixels >= bounds_area;
}

// Camera rays render_pixels traces for `unit` at `aa` samples a pixel when samples are shared:
// the lattice points its pixels' grids need, or aa a pixel where it shares none. The finest
// level's units skip the coarser anchors (one pixel in four), whose centres alone no
// neighbour needs.
long long shared_unit_rays(const UnitPixels& unit, int aa);

// The share of their samples the traced pixels of a plan with `passes` passes trace themselves
// when samples are shared (the rest their neighbours trace): what scales a probe of lone
// pixels, which share nothing, to the plan. `first_two` is the plan made with at most two
// passes; every pass after the first is laid out as the second.
double traced_share(const Plan& first_two, int passes, int aa);

class SampleLattice {
 public:
  // The lattice under the sample grids of `pixels`, which must hold (x, y) of every pixel
  // whose samples are asked for.
  explicit SampleLattice(const PixelRect& pixels)
      : x0_(pixels.x0),
        y0_(pixels.y0),
        columns_(2 * pixels.width() + 1),
        values_(static_cast<std::size_t>(columns_) * (2 * pixels.height() + 1)),
        traced_(values_.size(), false) {}

  // Pixel (x, y)'s sample at `offset` (half-pixel multiples): trace(px, py) the first time any
  // pixel asks for that point, the stored value after.
  template <class Trace>
  const Rgb& at(int x, int y, const SampleOffset& offset, Trace&& trace) {
    const auto column = static_cast<std::size_t>(2 * (x - x0_) + static_cast<int>(2 * offset.dx));
    const auto row = static_cast<std::size_t>(2 * (y - y0_) + static_cast<int>(2 * offset.dy));
    const std::size_t i = row * static_cast<std::size_t>(columns_) + column;
    if (!traced_[i]) {
      values_[i] = trace(x + offset.dx, y + offset.dy);
      traced_[i] = true;
    }
    return values_[i];
  }

 private:
  int x0_, y0_;
  int columns_;
  std::vector<Rgb> values_;
  std::vector<bool> traced_;
};

}  // namespace tessera
