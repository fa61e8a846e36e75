#include "common/loaders/scene_source.h"

#include <fstream>
#include <system_error>
#include <vector>

namespace tessera {

// ---------------------------------------------------------------------------------------------
// Path resolution

std::optional<std::string> resolve_scene_path(const std::string& from_file,
                                              const std::string& name) {
  if (name.empty() || name.find('\0') != std::string::npos) return std::nullopt;
  const bool absolute = name.front() == '/' || (from_file.starts_with('/'));
  std::vector<std::string> parts;
  // Appends the segments of `text` to `parts`. ".." climbs out of a relative root and stays as
  // a segment; above "/" it stays at "/", as the file system has it.
  const auto append = [&](const std::string& text) {
    std::size_t begin = 0;
    while (begin <= text.size()) {
      std::size_t end = text.find('/', begin);
      if (end == std::string::npos) end = text.size();
      const std::string segment = text.substr(begin, end - begin);
      if (segment == "..") {
        if (!parts.empty() && parts.back() != "..") {
          parts.pop_back();
        } else if (!absolute) {
          parts.push_back(segment);
        }
      } else if (!segment.empty() && segment != ".") {
        parts.push_back(segment);
      }
      begin = end + 1;
    }
  };
  const std::size_t slash = from_file.rfind('/');
  if (name.front() != '/' && slash != std::string::npos) append(from_file.substr(0, slash));
  append(name);
  if (parts.empty()) return std::nullopt;
  std::string result = absolute ? "/" + parts.front() : parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) result += "/" + parts[i];
  return result;
}

bool SceneSource::admits(const std::string& path) const {
  return !path.empty() && path.front() != '/' && path != ".." && !path.starts_with("../");
}

std::string why_unreadable(const SceneSource& source, const std::string& path) {
  return source.admits(path) ? "not found" : "is outside the scene's root";
}

// ---------------------------------------------------------------------------------------------
// DirectorySource

DirectorySource::DirectorySource(std::filesystem::path root, bool confined)
    : root_(std::move(root)), confined_(confined) {}

bool DirectorySource::admits(const std::string& path) const {
  namespace fs = std::filesystem;
  if (!confined_) return true;
  if (path.empty() || fs::path(path).is_absolute()) return false;
  // "../root/a.sdl" goes out and back in: what counts is where it ends.
  const fs::path inside =
      (root_ / path).lexically_normal().lexically_relative(root_.lexically_normal());
  return !inside.empty() && *inside.begin() != "..";
}

std::optional<std::string> DirectorySource::read(const std::string& path) const {
  namespace fs = std::filesystem;
  if (path.empty() || path.find('\0') != std::string::npos) return std::nullopt;
  const fs::path relative(path);
  std::error_code ec;
  fs::path full;
  if (confined_) {
    if (relative.is_absolute() || relative.has_root_path()) return std::nullopt;
    const fs::path root = fs::canonical(root_, ec);
    if (ec) return std::nullopt;
    // canonical() follows every symbolic link, so a link that leads out of the root shows up
    // as a path outside it.
    full = fs::canonical(root / relative, ec);
    if (ec) return std::nullopt;
    const fs::path inside = full.lexically_relative(root);
    if (inside.empty() || inside == "." || *inside.begin() == "..") return std::nullopt;
  } else {
    full = root_ / relative;  // an absolute path replaces the root
  }
  if (!fs::is_regular_file(full, ec) || ec) return std::nullopt;
  std::ifstream in(full, std::ios::binary);
  if (!in) return std::nullopt;
  // In blocks, not a character at a time through istreambuf_iterator (a 10 MB mesh took 120 M
  // instructions to read that way).
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(fs::file_size(full, ec)));
  char block[1 << 16];
  while (in.read(block, sizeof block) || in.gcount() > 0)
    bytes.append(block, static_cast<std::size_t>(in.gcount()));
  if (in.bad()) return std::nullopt;
  return bytes;
}

// ---------------------------------------------------------------------------------------------
// MemorySource

std::optional<std::string> MemorySource::read(const std::string& path) const {
  const auto it = files_.find(path);
  if (it == files_.end()) return std::nullopt;
  return it->second;
}

DirectorySource folder_of(const std::filesystem::path& file) {
  std::filesystem::path root = file.parent_path();
  if (root.empty()) root = ".";
  return DirectorySource(root);
}

}  // namespace tessera
