#include "worker/render_cli/report.h"

#include <cstdio>

#include "common/render/render.h"
#include "common/render/tracer.h"

namespace tessera {

void print_warnings(const Scene& scene, const PreparedScene& prepared) {
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  for (const std::string& w : prepared.unsupported())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
}

void print_report(const PreparedScene& prepared, const RenderSettings& settings,
                  const RenderStats& stats, double cpu_seconds, const std::string& output_path) {
  std::string effects;
  for (const std::string& name : render_effects(prepared, settings).names())
    effects += (effects.empty() ? "" : ", ") + name;
  std::printf("wrote %s (%dx%d)\n", output_path.c_str(), settings.width, settings.height);
  std::printf("effects: %s\n", effects.empty() ? "none" : effects.c_str());
  std::printf("time: %.3f s\n", stats.seconds);
  // The render's wall time above includes whatever else ran on its cores: on a shared machine
  // one thread's render of the demo took 0.174-0.269 s while its CPU time stayed at 0.174-0.176 s
  // (docs/PERFORMANCE.md, "Where the one-thread render time goes").
  std::printf("cpu: %.3f s\n", cpu_seconds);
  std::printf("rays: camera %llu, shadow %llu, reflection %llu, refraction %llu\n",
              static_cast<unsigned long long>(stats.camera_rays),
              static_cast<unsigned long long>(stats.shadow_rays),
              static_cast<unsigned long long>(stats.reflection_rays),
              static_cast<unsigned long long>(stats.refraction_rays));
  std::printf("tests: shapes %llu, triangles %llu, bvh nodes %llu\n",
              static_cast<unsigned long long>(stats.intersections.shape_tests),
              static_cast<unsigned long long>(stats.intersections.triangle_tests),
              static_cast<unsigned long long>(stats.intersections.bvh_nodes));
  if (stats.nan_samples > 0)
    std::printf("warning: %llu samples were not finite and were written as black\n",
                static_cast<unsigned long long>(stats.nan_samples));
  if (stats.ray_budget_pixels > 0)
    std::printf(
        "warning: %llu pixels reached the ray budget of %llu rays a sample; their further cones "
        "were narrowed to their central rays\n",
        static_cast<unsigned long long>(stats.ray_budget_pixels),
        static_cast<unsigned long long>(Tracer::kMaxRaysPerSample));
}

}  // namespace tessera
