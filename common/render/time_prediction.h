// Predicting a render's time before it starts (issue 5): trace a small, spread-out probe of
// pixels with the job's settings, then scale the measured cost per pixel to the whole job
// and the worker threads available.
#pragma once

#include <optional>
#include <vector>

#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/render/settings.h"

namespace tessera {

struct CostProbe {
  long long pixels = 0;  // pixels traced (one pass each)
  double seconds = 0;    // time they took on one thread
  double seconds_per_pixel_pass() const { return pixels > 0 ? seconds / double(pixels) : 0; }
};

struct ProbeBudget {
  int max_pixels = 256;       // a 16 x 16 grid over the image
  double max_seconds = 0.03;  // stop early on costly scenes (keeps submission quick)
};

// The probe's pixels: centres of a grid of about max_pixels cells, in an order in which every
// prefix is spread over the whole image.
std::vector<PixelCoord> probe_pixel_order(int width, int height, int max_pixels);

// Traces pass 0 of up to budget.max_pixels pixels on the calling thread, in the order
// above, so stopping early still samples all of the image.
CostProbe probe_render_cost(const PreparedScene& scene, const RenderSettings& settings,
                            const ProbeBudget& budget = {});

// Wall seconds for `pixel_passes` traced pixel passes at `seconds_per_pixel_pass` each, shared
// by `threads` worker threads; nothing when there is no thread to run them.
std::optional<double> predict_render_seconds(double seconds_per_pixel_pass, long long pixel_passes,
                                             int threads);

// Learns how the workers' real time relates to the probe's prediction: their speed against
// the probing machine's, how well their threads scale, the service's own overhead. Each
// finished job that ran alone moves the factor halfway (geometrically) towards its
// actual / predicted ratio, clamped to [1/4, 4] so that one odd job cannot wreck it.
class PredictionCalibration {
 public:
  double factor() const { return factor_; }
  double apply(double predicted_seconds) const { return predicted_seconds * factor_; }
  void observe(double uncalibrated_seconds, double actual_seconds);

 private:
  double factor_ = 1;
};

}  // namespace tessera
