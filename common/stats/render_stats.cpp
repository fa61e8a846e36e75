#include "common/stats/render_stats.h"

namespace tessera {

RenderStats& RenderStats::operator+=(const RenderStats& o) {
  camera_rays += o.camera_rays;
  shadow_rays += o.shadow_rays;
  reflection_rays += o.reflection_rays;
  refraction_rays += o.refraction_rays;
  intersections.shape_tests += o.intersections.shape_tests;
  intersections.triangle_tests += o.intersections.triangle_tests;
  intersections.bvh_nodes += o.intersections.bvh_nodes;
  pixels += o.pixels;
  samples += o.samples;
  nan_samples += o.nan_samples;
  ray_budget_pixels += o.ray_budget_pixels;
  seconds += o.seconds;
  return *this;
}

}  // namespace tessera
