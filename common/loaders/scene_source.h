// Where a scene's files come from. Loaders never touch the file system directly: the CLI reads
// a folder, the service reads a submitted bundle, tests read memory. Every path a scene names
// (include, mesh, image texture) is resolved relative to the file that names it and must stay
// inside the source's root; anything else is refused.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace tessera {

class SceneSource {
 public:
  virtual ~SceneSource() = default;
  // The bytes of the file at `path`, a normalized path relative to the root (as returned by
  // resolve_scene_path), or nullopt when there is no such file.
  virtual std::optional<std::string> read(const std::string& path) const = 0;
};

// Resolves `name`, written in the file at root-relative `from_file`, to a normalized
// root-relative path ("a/b/c.obj"). Nullopt when it is absolute or climbs out of the root.
std::optional<std::string> resolve_scene_path(const std::string& from_file,
                                              const std::string& name);

// Files under a folder on disk. Symbolic links that lead outside the folder are refused.
class DirectorySource : public SceneSource {
 public:
  explicit DirectorySource(std::filesystem::path root);
  std::optional<std::string> read(const std::string& path) const override;

 private:
  std::filesystem::path root_;
};

// The folder that holds `file` ("." for a bare file name), for the command line.
DirectorySource folder_of(const std::filesystem::path& file);

// Files held in memory, keyed by root-relative path (tests, bundles).
class MemorySource : public SceneSource {
 public:
  MemorySource() = default;
  explicit MemorySource(std::map<std::string, std::string> files) : files_(std::move(files)) {}
  void add(const std::string& path, std::string bytes) { files_[path] = std::move(bytes); }
  std::optional<std::string> read(const std::string& path) const override;

 private:
  std::map<std::string, std::string> files_;
};

}  // namespace tessera
