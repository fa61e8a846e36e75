// A frame's payload (frame.h): bytes, or float32 values whose bytes are the payload itself
// (pixels travel as the host's float32 bytes; messages.cpp allows only little-endian hosts).
// A connection reads a payload of whole floats into float values, so that a result's values go
// from the socket to the coordinator's merge and its store without a copy (docs/SCALING.md).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace tessera {

class Payload {
 public:
  Payload() = default;
  // Implicit: encoders build payloads as strings, and float values (a result's) as they are.
  Payload(std::string bytes) : data_(std::move(bytes)) {}
  Payload(const char* bytes) : data_(std::string(bytes)) {}
  Payload(std::vector<float> values) : data_(std::move(values)) {}

  // `bytes` to read into: float values when they are whole floats, else a string.
  static Payload to_read(std::size_t bytes);

  char* data();
  std::size_t size() const;
  bool empty() const { return size() == 0; }
  std::string_view view() const;
  // The payload's float values (its size a multiple of 4: the caller checks), taken over when
  // it holds them, else copied from its bytes.
  std::vector<float> take_floats() &&;

  friend bool operator==(const Payload& a, const Payload& b) { return a.view() == b.view(); }

 private:
  std::variant<std::string, std::vector<float>> data_;
};

}  // namespace tessera
