// Whole-image renders of the sample scenes, single-threaded so that figures compare across
// machines; the BVH against brute force (the seeds' "acceleration off").
#include <benchmark/benchmark.h>

#include "common/loaders/sdl_loader.h"
#include "common/render/render.h"

namespace tessera {
namespace {

void render_scene(benchmark::State& state, const char* relative_path, BvhMode mode, int aa) {
  const Scene scene = load_sdl_file(std::string(TESSERA_SOURCE_DIR) + "/scenes/" + relative_path);
  const PreparedScene prepared(scene, mode);
  RenderSettings settings;
  settings.width = 320;
  settings.height = 240;
  settings.aa_samples = aa;
  settings.bvh = mode;
  RenderStats stats;
  for (auto _ : state) benchmark::DoNotOptimize(render_image(prepared, settings, 1, stats));
  const double renders = static_cast<double>(state.iterations());
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(stats.camera_rays + stats.shadow_rays +
                                             stats.reflection_rays + stats.refraction_rays) /
                             renders,
                         benchmark::Counter::kIsIterationInvariantRate);
  state.counters["tests_per_pixel"] =
      static_cast<double>(stats.intersections.shape_tests + stats.intersections.triangle_tests) /
      (renders * settings.width * settings.height);
}

BENCHMARK_CAPTURE(render_scene, demo_bvh, "demo.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, demo_no_bvh, "demo.sdl", BvhMode::None, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, demo_aa5, "demo.sdl", BvhMode::Sah, 5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, mesh_bvh, "features/mesh.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, mesh_no_bvh, "features/mesh.sdl", BvhMode::None, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, textures, "features/textures.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, image_texture, "features/image_texture.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, csg, "features/csg.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(render_scene, torus, "features/torus.sdl", BvhMode::Sah, 1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tessera
