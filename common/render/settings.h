// How to render: the accuracy knobs users set per render (CLI flags, job settings).
#pragma once

#include <cstdint>

#include "common/accel/bvh.h"
#include "common/scene/motion.h"  // kMaxTimeSamples

namespace tessera {

struct RenderSettings {
  int width = 640;
  int height = 480;
  int aa_samples = 1;       // 1, 5 or 9 samples per pixel per pass (§4.4)
  bool stochastic = false;  // jitter the sample positions (§4.4.2)
  double jitter = 1.0;      // jitter strength, in pixels (eq. 4.52 with block size 1)
  std::uint64_t seed = 0;   // keys every random number (render/sampler.h)
  int passes = 1;           // sample passes; the image is the mean of all passes
  int time_samples = 0;     // motion-blur times per camera sample (1..kMaxTimeSamples); 0: the
                            // scene's motionBlur count
  BvhMode bvh = BvhMode::Sah;
};

}  // namespace tessera
