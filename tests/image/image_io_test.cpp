#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>

#include "common/image/exr/encode_exr.h"
#include "common/image/image.h"
#include "common/image/png/encode_png.h"

namespace tessera {
namespace {

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("tessera_" + std::to_string(::getpid()) + "_" + name);
}

TEST(ImageIo, ExrKeepsFloatValuesExactly) {
  Image image(3, 2);
  image.set(0, 0, {0.1, 2.5, -0.25});
  image.set(2, 1, {1e-7, 123.456, 0.333333});
  const auto path = temp_file("exact.exr");
  write_image(image, path.string());
  EXPECT_EQ(read_image(path.string()), image);
  std::filesystem::remove(path);
}

TEST(ImageIo, PngClampsToUnitRangeAndQuantizes) {
  Image image(2, 1);
  image.set(0, 0, {-1, 0.5, 7});
  image.set(1, 0, {1, 0, 0.2});
  const auto path = temp_file("clamp.png");
  write_image(image, path.string());
  const Image back = read_image(path.string());
  EXPECT_EQ(back.get(0, 0).r, 0.0f);
  EXPECT_NEAR(back.get(0, 0).g, 128.0 / 255.0, 1e-6);
  EXPECT_EQ(back.get(0, 0).b, 1.0f);
  EXPECT_EQ(back.get(1, 0).r, 1.0f);
  EXPECT_NEAR(back.get(1, 0).b, 51.0 / 255.0, 1e-6);
  std::filesystem::remove(path);
}

TEST(ImageIo, UnwritablePathThrowsWithThePath) {
  Image image(1, 1);
  try {
    write_image(image, "/nonexistent-dir/x.png");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos);
  }
}

TEST(ImageIo, UnknownFormatThrows) {
  EXPECT_THROW(write_image(Image(1, 1), "/tmp/x.notaformat"), std::runtime_error);
}

// tessera-render and the coordinator encode PNG with libpng and EXR with OpenEXR, the tools and
// tests with OpenImageIO: the files must hold the same values, or images that should agree
// bit for bit do not.
Image hard_values() {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               -1.0f,
                               1.0f,
                               7.0f,
                               1e-8f,
                               0.5f,
                               1.0f / 3.0f,
                               1e30f,
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity()};
  for (int level = 0; level < 256; ++level)  // each rounding boundary, and a hair either side
    for (float offset : {-1e-4f, 0.0f, 1e-4f})
      values.push_back((static_cast<float>(level) + 0.5f) / 255.0f + offset);
  Image image(static_cast<int>(values.size()), 3);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = values[i % values.size()];
  return image;
}

TEST(EncodePng, HoldsTheValuesOpenImageIoWrites) {
  const Image image = hard_values();
  const auto theirs = temp_file("theirs.png");
  write_image(image, theirs.string());  // OpenImageIO, in this test program
  const Image back = decode_image(encode_png(image), "ours.png", 1u << 20);
  EXPECT_EQ(back, read_image(theirs.string()));
  EXPECT_EQ(back.width, image.width);
  std::filesystem::remove(theirs);
}

TEST(EncodeExr, KeepsEveryFloatExactly) {
  const Image image = hard_values();
  const Image back = decode_image(encode_exr(image), "ours.exr", 1u << 20);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  for (std::size_t i = 0; i < image.rgb.size(); ++i)  // NaN too: compared as bits
    EXPECT_EQ(std::bit_cast<std::uint32_t>(back.rgb[i]), std::bit_cast<std::uint32_t>(image.rgb[i]))
        << "value " << i;
}

}  // namespace
}  // namespace tessera
