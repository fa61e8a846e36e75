#include "common/image/calloc_allocator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "common/image/image.h"

namespace tessera {
namespace {

bool all_zero(const std::vector<float, CallocAllocator<float>>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return v == 0.0f; });
}

// Memory malloc hands out again after a free still holds what was written into it; a vector
// that skips value-initialization must get zeros anyway.
TEST(CallocAllocator, VectorsStartAsZerosInMemoryUsedBefore) {
  for (const std::size_t n : {std::size_t{2}, std::size_t{1000}, std::size_t{3} << 20}) {
    for (int round = 0; round < 3; ++round) {
      std::vector<float, CallocAllocator<float>> values(n);
      ASSERT_TRUE(all_zero(values)) << n << " floats, round " << round;
      std::fill(values.begin(), values.end(), 7.0f);
    }
  }
}

TEST(CallocAllocator, CopiesAndFilledVectorsKeepTheirValues) {
  const std::vector<float, CallocAllocator<float>> filled(1000, 2.5f);
  const auto copy = filled;
  EXPECT_TRUE(std::all_of(copy.begin(), copy.end(), [](float v) { return v == 2.5f; }));
}

TEST(Image, ANewImageIsBlack) {
  for (int round = 0; round < 3; ++round) {
    Image image(640, 480);
    ASSERT_TRUE(all_zero(image.rgb)) << "round " << round;
    image.set(639, 479, Rgb{1, 2, 3});
    std::fill(image.rgb.begin(), image.rgb.end(), 7.0f);
  }
  Image small(3, 2);
  EXPECT_TRUE(all_zero(small.rgb));
}

}  // namespace
}  // namespace tessera
