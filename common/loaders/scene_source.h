// Where a scene's files come from. Loaders never touch the file system directly: the CLI reads
// a folder, the service reads a submitted bundle, tests read memory. Every path a scene names
// (include, mesh, image texture, Inline) is resolved relative to the file that names it. A
// source may confine the scene to its root (a bundle, `--root DIR`): then a path that leads
// out of it is refused, with another message than a file that is missing. The command line
// without `--root` reads whatever its user can read.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace tessera {

class SceneSource {
 public:
  virtual ~SceneSource() = default;
  // The bytes of the file at `path`, as returned by resolve_scene_path, or nullopt when there
  // is no such file or the source does not admit it.
  virtual std::optional<std::string> read(const std::string& path) const = 0;
  // Whether `path` lies inside the root this source confines scenes to, so that a read that
  // failed means a missing file. By default: relative and not climbing out ("../").
  virtual bool admits(const std::string& path) const;
};

// Resolves `name`, written in the file at `from_file`, to a lexically normalized path
// ("a/b/c.obj"): relative to the root, or climbing out of it ("../t/y.jpg"), or absolute when
// `name` is. Nullopt for an empty name, a NUL byte, or a name that resolves to the root itself.
// Whether the file may be read is the source's to say (SceneSource::admits).
std::optional<std::string> resolve_scene_path(const std::string& from_file,
                                              const std::string& name);

// Why `source` has no file at `path`, for a message after the path: "is outside the scene's
// root" or "not found".
std::string why_unreadable(const SceneSource& source, const std::string& path);

// Files on disk, resolved against a folder. Confined: only files under the folder, symbolic
// links that lead outside it refused. Not confined: any path the process can read, relative
// ones against the folder.
class DirectorySource : public SceneSource {
 public:
  explicit DirectorySource(std::filesystem::path root, bool confined = true);
  std::optional<std::string> read(const std::string& path) const override;
  bool admits(const std::string& path) const override;

 private:
  std::filesystem::path root_;
  bool confined_;
};

// The folder that holds `file` ("." for a bare file name), confined to it.
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
