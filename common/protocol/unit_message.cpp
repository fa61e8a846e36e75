#include "common/protocol/unit_message.h"

#include <bit>
#include <cstring>

#include "common/protocol/frame.h"

namespace tessera {

// Pixels travel as the host's float32 bytes; every supported host is little-endian x86-64
// (docs/ARCHITECTURE.md, "Determinism"), and a big-endian build fails here rather than mixing up
// bytes.
static_assert(std::endian::native == std::endian::little);
static_assert(sizeof(float) == 4);

namespace {
constexpr int kMaxCoordinate = 1 << 16;
}

nlohmann::json unit_pixels_to_json(const UnitPixels& u) {
  return {{"rect", {u.rect.x0, u.rect.y0, u.rect.x1, u.rect.y1}},
          {"step", u.step},
          {"exclude", u.exclude},
          {"pattern", u.pattern == PixelPattern::Anchors ? "anchors" : "centres"}};
}

UnitPixels unit_pixels_from_json(const nlohmann::json& j) {
  UnitPixels u;
  try {
    const auto& r = j.at("rect");
    if (!r.is_array() || r.size() != 4) throw ProtocolError("unit rect needs 4 numbers");
    u.rect = {r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>()};
    u.step = j.at("step").get<int>();
    u.exclude = j.at("exclude").get<int>();
    const auto pattern = j.at("pattern").get<std::string>();
    if (pattern != "anchors" && pattern != "centres") throw ProtocolError("unit pattern");
    u.pattern = pattern == "anchors" ? PixelPattern::Anchors : PixelPattern::Centres;
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("bad unit: ") + e.what());
  }
  const Tile& r = u.rect;
  if (r.x0 < 0 || r.y0 < 0 || r.x1 < r.x0 || r.y1 < r.y0 || r.x1 > kMaxCoordinate ||
      r.y1 > kMaxCoordinate || u.step <= 0 || u.step > kMaxCoordinate || u.exclude < 0)
    throw ProtocolError("unit pixel set out of range");
  return u;
}

std::string pack_floats(std::span<const float> values) {
  std::string out(values.size() * sizeof(float), '\0');
  if (!values.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

std::vector<float> unpack_floats(const std::string& payload, std::size_t count) {
  if (payload.size() != count * sizeof(float))
    throw ProtocolError("payload of " + std::to_string(payload.size()) + " bytes for " +
                        std::to_string(count) + " floats");
  std::vector<float> out(count);
  if (count > 0) std::memcpy(out.data(), payload.data(), payload.size());
  return out;
}

}  // namespace tessera
