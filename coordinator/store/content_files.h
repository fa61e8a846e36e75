// Files beside the job database (bundles, images): written whole under a temporary name,
// synced and renamed, so that a crash leaves either the old state or the complete file, never
// a torn one. A leftover temporary is an orphan that JobDatabase sweeps at open.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace tessera {

inline constexpr std::string_view kTemporaryPrefix = ".tmp-";

// Throws std::system_error naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);
std::string read_whole_file(const std::filesystem::path& path);

// Throws std::system_error for errno, e.g. "cannot write DIR/results/3: No space left on device".
[[noreturn]] void fail_errno(const std::string& what, const std::filesystem::path& path);

}  // namespace tessera
