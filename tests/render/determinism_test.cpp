// A pixel's value depends only on the scene, the settings and the pixel (docs/ARCHITECTURE.md,
// "Determinism").
#include <gtest/gtest.h>

#include "common/render/frame_buffer.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

// Rough: its normals are perturbed at random, keyed by pixel and sample.
Scene busy_scene() { return sphere_and_glass_cube(0.05); }

RenderSettings noisy_settings() {
  RenderSettings s = settings(48, 36);
  s.aa_samples = 5;
  s.stochastic = true;
  s.jitter = 0.8;
  s.passes = 2;
  s.seed = 42;
  return s;
}

TEST(Determinism, OneThreadEqualsManyThreadsBitForBit) {
  const Scene scene = busy_scene();
  const RenderSettings s = noisy_settings();
  EXPECT_EQ(render(scene, s, nullptr, 1), render(scene, s, nullptr, 4));
}

TEST(Determinism, SubRectangleEqualsThoseImagePixels) {
  const Scene scene = busy_scene();
  const RenderSettings s = noisy_settings();
  const Image whole = render(scene, s);
  const PreparedScene prepared(scene, s.bvh);
  const PixelRect rect{13, 7, 31, 22};
  FrameBuffer frame(s.width, s.height);
  std::vector<Rgb> values(static_cast<std::size_t>(rect.area()));
  RenderStats stats;
  for (int pass = 0; pass < s.passes; ++pass) {
    render_pass(prepared, s, rect, pass, values, stats);
    std::size_t i = 0;
    for (int y = rect.y0; y < rect.y1; ++y)
      for (int x = rect.x0; x < rect.x1; ++x, ++i) {
        const float rgb[3] = {float(values[i].r), float(values[i].g), float(values[i].b)};
        frame.add_pass(x, y, rgb);
      }
  }
  const Image part = frame.resolve();
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x)
      ASSERT_EQ(part.get(x, y), whole.get(x, y)) << x << "," << y;
}

// A region (issue 21 §4) renders its pixels as the whole image does, and nothing else.
TEST(Determinism, RegionEqualsThoseImagePixelsAndIsBlackElsewhere) {
  const Scene scene = busy_scene();
  RenderSettings s = noisy_settings();
  const Image whole = render(scene, s);
  s.region = PixelRect{13, 7, 31, 22};
  const Image part = render(scene, s, nullptr, 3);
  ASSERT_EQ(part.width, whole.width);
  ASSERT_EQ(part.height, whole.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const bool inside = x >= 13 && x < 31 && y >= 7 && y < 22;
      ASSERT_EQ(part.get(x, y), inside ? whole.get(x, y) : Rgb{}) << x << "," << y;
    }
}

TEST(Determinism, ListedPixelsEqualTheRectangleRender) {
  const Scene scene = busy_scene();
  const RenderSettings s = noisy_settings();
  const PreparedScene prepared(scene, s.bvh);
  const std::vector<PixelCoord> pixels{{0, 0}, {47, 35}, {20, 17}, {3, 30}};
  std::vector<Rgb> listed(pixels.size());
  RenderStats stats;
  render_pixels(prepared, s, pixels, 1, listed, stats);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    Rgb one[1];
    render_pass(prepared, s, {pixels[i].x, pixels[i].y, pixels[i].x + 1, pixels[i].y + 1}, 1, one,
                stats);
    EXPECT_EQ(listed[i], one[0]);
  }
}

TEST(Determinism, SeedChangesStochasticImages) {
  const Scene scene = busy_scene();
  RenderSettings s = noisy_settings();
  const Image a = render(scene, s);
  s.seed = 43;
  EXPECT_NE(a, render(scene, s));
}

TEST(Determinism, BvhAndBruteForceAgree) {
  const Scene scene = busy_scene();
  RenderSettings s = noisy_settings();
  const Image with_bvh = render(scene, s);
  s.bvh = BvhMode::None;
  EXPECT_EQ(with_bvh, render(scene, s));
}

}  // namespace
}  // namespace tessera::test
