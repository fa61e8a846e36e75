#include "common/loaders/scene_loader.h"

#include "common/loaders/lexical.h"
#include "common/loaders/sdl_loader.h"
#include "common/loaders/vrml_loader.h"

namespace tessera {

std::optional<SceneFormat> scene_format_named(std::string_view name) {
  if (name == "sdl") return SceneFormat::Sdl;
  if (name == "vrml") return SceneFormat::Vrml;
  return std::nullopt;
}

SceneFormat scene_format_of(const std::filesystem::path& file) {
  const std::string name = to_lower(file.filename().string());
  for (const std::string_view ending : {".wrl", ".wrl.gz", ".wrz"})
    if (name.ends_with(ending)) return SceneFormat::Vrml;
  return SceneFormat::Sdl;
}

Scene load_scene(const SceneSource& source, const std::string& path, SceneFormat format,
                 const LoadBudget& budget, const std::optional<Camera>& camera) {
  if (format == SceneFormat::Vrml) return load_vrml(source, path, budget, camera);
  Scene scene = load_sdl(source, path, budget);
  if (camera) {  // nothing an SDL scene loads depends on its camera
    scene.camera = *camera;
    scene.camera.view_angle_on_smaller_side = false;
  }
  return scene;
}

Scene load_scene_file(const std::filesystem::path& file, const LoadBudget& budget,
                      const std::optional<std::filesystem::path>& root,
                      const std::optional<Camera>& camera) {
  namespace fs = std::filesystem;
  const SceneFormat format = scene_format_of(file);
  if (!root) {
    const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    return load_scene(DirectorySource(folder, /*confined=*/false), file.filename().string(), format,
                      budget, camera);
  }
  const fs::path inside = fs::absolute(file).lexically_normal().lexically_relative(
      fs::absolute(*root).lexically_normal());
  if (inside.empty() || *inside.begin() == "..")
    throw SceneError({file.string(), 1, 1}, "the scene file is outside --root " + root->string());
  return load_scene(DirectorySource(*root), inside.generic_string(), format, budget, camera);
}

}  // namespace tessera
