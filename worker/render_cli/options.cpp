#include "worker/render_cli/options.h"

#include <algorithm>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "common/settings/settings_schema.h"
#include "worker/render_cli/setting_flags.h"

namespace tessera {
namespace {

// tessera-render's command line, writing into `o` and `settings` as it parses.
std::unique_ptr<CLI::App> make_app(RenderCliOptions& o, JobSettings& settings) {
  auto app = std::make_unique<CLI::App>(
      "tessera-render: renders a scene file to an image on this machine (README.md)",
      "tessera-render");
  app->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app->add_option("scene", o.scene_path, "the scene: SCENE.sdl, or WORLD.wrl, .wrl.gz, .wrz")
      ->type_name("SCENE");
  app->add_option("-o", o.output_path, "the image: .exr keeps floats, .png clamps to [0, 1]")
      ->type_name("OUT");
  add_setting_flags(*app, settings, kRenderCli);
  app->add_option("--threads", o.threads, "threads (default: all cores)")
      ->check(CLI::Range(0, 1024));
  app->add_option_function<std::string>(
         "--debug-view",
         [&o](const std::string& view) {
           o.debug_view = view == "normals" ? DebugView::Normals : DebugView::Cost;
         },
         "writes a debug view instead of the render: normals (the first hit's shading normal as "
         "colour) or cost (intersection tests per pixel)")
      ->check(CLI::IsMember({"normals", "cost"}))
      ->type_name("normals|cost");
  app->add_flag("--quiet", o.quiet, "no progress or statistics");
  app->add_option("--root", o.root,
                  "the files the scene names must lie inside DIR (default: any file, relative "
                  "paths against the naming file's folder)")
      ->type_name("DIR");
  return app;
}

}  // namespace

std::variant<RenderCliOptions, CliHelp, std::string> parse_render_cli(
    const std::vector<std::string>& args) {
  RenderCliOptions o;
  JobSettings settings;
  const std::unique_ptr<CLI::App> app = make_app(o, settings);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // as CLI11 reads them
  try {
    app->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return CliHelp{};
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  if (o.scene_path.empty()) return std::string("no scene file given");
  if (o.output_path.empty()) return std::string("no output file given (-o OUT.png)");
  if (const std::optional<std::string> error = settings_error(settings.render))
    return "--" + *error;
  o.settings = settings.render;
  o.camera = settings.overrides.camera;
  o.strict = settings.load.strict;
  return o;
}

std::string render_cli_usage() {
  RenderCliOptions o;
  JobSettings settings;
  return make_app(o, settings)->help();
}

}  // namespace tessera
