// A job's unit results' payloads (their float32 values), appended to one file per job beside the
// job database, DIR/results/<job id>, rather than stored as SQLite blobs: a blob was copied into
// SQLite's log, again into the database at the log's checkpoint, and read back for it, and these
// copies were most of the store thread's time. A result's row keeps where its payload lies (offset
// and length) and a checksum; the payload is written and synced before that row commits, so a
// committed row never points at bytes a crash lost. Bytes past the last committed payload (a
// crash or a failed write between the two) belong to no row and are cut off at the next open.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

namespace tessera {

// A checksum of a payload, kept in its row: a payload the file does not give back whole (cut
// short, zeroed, overwritten) is told from a good one. Not cryptographic; several GB/s.
std::uint64_t payload_checksum(std::span<const std::byte> bytes);

// Writes `payloads` one after the other into `file` from byte `offset` on (creating the file),
// then syncs them, and the folder when the file is new. Throws std::system_error naming the
// file.
void append_payloads(const std::filesystem::path& file, std::int64_t offset,
                     const std::vector<std::span<const std::byte>>& payloads);

// Cuts `file` to `bytes` when it is longer (a missing file is left missing). Throws
// std::system_error naming the file.
void truncate_payloads(const std::filesystem::path& file, std::int64_t bytes);

// One job's payload file opened for reading; a missing file reads as empty.
class PayloadReader {
 public:
  explicit PayloadReader(const std::filesystem::path& file);
  ~PayloadReader();
  PayloadReader(const PayloadReader&) = delete;
  PayloadReader& operator=(const PayloadReader&) = delete;

  // The `bytes` bytes at `offset` as floats, when the file holds them all and they match
  // `checksum`; false otherwise (values then unspecified).
  bool read(std::int64_t offset, std::int64_t bytes, std::uint64_t checksum,
            std::vector<float>& values) const;

 private:
  int fd_ = -1;
};

}  // namespace tessera
