#include "coordinator/store/content_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <system_error>

namespace tessera {

void fail_errno(const std::string& what, const std::filesystem::path& path) {
  throw std::system_error(errno, std::generic_category(), what + " " + path.string());
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  std::filesystem::path temporary =
      path.parent_path() / (std::string(kTemporaryPrefix) + path.filename().string());
  int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail_errno("cannot create", temporary);
  std::size_t written = 0;
  while (written < bytes.size()) {
    ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      int saved = errno;
      ::close(fd);
      ::unlink(temporary.c_str());
      errno = saved;
      fail_errno("cannot write", temporary);
    }
    written += static_cast<std::size_t>(n);
  }
  // Synced before the rename and before the database row that refers to it commits, so that
  // a committed row never points at a file lost with the page cache.
  bool file_synced = ::fsync(fd) == 0;
  if (::close(fd) != 0) file_synced = false;
  if (!file_synced) {
    int saved = errno;
    ::unlink(temporary.c_str());
    errno = saved;
    fail_errno("cannot sync", temporary);
  }
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    int saved = errno;
    ::unlink(temporary.c_str());
    errno = saved;
    fail_errno("cannot rename to", path);
  }
  // The rename itself is durable only once its directory is synced.
  int folder = ::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder < 0) fail_errno("cannot open", path.parent_path());
  bool synced = ::fsync(folder) == 0;
  ::close(folder);
  if (!synced) fail_errno("cannot sync", path.parent_path());
}

std::string read_whole_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::system_error(ENOENT, std::generic_category(), "cannot read " + path.string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return std::move(bytes).str();
}

}  // namespace tessera
