#include "common/image/decoded_texture.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace tessera {
namespace {

// Byte 17 of the layout in decoded_texture.h: 0 for eight-bit samples, 1 for float32.
constexpr std::size_t kSampleKindAt = 17;

bool same_bits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.rgb.size() == b.rgb.size() &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

Image ramp() {  // every 8-bit value once per channel, as an image decoder gives them
  Image image(256, 1);
  for (int k = 0; k < 256; ++k)
    image.set(k, 0,
              {static_cast<float>(k) * (1.0f / 255.0f),
               static_cast<float>(255 - k) * (1.0f / 255.0f), 0});
  return image;
}

TEST(DecodedTexture, EightBitValuesTravelAsBytesAndComeBackBitForBit) {
  const Image image = ramp();
  const std::string bytes = encode_decoded_texture(image, 3);
  ASSERT_TRUE(is_decoded_texture(bytes));
  EXPECT_EQ(bytes[kSampleKindAt], 0);
  EXPECT_TRUE(same_bits(decode_decoded_texture(bytes, "ramp.png", 1 << 20), image));
  EXPECT_EQ(decoded_texture_channels(bytes, "ramp.png"), 3);
}

TEST(DecodedTexture, OtherValuesTravelAsFloatsBitForBit) {
  Image image(2, 2);
  image.set(0, 0, {0.1, 2.5, -0.25});
  image.set(1, 1, {1e-7, 0.5f + 1e-7f, 1.0f / 3.0f});
  const std::string bytes = encode_decoded_texture(image, 1);
  EXPECT_EQ(bytes[kSampleKindAt], 1);
  EXPECT_TRUE(same_bits(decode_texture(bytes, "hdr.exr", 4), image));
  EXPECT_EQ(texture_channels(bytes, "hdr.exr"), 1);
}

TEST(DecodedTexture, APngDecodesToTheSameFloatsAsItsDecodedForm) {
  Image source = ramp();
  const auto path = std::filesystem::temp_directory_path() /
                    ("tessera_" + std::to_string(::getpid()) + "_ramp.png");
  write_image(source, path.string());
  std::ifstream in(path, std::ios::binary);
  std::stringstream file;
  file << in.rdbuf();
  std::filesystem::remove(path);
  const Image direct = decode_texture(file.str(), "ramp.png", 1 << 20);
  const std::string decoded =
      encode_decoded_texture(direct, texture_channels(file.str(), "ramp.png"));
  EXPECT_EQ(decoded[kSampleKindAt], 0) << "OpenImageIO's 8-bit values are k * (1.0f / 255.0f)";
  EXPECT_TRUE(same_bits(decode_texture(decoded, "ramp.png", 1 << 20), direct));
  EXPECT_EQ(texture_channels(decoded, "ramp.png"), 3);
}

TEST(DecodedTexture, RefusesMalformedFormsNamingTheFile) {
  const std::string good = encode_decoded_texture(ramp(), 3);
  const auto refused = [](const std::string& bytes, std::size_t max_pixels) {
    try {
      decode_decoded_texture(bytes, "t/wood.jpg", max_pixels);
    } catch (const std::runtime_error& e) {
      return std::string(e.what()).find("t/wood.jpg") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused(good.substr(0, 12), 1 << 20));               // short header
  EXPECT_TRUE(refused(good.substr(0, good.size() - 4), 1 << 20));  // truncated samples
  EXPECT_TRUE(refused(good, 255));                                 // over the pixel budget
  std::string wrong_size = good;
  wrong_size[8] = 2;  // width 2 instead of 256: the samples inflate to more
  EXPECT_TRUE(refused(wrong_size, 1 << 20));
  std::string bad_kind = good;
  bad_kind[kSampleKindAt] = 7;
  EXPECT_TRUE(refused(bad_kind, 1 << 20));
  EXPECT_FALSE(refused(good, 1 << 20));
}

}  // namespace
}  // namespace tessera
