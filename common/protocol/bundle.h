// A scene bundle: the main scene file and every file it reads (includes, meshes, textures),
// keyed by root-relative path. It travels to each worker once per job and is cached there by
// its content hash.
#pragma once

#include <map>
#include <string>
#include <string_view>

#include "common/protocol/frame.h"

namespace tessera {

struct Bundle {
  std::string main;  // root-relative path of the scene file
  std::string format = "sdl";
  std::map<std::string, std::string> files;
  friend bool operator==(const Bundle&, const Bundle&) = default;
};

// SHA-256 over a canonical serialization of main, format and files, as hex.
std::string content_hash(const Bundle& bundle);

// The bundle as a header (file names and sizes) plus a payload (the files' bytes in order).
void encode_bundle(const Bundle& bundle, nlohmann::json& header, std::string& payload);
// Throws ProtocolError when the sizes do not add up or a path is not a plain relative path.
Bundle decode_bundle(const nlohmann::json& header, std::string_view payload);

// True for a normalized root-relative path: no empty, "." or ".." parts, not absolute.
bool is_plain_relative_path(const std::string& path);

}  // namespace tessera
