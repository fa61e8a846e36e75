// The tracer's entry points, shaped like the work (docs/ARCHITECTURE.md): the CLI, the worker and
// the tests all call these, with no global state.
//
// A pixel's value depends only on the prepared scene, the settings, the pixel and the pass:
// never on the rectangle, thread or host that computes it (render/sampler.h).
//
// Every entry point takes an optional RenderInterrupt (render/interrupt.h): when its cancel
// flag is set or its deadline passes, the render stops within milliseconds, even inside a
// pixel, and throws RenderInterrupted; nothing of the unfinished pixels is returned. Each pixel
// sample is also bounded by Tracer::kMaxRaysPerSample rays (render/tracer.h), counted in
// RenderStats::ray_budget_pixels, so a pixel's cost has a ceiling whatever the scene.
#pragma once

#include <functional>
#include <span>

#include "common/image/image.h"
#include "common/math/pixel_rect.h"
#include "common/render/interrupt.h"
#include "common/render/prepared_scene.h"
#include "common/settings/render_settings.h"
#include "common/stats/render_stats.h"

namespace tessera {

// The effects a render simulates: the scene's, plus anti-aliasing when the settings ask for
// more than one sample per pixel; the shadow mode turns hard shadows off or into soft ones;
// gloss and translucency need cones of more than one ray.
EffectSet render_effects(const PreparedScene& scene, const RenderSettings& settings);

// Traces one sample pass (settings.aa_samples samples per pixel) of the pixels of `rect` on
// the calling thread; out[(y - y0) * width + (x - x0)] receives the pass's mean colour.
// Adds to `stats` (rays, tests, samples; not seconds).
void render_pass(const PreparedScene& scene, const RenderSettings& settings, const PixelRect& rect,
                 int pass, std::span<Rgb> out, RenderStats& stats,
                 const RenderInterrupt& interrupt = {});

// Traces the listed pixels (x, y) of one pass, for the progressive scheduler whose units are
// sparse anchors; same values as render_pass.
void render_pixels(const PreparedScene& scene, const RenderSettings& settings,
                   std::span<const PixelCoord> pixels, int pass, std::span<Rgb> out,
                   RenderStats& stats, const RenderInterrupt& interrupt = {});

// Renders the whole image, or only settings.region in a full-size frame that is black
// elsewhere, with `threads` threads (0 = all cores): settings.passes passes, averaged, then
// post-normalized when the settings ask for it (§4.6). `progress(done, total)` is
// called from worker threads with counts of tiles.
using ProgressFn = std::function<void(long long done, long long total)>;
Image render_image(const PreparedScene& scene, const RenderSettings& settings, int threads,
                   RenderStats& stats, const ProgressFn& progress = {},
                   const RenderInterrupt& interrupt = {});

}  // namespace tessera
