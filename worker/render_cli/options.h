// Command-line options of tessera-render.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "common/render/settings.h"

namespace tessera {

enum class DebugView { None, Normals, Cost };  // common/render/debug_views.h

struct RenderCliOptions {
  std::string scene_path;
  std::string output_path;
  RenderSettings settings;
  int threads = 0;  // 0: all cores
  bool quiet = false;
  bool strict = false;  // what lenient loading warns about is an error (LoadBudget::strict)
  std::string root;     // non-empty: the scene's paths must stay inside this folder
  DebugView debug_view = DebugView::None;
};

struct CliHelp {};  // --help was asked for

// Parses argv; returns the options, CliHelp, or an error message naming the bad argument.
std::variant<RenderCliOptions, CliHelp, std::string> parse_render_cli(
    const std::vector<std::string>& args);

extern const char* const kRenderCliUsage;

}  // namespace tessera
