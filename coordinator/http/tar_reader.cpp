#include "coordinator/http/tar_reader.h"

#include <memory>
#include <stdexcept>

#include <archive.h>
#include <archive_entry.h>

namespace tessera {
namespace {

using ArchivePtr = std::unique_ptr<archive, decltype(&archive_read_free)>;

[[noreturn]] void fail(archive* a, const std::string& what) {
  const char* why = archive_error_string(a);
  throw std::runtime_error("tar: " + what + (why ? std::string(": ") + why : std::string()));
}

}  // namespace

std::map<std::string, std::string> read_tar(std::string_view bytes) {
  ArchivePtr a(archive_read_new(), archive_read_free);
  if (!a) throw std::runtime_error("tar: out of memory");
  // Tar only, uncompressed: bundles are small, and a compression filter would let a small body
  // expand without bound.
  archive_read_support_format_tar(a.get());
  if (archive_read_open_memory(a.get(), bytes.data(), bytes.size()) != ARCHIVE_OK)
    fail(a.get(), "not a tar archive");
  std::map<std::string, std::string> files;
  archive_entry* entry = nullptr;
  for (;;) {
    const int status = archive_read_next_header(a.get(), &entry);
    if (status == ARCHIVE_EOF) break;
    if (status != ARCHIVE_OK) fail(a.get(), "damaged header");
    if (archive_entry_filetype(entry) != AE_IFREG) continue;
    const char* path = archive_entry_pathname(entry);
    if (!path) fail(a.get(), "an entry without a name");
    std::string name = path;
    while (name.starts_with("./")) name.erase(0, 2);
    // The whole archive is in memory, so an entry's contents are never larger than it.
    const la_int64_t size = archive_entry_size(entry);
    if (size < 0 || static_cast<std::size_t>(size) > bytes.size())
      fail(a.get(), "entry \"" + name + "\" has an impossible size");
    std::string data(static_cast<std::size_t>(size), '\0');
    const la_ssize_t read = archive_read_data(a.get(), data.data(), data.size());
    if (read < 0 || static_cast<std::size_t>(read) != data.size())
      fail(a.get(), "entry \"" + name + "\" is truncated");
    files[name] = std::move(data);
  }
  return files;
}

}  // namespace tessera
