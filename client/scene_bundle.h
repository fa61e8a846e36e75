// The scene file and every file it reads (includes, meshes, textures, Inlines), as a bundle to
// submit: the loaders report what they read (common/loaders/recording_source.h), so the bundle
// holds exactly what the coordinator's own load of it will ask for.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/protocol/bundle.h"

namespace tessera {

struct SceneBundle {
  Bundle bundle;
  std::vector<std::string> warnings;  // of the local load, as tessera-render prints them
};

// Loads `scene` (its name picks SDL or VRML) from the folder `root` (default: the scene's own
// folder); every file it names must lie inside that folder, since the bundle keys files by
// their paths relative to it. Throws SceneError naming file, line and column.
SceneBundle bundle_scene(const std::filesystem::path& scene,
                         const std::optional<std::filesystem::path>& root, bool strict);

// The bundle as a multipart/form-data body (docs/SERVICE.md): fields main, format and settings
// (JSON), and each file as a `file` part named by its bundle path. Returns the body; `boundary`
// receives the boundary for the Content-Type.
std::string multipart_body(const Bundle& bundle, const std::string& settings_json,
                           std::string& boundary);

}  // namespace tessera
