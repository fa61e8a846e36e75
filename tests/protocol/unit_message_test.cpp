#include "common/protocol/unit_message.h"

#include <gtest/gtest.h>

#include <cstring>

#include "common/protocol/frame.h"

namespace tessera {
namespace {

TEST(UnitMessage, PixelSetRoundTrips) {
  const UnitPixels u{
      .rect = {8, 16, 40, 48}, .step = 4, .exclude = 8, .pattern = PixelPattern::Anchors};
  EXPECT_EQ(unit_pixels_from_json(unit_pixels_to_json(u)), u);
  const UnitPixels c{.rect = {0, 0, 5, 3}, .step = 4, .pattern = PixelPattern::Centres};
  EXPECT_EQ(unit_pixels_from_json(unit_pixels_to_json(c)), c);
}

TEST(UnitMessage, AbsurdPixelSetsAreRefused) {
  nlohmann::json j = unit_pixels_to_json({.rect = {0, 0, 4, 4}});
  j["step"] = 0;
  EXPECT_THROW(unit_pixels_from_json(j), ProtocolError);
  j = unit_pixels_to_json({.rect = {0, 0, 4, 4}});
  j["rect"] = {0, 0, 1 << 30, 4};
  EXPECT_THROW(unit_pixels_from_json(j), ProtocolError);
  j["rect"] = "everything";
  EXPECT_THROW(unit_pixels_from_json(j), ProtocolError);
  j = unit_pixels_to_json({.rect = {0, 0, 4, 4}});
  j["pattern"] = "spiral";
  EXPECT_THROW(unit_pixels_from_json(j), ProtocolError);
}

TEST(UnitMessage, FloatsTravelBitExactly) {
  const std::vector<float> v = {0.1f, -0.0f, 1e-38f, 3.4e38f, 0.333333343f, 7.0f};
  const std::vector<float> back = unpack_floats(pack_floats(v), v.size());
  ASSERT_EQ(back.size(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    EXPECT_EQ(std::memcmp(&back[i], &v[i], sizeof(float)), 0);
  EXPECT_THROW(unpack_floats(pack_floats(v), v.size() + 1), ProtocolError);
}

}  // namespace
}  // namespace tessera
