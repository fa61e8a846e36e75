#include <gtest/gtest.h>

#include <filesystem>

#include "common/image/image.h"

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

}  // namespace
}  // namespace tessera
