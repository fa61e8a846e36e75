#include "client/submit_options.h"

#include <memory>

#include <CLI/CLI.hpp>

#include "common/protocol/job_spec.h"
#include "worker/render_cli/setting_flags.h"

namespace tessera {
namespace {

std::unique_ptr<CLI::App> make_app(SubmitOptions& o) {
  auto app = std::make_unique<CLI::App>(
      "tessera-submit: renders a scene file on a Tessera coordinator, with the files it "
      "includes, and downloads the image (docs/SERVICE.md)",
      "tessera-submit");
  app->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app->add_option("scene", o.scene_path, "the scene: SCENE.sdl, or WORLD.wrl, .wrl.gz, .wrz")
      ->type_name("SCENE");
  app->add_option("--coordinator", o.coordinator, "the coordinator's HTTP or HTTPS address")
      ->type_name("http[s]://HOST:PORT");
  app->add_option_function<std::string>(
         "--tls-ca", [&o](const std::string& ca) { o.tls.ca = ca; },
         "for https: trust these certificates (PEM) instead of the system's")
      ->type_name("FILE")
      ->check(CLI::ExistingFile);
  app->add_option("-o", o.output_path,
                  "writes the image: .exr keeps floats, .png clamps to [0, 1] (default: none; "
                  "the job stays on the coordinator)")
      ->type_name("OUT");
  app->add_option("--token", o.token, "the coordinator's API token (its --api-token)")
      ->type_name("T");
  app->add_option("--root", o.root,
                  "the folder the scene's files are sent relative to; every file the scene names "
                  "must lie inside it (default: the scene's folder)")
      ->type_name("DIR");
  app->add_flag("--quiet", o.quiet, "no progress, only errors");
  add_setting_flags(*app, o.settings, kJobRequest);
  return app;
}

}  // namespace

std::variant<SubmitOptions, SubmitHelp, std::string> parse_submit_cli(
    const std::vector<std::string>& args) {
  SubmitOptions o;
  const std::unique_ptr<CLI::App> app = make_app(o);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // as CLI11 reads them
  try {
    app->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return SubmitHelp{};
  } catch (const CLI::ParseError& e) {
    return std::string(e.what());
  }
  if (o.scene_path.empty()) return std::string("no scene file given");
  if (o.coordinator.empty()) return std::string("no coordinator given (--coordinator URL)");
  if (!o.output_path.empty() && !o.output_path.ends_with(".exr") &&
      !o.output_path.ends_with(".png"))
    return "-o " + o.output_path + ": the image must be .exr or .png";
  if (const std::optional<std::string> error = settings_error(o.settings.render))
    return "--" + *error;
  return o;
}

std::string submit_cli_usage() {
  SubmitOptions o;
  return make_app(o)->help();
}

std::string settings_json(const JobSettings& settings) {
  nlohmann::json j = nlohmann::json::object();
  for (const SettingSpec& spec : settings_schema()) {
    if (!(spec.layers & kJobRequest)) continue;
    const SettingValue value = spec.access.get(settings);
    if (value != spec.default_value()) j[std::string(spec.name)] = setting_to_json(value);
  }
  return j.dump();
}

}  // namespace tessera
