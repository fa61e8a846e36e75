// Command line of tessera-render (CLI11): the scene, -o OUT, the render settings of
// common/settings/settings_schema.h as flags (their help and ranges come from it), and the
// options of this program alone (--threads, --debug-view, --quiet).
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "common/settings/render_settings.h"

namespace tessera {

enum class DebugView { None, Normals, Cost };  // common/render/debug_views.h

struct RenderCliOptions {
  std::string scene_path;
  std::string output_path;
  RenderSettings settings;
  std::optional<Camera> camera;  // --camera: replaces the scene's (load_scene)
  int threads = 0;               // 0: all cores
  bool quiet = false;
  bool strict = false;  // what lenient loading warns about is an error (LoadBudget::strict)
  std::string root;     // non-empty: the scene's paths must stay inside this folder
  DebugView debug_view = DebugView::None;
};

struct CliHelp {};  // --help was asked for

// Parses the arguments after the program's name; returns the options, CliHelp, or an error
// message naming the bad flag and value.
std::variant<RenderCliOptions, CliHelp, std::string> parse_render_cli(
    const std::vector<std::string>& args);

// The help: usage, the settings with their ranges and defaults, the other options.
std::string render_cli_usage();

}  // namespace tessera
