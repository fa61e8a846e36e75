#include "worker/render_cli/options.h"

#include <algorithm>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "common/render/settings_schema.h"

namespace tessera {
namespace {

// What CLI11 shows after a flag that takes a value.
std::string value_name(const SettingSpec& spec) {
  switch (spec.type) {
    case SettingType::Integer:
      return "INT";
    case SettingType::Number:
      return "NUMBER";
    case SettingType::Seed:
      return "UINT";
    case SettingType::Choice: {
      std::string names;
      for (const std::string_view choice : spec.choices)
        names += (names.empty() ? "" : "|") + std::string(choice);
      return names;
    }
    case SettingType::Camera:
      return "EX EY EZ LX LY LZ UX UY UZ FOV";
    case SettingType::Boolean:
      break;
  }
  return {};
}

// The camera as ten values ("--camera 0 1 8 0 1 0 0 1 0 45"), checked once all are read.
void add_camera_setting(CLI::App& app, const SettingSpec& spec, JobSettings& settings) {
  app.add_option_function<std::vector<std::string>>(
         cli_flag(spec),
         [&spec, &settings](const std::vector<std::string>& numbers) {
           std::string text;
           for (const std::string& n : numbers) text += (text.empty() ? "" : " ") + n;
           const std::optional<SettingValue> value = setting_from_text(spec, text);
           const std::optional<std::string> error =
               value ? setting_error(spec, *value) : "must be ten numbers, " + value_name(spec);
           if (error)
             throw CLI::ValidationError(cli_flag(spec), "bad value '" + text + "': " + *error);
           spec.access.set(settings, *value);
         },
         std::string(spec.help) + " (default " + to_text(spec.default_value()) + ")")
      ->expected(10)
      ->type_name(value_name(spec));
}

// The setting as a flag: a Boolean sets the opposite of its default; any other checks its value
// against the schema ("--width: bad value '0': must be an integer in [1, 16384]").
void add_setting(CLI::App& app, const SettingSpec& spec, JobSettings& settings) {
  const std::string help(spec.help);
  if (spec.type == SettingType::Camera) return add_camera_setting(app, spec, settings);
  if (spec.type == SettingType::Boolean) {
    const bool set_to = !std::get<bool>(spec.default_value());
    app.add_flag_callback(
        cli_flag(spec), [&spec, &settings, set_to] { spec.access.set(settings, set_to); },
        set_to ? help : "turns off: " + help);
    return;
  }
  app.add_option_function<std::string>(
         cli_flag(spec),
         [&spec, &settings](const std::string& text) {
           spec.access.set(settings, *setting_from_text(spec, text));
         },
         help + " (default " + to_text(spec.default_value()) + ")")
      ->type_name(value_name(spec))
      ->check(CLI::Validator(
          [&spec](std::string& text) -> std::string {
            const std::optional<SettingValue> value = setting_from_text(spec, text);
            const std::optional<std::string> error =
                value ? setting_error(spec, *value) : "must be " + describe_values(spec);
            return error ? "bad value '" + text + "': " + *error : std::string();
          },
          describe_values(spec)));
}

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
  for (const SettingSpec& spec : settings_schema())
    if (spec.layers & kRenderCli) add_setting(*app, spec, settings);
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
