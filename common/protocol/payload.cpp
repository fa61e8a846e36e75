#include "common/protocol/payload.h"

namespace tessera {

Payload Payload::to_read(std::size_t bytes) {
  if (bytes % sizeof(float) == 0) return Payload(FloatValues(bytes / sizeof(float)));
  return Payload(std::string(bytes, '\0'));
}

char* Payload::data() {
  if (auto* values = std::get_if<FloatValues>(&data_))
    return reinterpret_cast<char*>(values->data());
  return std::get<std::string>(data_).data();
}

std::size_t Payload::size() const {
  if (const auto* values = std::get_if<FloatValues>(&data_)) return values->size() * sizeof(float);
  return std::get<std::string>(data_).size();
}

std::string_view Payload::view() const {
  if (const auto* values = std::get_if<FloatValues>(&data_))
    return {reinterpret_cast<const char*>(values->data()), values->size() * sizeof(float)};
  return std::get<std::string>(data_);
}

FloatValues Payload::take_floats() && {
  if (auto* values = std::get_if<FloatValues>(&data_)) return std::move(*values);
  const std::string& bytes = std::get<std::string>(data_);
  // Copied as bytes, not zero-filled first (the worker's and the tests' frames, decode_body).
  // may_alias lets a float be read from the string's chars, whose buffer is aligned for a float
  // (operator new's, or the string's own).
  using AliasedFloat [[gnu::may_alias]] = float;
  const auto* first = reinterpret_cast<const AliasedFloat*>(bytes.data());
  return FloatValues(first, first + bytes.size() / sizeof(float));
}

}  // namespace tessera
