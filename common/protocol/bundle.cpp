#include "common/protocol/bundle.h"

#include "common/protocol/sha256.h"

namespace tessera {

bool is_plain_relative_path(const std::string& path) {
  if (path.empty() || path.front() == '/' || path.find('\0') != std::string::npos) return false;
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    const std::string part = path.substr(start, end - start);
    if (part.empty() || part == "." || part == ".." || part.find('\\') != std::string::npos)
      return false;
    start = end + 1;
  }
  return true;
}

std::string content_hash(const Bundle& bundle) {
  // Length-prefixed fields, so that no two different bundles serialize alike.
  std::string canonical;
  auto add = [&](const std::string& s) {
    canonical += std::to_string(s.size());
    canonical += ':';
    canonical += s;
  };
  add(bundle.format);
  add(bundle.main);
  for (const auto& [path, bytes] : bundle.files) {
    add(path);
    add(bytes);
  }
  return to_hex(sha256(canonical));
}

void encode_bundle(const Bundle& bundle, nlohmann::json& header, std::string& payload) {
  header["main"] = bundle.main;
  header["format"] = bundle.format;
  auto& files = header["files"] = nlohmann::json::array();
  payload.clear();
  for (const auto& [path, bytes] : bundle.files) {
    files.push_back({{"path", path}, {"size", bytes.size()}});
    payload += bytes;
  }
}

Bundle decode_bundle(const nlohmann::json& header, std::string_view payload) {
  Bundle bundle;
  try {
    bundle.main = header.at("main").get<std::string>();
    bundle.format = header.at("format").get<std::string>();
    std::size_t offset = 0;
    for (const auto& f : header.at("files")) {
      const auto path = f.at("path").get<std::string>();
      const auto size = f.at("size").get<std::size_t>();
      if (!is_plain_relative_path(path)) throw ProtocolError("bundle path \"" + path + "\"");
      if (size > payload.size() - offset) throw ProtocolError("bundle sizes exceed its payload");
      bundle.files[path] = std::string(payload.substr(offset, size));
      offset += size;
    }
    if (offset != payload.size()) throw ProtocolError("bundle payload has trailing bytes");
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("bad bundle header: ") + e.what());
  }
  if (!bundle.files.count(bundle.main)) throw ProtocolError("bundle lacks its main scene file");
  return bundle;
}

}  // namespace tessera
