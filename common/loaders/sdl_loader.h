// The SDL loader (scene description language, `002_…` chapter 3).
#pragma once

#include <filesystem>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/scene/scene.h"

namespace tessera {

// Parses the SDL file at root-relative `path` of `source`, with its includes and meshes.
// Throws SceneError naming file, line, column and what was expected.
Scene load_sdl(const SceneSource& source, const std::string& path);

// Convenience for the command line: the scene's folder is the root.
Scene load_sdl_file(const std::filesystem::path& file);

}  // namespace tessera
