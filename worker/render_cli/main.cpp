// tessera-render: renders a scene file to an image on this machine, with all cores.
#include <cstdio>
#include <ctime>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "common/loaders/scene_loader.h"
#include "common/render/debug_views.h"
#include "common/render/render.h"
#include "worker/render_cli/options.h"
#include "worker/render_cli/progress.h"
#include "worker/render_cli/report.h"

int main(int argc, char** argv) {
  using namespace tessera;
  const auto parsed = parse_render_cli(std::vector<std::string>(argv + 1, argv + argc));
  if (std::holds_alternative<CliHelp>(parsed)) {
    std::fputs(render_cli_usage().c_str(), stdout);
    return 0;
  }
  if (const auto* error = std::get_if<std::string>(&parsed)) {
    std::fprintf(stderr, "tessera-render: %s (tessera-render --help lists the options)\n",
                 error->c_str());
    return 2;
  }
  const auto& options = std::get<RenderCliOptions>(parsed);
  try {
    LoadBudget budget;
    budget.strict = options.strict;
    const Scene scene = load_scene_file(
        options.scene_path, budget,
        options.root.empty() ? std::nullopt : std::optional<std::filesystem::path>(options.root),
        options.camera);
    // The BVH build uses the render's threads (all cores when --threads is 0).
    const int threads = options.threads > 0 ? options.threads
                                            : static_cast<int>(std::thread::hardware_concurrency());
    const PreparedScene prepared(scene, options.settings.bvh, threads);
    if (!options.quiet) print_warnings(scene, prepared);
    if (options.debug_view != DebugView::None) {
      std::uint64_t largest = 0;
      write_image(options.debug_view == DebugView::Normals
                      ? render_normals(prepared, options.settings)
                      : render_cost(prepared, options.settings, largest),
                  options.output_path);
      if (!options.quiet && options.debug_view == DebugView::Cost)
        std::printf("wrote %s: white is %llu intersection tests a pixel\n",
                    options.output_path.c_str(), static_cast<unsigned long long>(largest));
      return 0;
    }
    TerminalProgress progress;
    RenderStats stats;
    const std::clock_t cpu_start = std::clock();
    const Image image = render_image(
        prepared, options.settings, options.threads, stats,
        options.quiet ? ProgressFn{}
                      : ProgressFn{[&](long long d, long long t) { progress.update(d, t); }});
    const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    progress.finish();
    write_image(image, options.output_path);
    if (!options.quiet)
      print_report(prepared, options.settings, stats, cpu_seconds, options.output_path);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera-render: %s\n", e.what());
    return 1;
  }
}
