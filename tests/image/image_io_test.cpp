#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/image/image.h"
#include "common/image/png/write_png.h"

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

// tessera-render writes its PNGs with libpng and the coordinator with OpenImageIO: both must
// hold the same bytes for the same intensities, or a job's PNG and tessera-render's differ.
TEST(WritePng, HoldsTheValuesOpenImageIoWrites) {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               -1.0f,
                               1.0f,
                               7.0f,
                               1e-8f,
                               0.5f,
                               1.0f / 3.0f,
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity()};
  for (int level = 0; level < 256; ++level)  // each rounding boundary, and a hair either side
    for (float offset : {-1e-4f, 0.0f, 1e-4f})
      values.push_back((static_cast<float>(level) + 0.5f) / 255.0f + offset);
  Image image(static_cast<int>(values.size()), 3);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = values[i % values.size()];
  const auto ours = temp_file("ours.png"), theirs = temp_file("theirs.png");
  write_png(image, ours.string());
  write_image(image, theirs.string());  // OpenImageIO, in this test program
  const Image back = read_image(ours.string());
  EXPECT_EQ(back, read_image(theirs.string()));
  EXPECT_EQ(back.width, image.width);
  std::filesystem::remove(ours);
  std::filesystem::remove(theirs);
}

TEST(WritePng, UnwritablePathThrowsWithThePath) {
  try {
    write_png(Image(1, 1), "/nonexistent-dir/x.png");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace tessera
