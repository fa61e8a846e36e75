// Reads the regular files of a POSIX (ustar) tar archive held in memory: the bundle upload
// format. Only what bundles need: names (with the ustar prefix), sizes and contents.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace tessera {

// Throws std::runtime_error for a truncated or malformed archive. Directories, links and
// other entry types are skipped; "./" prefixes are dropped.
std::map<std::string, std::string> read_tar(std::string_view archive);

}  // namespace tessera
