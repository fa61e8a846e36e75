// The scene formats and the one entry point that picks the loader: SDL or VRML.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "common/loaders/load_budget.h"
#include "common/loaders/scene_source.h"
#include "common/scene/scene.h"

namespace tessera {

enum class SceneFormat { Sdl, Vrml };

// The format named "sdl" or "vrml" (a job's `format`), or nullopt.
std::optional<SceneFormat> scene_format_named(std::string_view name);

// The format a file name implies: VRML for .wrl, .wrl.gz and .wrz, SDL otherwise.
SceneFormat scene_format_of(const std::filesystem::path& file);

// Loads the scene at root-relative `path` of `source` with the loader of `format`, all of its
// files together within `budget`. Throws SceneError naming file, line and column;
// LoadBudgetExceeded (a SceneError) naming the limit the scene went over, or the deadline.
// A `camera` (a job's camera setting, SceneOverrides::camera) replaces the scene's, its
// view_angle read as the format's own angle; the scene is then what the file edited to that
// camera gives, bit for bit.
Scene load_scene(const SceneSource& source, const std::string& path, SceneFormat format,
                 const LoadBudget& budget = {}, const std::optional<Camera>& camera = std::nullopt);

// For the command line: the file's name picks the format. Without `root`, the paths the scene
// names resolve against the folder of the file that names them, wherever they lead; with it,
// they must stay inside `root` (and so must `file`).
Scene load_scene_file(const std::filesystem::path& file, const LoadBudget& budget = {},
                      const std::optional<std::filesystem::path>& root = std::nullopt,
                      const std::optional<Camera>& camera = std::nullopt);

}  // namespace tessera
