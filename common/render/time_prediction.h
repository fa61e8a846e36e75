// Predicting a render's time before it starts (issue 5): trace a small, spread-out probe of
// pixels with the job's settings, then scale the measured cost per pixel to the whole job
// and the worker threads available.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/settings/render_settings.h"

namespace tessera {

struct CostProbe {
  long long pixels = 0;  // pixels traced (one pass each)
  double seconds = 0;    // the CPU time they took on the probing thread
  // The probe's deadline (ProbeBudget::max_total_seconds) stopped it inside a pixel. `pixels`
  // and `seconds` then count every pixel finished since the probe began, warm-up included, and
  // the thread's CPU time until the deadline, spent on those and on one more unfinished pixel.
  bool cut_short = false;
  // Seconds a pixel pass takes on one thread: the mean over the pixels traced; when cut short,
  // a lower bound, counting the unfinished pixel as if it had just finished.
  double seconds_per_pixel_pass() const {
    const long long counted = pixels + (cut_short ? 1 : 0);
    return counted > 0 ? seconds / double(counted) : 0;
  }
};

struct ProbeBudget {
  int max_pixels = 1024;      // a 32 x 32 grid over the image
  double max_seconds = 0.03;  // stop early on costly scenes (keeps submission quick)
  // The whole probe, warm-up included, stops at this many wall seconds even inside a pixel (a
  // scene with one pixel of runaway cost).
  double max_total_seconds = 0.5;
};

// The probe's pixels: centres of a grid of about max_pixels cells, in an order in which every
// prefix is spread over the whole image.
std::vector<PixelCoord> probe_pixel_order(int width, int height, int max_pixels);

// Traces pass 0 of up to budget.max_pixels pixels on the calling thread, in the order
// above, so stopping early still samples all of the image; untimed warm-up pixels first.
CostProbe probe_render_cost(const PreparedScene& scene, const RenderSettings& settings,
                            const ProbeBudget& budget = {});

// Wall seconds for `pixel_passes` traced pixel passes at `seconds_per_pixel_pass` each, shared
// by `threads` worker threads; nothing when there is no thread to run them.
std::optional<double> predict_render_seconds(double seconds_per_pixel_pass, long long pixel_passes,
                                             int threads);

}  // namespace tessera
