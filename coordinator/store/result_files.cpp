#include "coordinator/store/result_files.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <bit>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "coordinator/store/content_files.h"

namespace tessera {

namespace {

// Closes the descriptor however the scope is left.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

constexpr std::uint64_t kPrime = 0x9E3779B185EBCA87ull;

std::uint64_t mix(std::uint64_t hash, std::uint64_t word) {
  return std::rotl(hash ^ word, 31) * kPrime;
}

}  // namespace

std::uint64_t payload_checksum(std::span<const std::byte> bytes) {
  // Four independent lanes, so that the multiplications overlap instead of waiting on each other.
  std::array<std::uint64_t, 4> lanes = {1, 2, 3, 4};
  const std::byte* p = bytes.data();
  std::size_t i = 0;
  for (; i + 32 <= bytes.size(); i += 32)
    for (std::size_t lane = 0; lane < 4; ++lane) {
      std::uint64_t word;
      std::memcpy(&word, p + i + 8 * lane, 8);
      lanes[lane] = mix(lanes[lane], word);
    }
  std::uint64_t hash = bytes.size();
  for (std::uint64_t lane : lanes) hash = mix(hash, lane);
  for (; i < bytes.size(); ++i) hash = mix(hash, std::to_integer<std::uint64_t>(p[i]));
  return hash ^ (hash >> 29);
}

void append_payloads(const std::filesystem::path& file, std::int64_t offset,
                     const std::vector<std::span<const std::byte>>& payloads) {
  const bool first = offset == 0;  // the file may be new
  {
    FileDescriptor out{::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644)};
    if (out.fd < 0) fail_errno("cannot open", file);
    for (std::span<const std::byte> payload : payloads) {
      while (!payload.empty()) {
        ssize_t n = ::pwrite(out.fd, payload.data(), payload.size(), offset);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail_errno("cannot write", file);
        payload = payload.subspan(static_cast<std::size_t>(n));
        offset += n;
      }
    }
    // Synced before the rows that point at these bytes commit (their log is synced later, at
    // its checkpoint): a committed row never points at bytes lost with the page cache.
    if (::fdatasync(out.fd) != 0) fail_errno("cannot sync", file);
  }
  if (!first) return;
  // A new file's name is durable only once its folder is synced.
  FileDescriptor folder{::open(file.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (folder.fd < 0) fail_errno("cannot open", file.parent_path());
  if (::fsync(folder.fd) != 0) fail_errno("cannot sync", file.parent_path());
}

void truncate_payloads(const std::filesystem::path& file, std::int64_t bytes) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (error || size <= static_cast<std::uintmax_t>(bytes)) return;
  if (::truncate(file.c_str(), bytes) != 0) fail_errno("cannot truncate", file);
}

PayloadReader::PayloadReader(const std::filesystem::path& file)
    : fd_(::open(file.c_str(), O_RDONLY | O_CLOEXEC)) {}

PayloadReader::~PayloadReader() {
  if (fd_ >= 0) ::close(fd_);
}

bool PayloadReader::read(std::int64_t offset, std::int64_t bytes, std::uint64_t checksum,
                         std::vector<float>& values) const {
  if (fd_ < 0 || offset < 0 || bytes < 0 || bytes % sizeof(float) != 0) return false;
  values.resize(static_cast<std::size_t>(bytes) / sizeof(float));
  auto* out = reinterpret_cast<char*>(values.data());
  std::int64_t done = 0;
  while (done < bytes) {
    ssize_t n = ::pread(fd_, out + done, static_cast<std::size_t>(bytes - done), offset + done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;  // an error, or the file ends before the payload does
    done += n;
  }
  return payload_checksum(std::as_bytes(std::span(values))) == checksum;
}

}  // namespace tessera
