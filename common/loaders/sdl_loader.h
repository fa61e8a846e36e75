// The SDL loader (scene description language, `002_…` chapter 3).
#pragma once

#include <filesystem>
#include <string>

#include "common/loaders/load_budget.h"
#include "common/loaders/scene_source.h"
#include "common/scene/scene.h"

namespace tessera {

// Parses the SDL file at root-relative `path` of `source`, with its includes and meshes.
// Throws SceneError naming file, line, column and what was expected; LoadBudgetExceeded when
// the scene goes over `budget`.
Scene load_sdl(const SceneSource& source, const std::string& path, const LoadBudget& budget = {});

// Convenience for the command line: the scene's folder is the root.
Scene load_sdl_file(const std::filesystem::path& file, const LoadBudget& budget = {});

}  // namespace tessera
