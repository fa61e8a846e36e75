// The parts of unit and result frames that are not plain JSON values: a unit's pixel set and
// the result's float32 pixels.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/progressive/unit_pixels.h"

namespace tessera {

nlohmann::json unit_pixels_to_json(const UnitPixels& unit);
// Throws ProtocolError for a malformed or absurd pixel set (non-positive step, negative or
// huge rectangle).
UnitPixels unit_pixels_from_json(const nlohmann::json& j);

// float32 values, little-endian, 3 per pixel.
std::string pack_floats(std::span<const float> values);
// Throws ProtocolError unless the payload holds exactly `count` floats.
std::vector<float> unpack_floats(const std::string& payload, std::size_t count);

}  // namespace tessera
