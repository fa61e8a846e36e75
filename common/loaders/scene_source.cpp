#include "common/loaders/scene_source.h"

#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

namespace tessera {

// ---------------------------------------------------------------------------------------------
// Path resolution

std::optional<std::string> resolve_scene_path(const std::string& from_file,
                                              const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\0') != std::string::npos) {
    return std::nullopt;
  }
  std::vector<std::string> parts;
  // Appends the segments of `text` to `parts`; false when ".." climbs above the root.
  const auto append = [&parts](const std::string& text) {
    std::size_t begin = 0;
    while (begin <= text.size()) {
      std::size_t end = text.find('/', begin);
      if (end == std::string::npos) end = text.size();
      const std::string segment = text.substr(begin, end - begin);
      if (segment == "..") {
        if (parts.empty()) return false;
        parts.pop_back();
      } else if (!segment.empty() && segment != ".") {
        parts.push_back(segment);
      }
      begin = end + 1;
    }
    return true;
  };
  const std::size_t slash = from_file.rfind('/');
  if (slash != std::string::npos && !append(from_file.substr(0, slash))) return std::nullopt;
  if (!append(name) || parts.empty()) return std::nullopt;
  std::string result = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) result += "/" + parts[i];
  return result;
}

// ---------------------------------------------------------------------------------------------
// DirectorySource

DirectorySource::DirectorySource(std::filesystem::path root) : root_(std::move(root)) {}

std::optional<std::string> DirectorySource::read(const std::string& path) const {
  namespace fs = std::filesystem;
  if (path.empty() || path.find('\0') != std::string::npos) return std::nullopt;
  const fs::path relative(path);
  if (relative.is_absolute() || relative.has_root_path()) return std::nullopt;
  std::error_code ec;
  const fs::path root = fs::canonical(root_, ec);
  if (ec) return std::nullopt;
  // canonical() follows every symbolic link, so a link that leads out of the root shows up as
  // a path outside it.
  const fs::path full = fs::canonical(root / relative, ec);
  if (ec) return std::nullopt;
  const fs::path inside = full.lexically_relative(root);
  if (inside.empty() || inside == "." || *inside.begin() == "..") return std::nullopt;
  if (!fs::is_regular_file(full, ec) || ec) return std::nullopt;
  std::ifstream in(full, std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
