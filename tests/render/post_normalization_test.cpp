// Post-normalization of the colours (§4.6): a step on the finished image.
#include "common/render/post_normalization.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Image row(std::initializer_list<float> values) {
  Image image(static_cast<int>(values.size()) / 3, 1);
  std::copy(values.begin(), values.end(), image.rgb.begin());
  return image;
}

TEST(PostNormalization, ScalesTheHighestComponentToOneThenAppliesTheBrightness) {
  Image image = row({0.5f, 2.0f, 1.0f, 0.25f, 0.0f, 1.5f});
  post_normalize(image, 1.0);
  EXPECT_EQ(image, row({0.25f, 1.0f, 0.5f, 0.125f, 0.0f, 0.75f}));
  image = row({0.5f, 2.0f, 1.0f, 0.25f, 0.0f, 1.5f});
  post_normalize(image, 0.5);
  EXPECT_EQ(image, row({0.125f, 0.5f, 0.25f, 0.0625f, 0.0f, 0.375f}));
}

TEST(PostNormalization, AnImageWithinRangeIsOnlyBrightened) {
  Image image = row({0.5f, 0.25f, 1.0f});
  post_normalize(image, 1.5);
  EXPECT_EQ(image, row({0.75f, 0.375f, 1.5f}));
}

// A matte ball under a light three times white: the lit side saturates unless normalized.
Scene overlit_ball() {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Sphere{}, Affine::identity(), Material{}));
  scene.lights.push_back(point_light({2, 2, 10}, {3, 3, 3}));
  return scene;
}

float highest(const Image& image) { return *std::max_element(image.rgb.begin(), image.rgb.end()); }

TEST(PostNormalization, TheBrightestPixelOfARenderEqualsTheBrightness) {
  const Scene scene = overlit_ball();
  RenderSettings s = settings(40, 30);
  const Image plain = render(scene, s);
  ASSERT_GT(highest(plain), 1.0f);
  s.normalize_colors = true;
  s.normalize_brightness = 0.9;
  const Image normalized = render(scene, s);
  EXPECT_FLOAT_EQ(highest(normalized), 0.9f);
  // Every value keeps its proportion to the brightest.
  for (std::size_t i = 0; i < plain.rgb.size(); ++i)
    EXPECT_NEAR(normalized.rgb[i], plain.rgb[i] * 0.9f / highest(plain), 1e-6) << i;
}

}  // namespace
}  // namespace tessera::test
