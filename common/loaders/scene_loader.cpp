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
                 const LoadBudget& budget) {
  return format == SceneFormat::Vrml ? load_vrml(source, path, budget)
                                     : load_sdl(source, path, budget);
}

Scene load_scene_file(const std::filesystem::path& file, const LoadBudget& budget) {
  return load_scene(folder_of(file), file.filename().string(), scene_format_of(file), budget);
}

}  // namespace tessera
