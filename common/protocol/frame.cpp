#include "common/protocol/frame.h"

namespace tessera {
namespace {

void put_u32(std::string& out, std::size_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<char>((v >> shift) & 0xff));
}

std::size_t get_u32(const std::uint8_t* p) {
  return static_cast<std::size_t>(p[0]) << 24 | static_cast<std::size_t>(p[1]) << 16 |
         static_cast<std::size_t>(p[2]) << 8 | p[3];
}

bool known_type(std::uint8_t t) {
  return t >= static_cast<std::uint8_t>(MessageType::Hello) &&
         t <= static_cast<std::uint8_t>(MessageType::Cancel);
}

}  // namespace

const char* to_string(MessageType type) {
  switch (type) {
    case MessageType::Hello:
      return "hello";
    case MessageType::Challenge:
      return "challenge";
    case MessageType::Auth:
      return "auth";
    case MessageType::Welcome:
      return "welcome";
    case MessageType::Reject:
      return "reject";
    case MessageType::Heartbeat:
      return "heartbeat";
    case MessageType::Job:
      return "job";
    case MessageType::Unit:
      return "unit";
    case MessageType::Result:
      return "result";
    case MessageType::JobFailed:
      return "job_failed";
    case MessageType::Cancel:
      return "cancel";
  }
  return "unknown";
}

std::string encode_frame(const Frame& frame, const FrameLimits& limits) {
  // Invalid UTF-8 (a scene's bytes in an error message) is replaced rather than thrown.
  return encode_frame_bytes(
      frame.type, frame.header.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
      frame.payload.view(), limits);
}

std::string encode_frame_bytes(MessageType type, std::string_view header, std::string_view payload,
                               const FrameLimits& limits) {
  const std::size_t body = 1 + 4 + header.size() + payload.size();
  if (header.size() > limits.max_header || body > limits.max_body)
    throw ProtocolError(std::string("frame too large: ") + to_string(type) + " of " +
                        std::to_string(body) + " bytes");
  std::string out;
  out.reserve(kFramePrefix + body);
  put_u32(out, body);
  out.push_back(static_cast<char>(type));
  put_u32(out, header.size());
  out += header;
  out += payload;
  return out;
}

std::size_t decode_body_length(const std::uint8_t prefix[kFramePrefix], const FrameLimits& limits) {
  const std::size_t body = get_u32(prefix);
  if (body < 5) throw ProtocolError("frame body too short: " + std::to_string(body) + " bytes");
  if (body > limits.max_body)
    throw ProtocolError("frame of " + std::to_string(body) + " bytes exceeds the limit of " +
                        std::to_string(limits.max_body));
  return body;
}

namespace {

// The type and header length at `p`, the start of a body of `body` bytes (at least 5), checked.
FrameHead check_head(const std::uint8_t* p, std::size_t body, const FrameLimits& limits) {
  if (!known_type(p[0])) throw ProtocolError("unknown message type " + std::to_string(p[0]));
  const std::size_t header_size = get_u32(p + 1);
  if (header_size > limits.max_header || header_size > body - 5)
    throw ProtocolError("bad header length " + std::to_string(header_size));
  return {static_cast<MessageType>(p[0]), header_size, body - 5 - header_size};
}

}  // namespace

FrameHead decode_frame_head(const std::uint8_t head[kFrameHead], const FrameLimits& limits) {
  return check_head(head + kFramePrefix, decode_body_length(head, limits), limits);
}

Frame decode_frame_parts(MessageType type, std::string_view header, Payload&& payload) {
  Frame frame;
  frame.type = type;
  frame.header = nlohmann::json::parse(header, nullptr, false);
  if (!frame.header.is_object())
    throw ProtocolError(std::string("header of ") + to_string(frame.type) +
                        " is not a JSON object");
  frame.payload = std::move(payload);
  return frame;
}

Frame decode_body(std::string_view body, const FrameLimits& limits) {
  if (body.size() < 5) throw ProtocolError("frame body too short");
  const FrameHead head =
      check_head(reinterpret_cast<const std::uint8_t*>(body.data()), body.size(), limits);
  return decode_frame_parts(head.type, body.substr(5, head.header_bytes),
                            std::string(body.substr(5 + head.header_bytes)));
}

std::optional<Frame> FrameDecoder::next() {
  if (buffer_.size() < kFramePrefix) return std::nullopt;
  const std::size_t body =
      decode_body_length(reinterpret_cast<const std::uint8_t*>(buffer_.data()), limits_);
  if (buffer_.size() < kFramePrefix + body) return std::nullopt;
  Frame frame = decode_body(std::string_view(buffer_).substr(kFramePrefix, body), limits_);
  buffer_.erase(0, kFramePrefix + body);
  return frame;
}

}  // namespace tessera
