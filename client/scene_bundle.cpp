#include "client/scene_bundle.h"

#include <stdexcept>

#include "common/loaders/recording_source.h"
#include "common/loaders/scene_loader.h"

namespace tessera {

SceneBundle bundle_scene(const std::filesystem::path& scene,
                         const std::optional<std::filesystem::path>& root, bool strict) {
  namespace fs = std::filesystem;
  const fs::path folder = root ? *root : scene.parent_path().empty() ? "." : scene.parent_path();
  const fs::path inside = fs::absolute(scene).lexically_normal().lexically_relative(
      fs::absolute(folder).lexically_normal());
  if (inside.empty() || *inside.begin() == "..")
    throw SceneError({scene.string(), 1, 1}, "the scene file is outside --root " + folder.string());
  const DirectorySource files(folder);
  const RecordingSource source(files);
  LoadBudget budget;
  budget.strict = strict;
  const SceneFormat format = scene_format_of(scene);
  SceneBundle out;
  out.bundle.main = inside.generic_string();
  out.bundle.format = format == SceneFormat::Vrml ? "vrml" : "sdl";
  out.warnings = load_scene(source, out.bundle.main, format, budget).warnings;
  out.bundle.files = source.files();
  return out;
}

std::string multipart_body(const Bundle& bundle, const std::string& settings_json,
                           std::string& boundary) {
  // A boundary that no part contains: derived from the content, lengthened until it is absent.
  boundary = "tessera-" + content_hash(bundle).substr(0, 24);
  const auto absent = [&] {
    if (settings_json.find(boundary) != std::string::npos) return false;
    for (const auto& [path, bytes] : bundle.files)
      if (bytes.find(boundary) != std::string::npos || path.find(boundary) != std::string::npos)
        return false;
    return true;
  };
  while (!absent()) boundary += "x";
  std::string body;
  const auto part = [&](const std::string& disposition, const std::string& data) {
    body += "--" + boundary + "\r\nContent-Disposition: form-data; " + disposition + "\r\n\r\n";
    body += data;
    body += "\r\n";
  };
  part("name=\"main\"", bundle.main);
  part("name=\"format\"", bundle.format);
  part("name=\"settings\"", settings_json);
  for (const auto& [path, bytes] : bundle.files) {
    if (path.find_first_of("\"\r\n") != std::string::npos)
      throw std::invalid_argument("the scene's file \"" + path +
                                  "\" has a quote or a line break in its name, which a form "
                                  "cannot carry");
    part("name=\"file\"; filename=\"" + path + "\"", bytes);
  }
  body += "--" + boundary + "--\r\n";
  return body;
}

}  // namespace tessera
