#include "coordinator/jobs/tar_reader.h"

#include <stdexcept>

namespace tessera {
namespace {

constexpr std::size_t kBlock = 512;

std::string field(std::string_view header, std::size_t offset, std::size_t size) {
  std::string_view f = header.substr(offset, size);
  return std::string(f.substr(0, f.find('\0')));
}

std::size_t octal(std::string_view header, std::size_t offset, std::size_t size) {
  std::size_t value = 0;
  bool digits = false;
  for (char c : header.substr(offset, size)) {
    if (c >= '0' && c <= '7') {
      value = value * 8 + static_cast<std::size_t>(c - '0');
      digits = true;
    } else if (c != ' ' && c != '\0') {
      throw std::runtime_error("tar: bad number in header");
    } else if (digits) {
      break;
    }
  }
  return value;
}

}  // namespace

std::map<std::string, std::string> read_tar(std::string_view archive) {
  std::map<std::string, std::string> files;
  std::size_t pos = 0;
  std::string long_name;  // GNU tar's 'L' entry names the next file
  while (pos + kBlock <= archive.size()) {
    const std::string_view header = archive.substr(pos, kBlock);
    if (header.find_first_not_of('\0') == std::string_view::npos) break;  // end marker
    const std::size_t size = octal(header, 124, 12);
    const char type = header[156];
    pos += kBlock;
    if (size > archive.size() - pos) throw std::runtime_error("tar: truncated archive");
    const std::string_view data = archive.substr(pos, size);
    pos += (size + kBlock - 1) / kBlock * kBlock;
    if (type == 'L') {
      long_name = std::string(data.substr(0, data.find('\0')));
      continue;
    }
    std::string name = long_name.empty() ? field(header, 0, 100) : long_name;
    if (long_name.empty() && header.substr(257, 5) == "ustar") {
      const std::string prefix = field(header, 345, 155);
      if (!prefix.empty()) name = prefix + "/" + name;
    }
    long_name.clear();
    while (name.rfind("./", 0) == 0) name.erase(0, 2);
    if (type == '0' || type == '\0') files[name] = std::string(data);
  }
  return files;
}

}  // namespace tessera
