#include "common/protocol/frame.h"

#include <gtest/gtest.h>

#include <array>

namespace tessera {
namespace {

Frame sample_frame() {
  Frame f;
  f.type = MessageType::Result;
  f.header = {{"job", 3}, {"unit", 17}};
  f.payload = std::string("\x00\x01\x02\xff", 4);
  return f;
}

TEST(Frame, RoundTripsThroughTheDecoderInAnyChunking) {
  const std::string bytes = encode_frame(sample_frame()) + encode_frame(Frame{});
  for (std::size_t chunk : {1u, 3u, 7u, 1000u}) {
    FrameDecoder decoder;
    std::vector<Frame> frames;
    for (std::size_t i = 0; i < bytes.size(); i += chunk) {
      decoder.feed(std::string_view(bytes).substr(i, chunk));
      while (auto f = decoder.next()) frames.push_back(std::move(*f));
    }
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].type, MessageType::Result);
    EXPECT_EQ(frames[0].header["unit"], 17);
    EXPECT_EQ(frames[0].payload, sample_frame().payload);
    EXPECT_EQ(frames[1].type, MessageType::Heartbeat);
    EXPECT_TRUE(frames[1].payload.empty());
  }
}

// A connection reads the head, then the header and the payload into buffers of their own: the
// frame is the one decode_body makes, and its payload is the buffer read into, not a copy.
TEST(Frame, AFrameReadInPartsDecodesAsOneReadWhole) {
  for (const std::size_t size : {1000, 1001}) {  // whole floats, and not
    Frame sent = sample_frame();
    sent.payload = std::string(size, 'p');
    const std::string bytes = encode_frame(sent);
    const FrameHead head =
        decode_frame_head(reinterpret_cast<const std::uint8_t*>(bytes.data()), {});
    EXPECT_EQ(head.type, MessageType::Result);
    EXPECT_EQ(kFrameHead + head.header_bytes + head.payload_bytes, bytes.size());
    EXPECT_EQ(head.payload_bytes, size);
    Payload payload = Payload::to_read(head.payload_bytes);
    ASSERT_EQ(payload.size(), size);
    bytes.copy(payload.data(), size, kFrameHead + head.header_bytes);
    const char* read_into = payload.data();
    const Frame taken =
        decode_frame_parts(head.type, std::string_view(bytes).substr(kFrameHead, head.header_bytes),
                           std::move(payload));
    const Frame whole = decode_body(std::string_view(bytes).substr(kFramePrefix), {});
    EXPECT_EQ(taken.type, whole.type);
    EXPECT_EQ(taken.header, whole.header);
    EXPECT_EQ(taken.payload, whole.payload);
    EXPECT_EQ(taken.payload.view().data(), read_into);
  }
  EXPECT_THROW(decode_frame_parts(MessageType::Result, "[1]", std::string()), ProtocolError);
}

TEST(Frame, OversizedFramesAreRefusedFromTheirPrefix) {
  FrameLimits small{.max_body = 64, .max_header = 32};
  Frame big;
  big.payload = std::string(100, 'x');
  EXPECT_THROW(encode_frame(big, small), ProtocolError);
  FrameDecoder decoder(small);
  decoder.feed(std::string("\x7f\xff\xff\xff", 4));  // no body needed to refuse it
  EXPECT_THROW(decoder.next(), ProtocolError);
}

TEST(Frame, MalformedBodiesAreRefused) {
  auto body_with = [](std::uint8_t type, const std::string& header, std::size_t header_len) {
    std::string b(1, static_cast<char>(type));
    for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<char>((header_len >> s) & 0xff));
    return b + header;
  };
  EXPECT_THROW(decode_body("abc", {}), ProtocolError);                         // too short
  EXPECT_THROW(decode_body(body_with(0, "{}", 2), {}), ProtocolError);         // unknown type
  EXPECT_THROW(decode_body(body_with(99, "{}", 2), {}), ProtocolError);        // unknown type
  EXPECT_THROW(decode_body(body_with(6, "{}", 50), {}), ProtocolError);        // header overrun
  EXPECT_THROW(decode_body(body_with(6, "{not json", 9), {}), ProtocolError);  // not JSON
  EXPECT_THROW(decode_body(body_with(6, "[1,2]", 5), {}), ProtocolError);      // not an object
  EXPECT_NO_THROW(decode_body(body_with(6, "{}", 2), {}));
  const std::uint8_t tiny[4] = {0, 0, 0, 2};
  EXPECT_THROW(decode_body_length(tiny, {}), ProtocolError);
}

TEST(Frame, InvalidUtf8InAHeaderIsReplacedNotThrown) {
  Frame f;
  f.type = MessageType::JobFailed;
  f.header = {{"error", std::string("scene.sdl:1:1: bad token \xff\xfe")}};
  FrameDecoder decoder;
  decoder.feed(encode_frame(f));
  const auto back = decoder.next();
  ASSERT_TRUE(back.has_value());
  EXPECT_NE(back->header["error"].get<std::string>().find("bad token"), std::string::npos);
}

TEST(Frame, TypeNames) {
  EXPECT_STREQ(to_string(MessageType::JobFailed), "job_failed");
  EXPECT_STREQ(to_string(MessageType::Hello), "hello");
}

}  // namespace
}  // namespace tessera
