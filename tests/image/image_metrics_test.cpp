// Error metrics of the accuracy report against images with known differences.
#include <gtest/gtest.h>

#include <cmath>

#include "common/image/image_metrics.h"

namespace tessera::test {
namespace {

Image filled(int w, int h, float v) {
  Image image(w, h);
  std::fill(image.rgb.begin(), image.rgb.end(), v);
  return image;
}

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  const Image a = filled(8, 4, 0.5f);
  const ImageError e = compare_images(a, a);
  EXPECT_EQ(e.rmse, 0);
  EXPECT_TRUE(std::isinf(e.psnr));
  EXPECT_EQ(e.share_off_by_step, 0);
}

TEST(ImageMetrics, UniformOffsetGivesItsRmseAndPsnr) {
  // Every channel off by 0.1: RMSE 0.1, PSNR 20 dB, every pixel off by more than 1/255.
  const ImageError e = compare_images(filled(10, 10, 0.6f), filled(10, 10, 0.5f));
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.psnr, 20, 1e-4);
  EXPECT_NEAR(e.max_error, 0.1, 1e-6);
  EXPECT_EQ(e.share_off_by_step, 1.0);
}

TEST(ImageMetrics, OnePixelOffCountsOnceWhateverItsChannels) {
  // One of 100 pixels off by 0.5 in all three channels: RMSE sqrt(3 * 0.25 / 300) = 0.05.
  const Image reference = filled(10, 10, 0.25f);
  Image image = reference;
  image.set(3, 7, {0.75, 0.75, 0.75});
  const ImageError e = compare_images(image, reference);
  EXPECT_NEAR(e.rmse, 0.05, 1e-6);
  EXPECT_NEAR(e.share_off_by_step, 0.01, 1e-12);
}

TEST(ImageMetrics, DifferencesWithinOneEightBitStepDoNotCount) {
  const ImageError e = compare_images(filled(4, 4, 0.5f + 0.9f / 255), filled(4, 4, 0.5f));
  EXPECT_EQ(e.share_off_by_step, 0);
  EXPECT_GT(e.rmse, 0);
}

TEST(ImageMetrics, ComparesAsDisplayedClampedToTheUnitRange) {
  // 2.0 and 1.5 both display as white; NaN displays as black.
  EXPECT_EQ(compare_images(filled(4, 4, 2.0f), filled(4, 4, 1.5f)).rmse, 0);
  EXPECT_EQ(compare_images(filled(4, 4, NAN), filled(4, 4, 0.0f)).rmse, 0);
}

TEST(ImageMetrics, SizesMustMatch) {
  EXPECT_THROW(compare_images(filled(4, 4, 0), filled(4, 5, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::test
