// Reads the regular files of a tar archive held in memory, the bundle upload format, with
// libarchive: ustar, PAX (long names, any size) and GNU (long names) archives, header checksums
// checked. Only what bundles need: names and contents.
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace tessera {

// Throws std::runtime_error for a truncated, damaged or non-tar archive, naming what libarchive
// found wrong. Directories, links and other entry types are skipped; "./" prefixes are dropped.
// Names are returned as written: the caller confines them (is_plain_relative_path).
std::map<std::string, std::string> read_tar(std::string_view archive);

}  // namespace tessera
