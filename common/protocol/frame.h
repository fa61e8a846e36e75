// Wire frames between coordinator and workers (docs/PROTOCOL.md):
//
//   u32 body length (big-endian, bytes after this field, at most FrameLimits::max_body)
//   u8  message type
//   u32 header length (big-endian, at most FrameLimits::max_header)
//   header: a JSON object, UTF-8
//   payload: the rest of the body, raw bytes (float32 pixels, bundle files; payload.h)
//
// The decoder is incremental and transport-free, so the codec is tested without sockets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/protocol/payload.h"

namespace tessera {

enum class MessageType : std::uint8_t {
  Hello = 1,       // worker: version, name, threads, nonce, cached bundle hashes
  Challenge = 2,   // coordinator: version, nonce, auth ("hmac-sha256", or "none" if --insecure)
  Auth = 3,        // worker: proof of the shared secret
  Welcome = 4,     // coordinator: accepted; the worker's id and the coordinator's own proof
  Reject = 5,      // coordinator: refused, with a reason; the connection closes
  Heartbeat = 6,   // either side, when it has sent nothing for a while
  Job = 7,         // coordinator: a job's settings, and its bundle unless the worker has it
  Unit = 8,        // coordinator: render these pixels of this pass
  Result = 9,      // worker: a unit's pixels (float32 RGB) and statistics
  JobFailed = 10,  // worker: the job's scene could not be prepared
  Cancel = 11,     // coordinator: drop the job's queued units and its prepared scene
};

const char* to_string(MessageType type);

struct Frame {
  MessageType type = MessageType::Heartbeat;
  nlohmann::json header = nlohmann::json::object();
  Payload payload;
};

struct FrameLimits {
  std::size_t max_body = 64u << 20;  // bundles with meshes and textures are the largest frames
  std::size_t max_header = 64u << 10;
};

// Malformed or oversized input: the connection that sent it is closed.
class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string encode_frame(const Frame& frame, const FrameLimits& limits = {});
// The frame of an already serialised header (a JSON object); throws ProtocolError past the limits.
std::string encode_frame_bytes(MessageType type, std::string_view header, std::string_view payload,
                               const FrameLimits& limits = {});

constexpr std::size_t kFramePrefix = 4;
// Validates the length prefix of a frame; returns the body length to read next.
std::size_t decode_body_length(const std::uint8_t prefix[kFramePrefix], const FrameLimits& limits);
// Decodes a complete body (everything after the length prefix).
Frame decode_body(std::string_view body, const FrameLimits& limits);

// A connection reads a frame in two steps: its first kFrameHead bytes (the length prefix, the
// type and the header's length), then the header and the payload straight into their own
// buffers (Payload::to_read), so that a result's pixels (up to 786 kB, one for every unit the
// coordinator merges) are neither moved nor copied after the read.
constexpr std::size_t kFrameHead = kFramePrefix + 5;
struct FrameHead {
  MessageType type;
  std::size_t header_bytes, payload_bytes;
};
// Validates a frame's first bytes; throws ProtocolError.
FrameHead decode_frame_head(const std::uint8_t head[kFrameHead], const FrameLimits& limits);
// The frame of a header's bytes and a payload, which it takes over; throws ProtocolError.
Frame decode_frame_parts(MessageType type, std::string_view header, Payload&& payload);

// Bytes in, frames out, for stream transports that deliver arbitrary chunks.
class FrameDecoder {
 public:
  explicit FrameDecoder(FrameLimits limits = {}) : limits_(limits) {}
  void feed(std::string_view bytes) { buffer_.append(bytes); }
  // The next complete frame, or nullopt until more bytes arrive. Throws ProtocolError.
  std::optional<Frame> next();

 private:
  FrameLimits limits_;
  std::string buffer_;
};

}  // namespace tessera
