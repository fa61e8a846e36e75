// Render statistics: rays by kind and intersection work, summed over threads and units.
#pragma once

#include <cstdint>

#include "common/stats/intersection_counters.h"

namespace tessera {

struct RenderStats {
  std::uint64_t camera_rays = 0;
  std::uint64_t shadow_rays = 0;
  std::uint64_t reflection_rays = 0;
  std::uint64_t refraction_rays = 0;
  IntersectionCounters intersections;
  std::uint64_t pixels = 0;
  std::uint64_t samples = 0;
  std::uint64_t nan_samples = 0;  // samples that came out NaN or infinite (counted, then zeroed)
  // Pixels with a sample that spent its ray budget (Tracer::kMaxRaysPerSample), whose later
  // cones were narrowed to their central rays.
  std::uint64_t ray_budget_pixels = 0;
  double seconds = 0;  // wall time of the render or unit

  RenderStats& operator+=(const RenderStats& o);
};

}  // namespace tessera
