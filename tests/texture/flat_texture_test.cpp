// Flat textures: the offset, clip and tiling arithmetic of §4.3.2, the procedural patterns, and
// bilinear filtering of images.
#include <gtest/gtest.h>

#include <cmath>

#include "common/texture/flat_texture.h"
#include "common/texture/image_texture.h"

namespace tessera {
namespace {

::testing::AssertionResult near(const Rgb& a, const Rgb& b, double tolerance = 1e-12) {
  if (std::fabs(a.r - b.r) <= tolerance && std::fabs(a.g - b.g) <= tolerance &&
      std::fabs(a.b - b.b) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.r << ", " << a.g << ", " << a.b << ") vs ("
                                       << b.r << ", " << b.g << ", " << b.b << ")";
}

PreparedFlatTexture procedural(int type, std::vector<double> params) {
  FlatTexture f;
  f.kind = FlatTexture::Kind::Procedural;
  f.procedural_type = type;
  f.params = std::move(params);
  return make_flat_texture(f, nullptr).value();
}

TEST(FlatTexture, NoneAndProceduralTypeZeroAreNoTexture) {
  EXPECT_FALSE(make_flat_texture(FlatTexture{}, nullptr).has_value());
}

TEST(FlatTexture, OffsetWrapsAroundThenTheSquareIsTiled) {
  PreparedFlatTexture f = procedural(1, {1, 1});
  f.offset_s = 0.25;
  f.offset_t = 0.5;
  TexCoord st = place_on_texture(f, {0.5, 0.25});
  EXPECT_DOUBLE_EQ(st.s, 0.75);
  EXPECT_DOUBLE_EQ(st.t, 0.75);
  st = place_on_texture(f, {0.9, 0.75});  // 1.15 and 1.25 wrap around
  EXPECT_NEAR(st.s, 0.15, 1e-15);
  EXPECT_DOUBLE_EQ(st.t, 0.25);
  f.tile_s = 3;
  f.tile_t = 0.5;
  st = place_on_texture(f, {0.5, 0.25});
  EXPECT_DOUBLE_EQ(st.s, 2.25);
  EXPECT_DOUBLE_EQ(st.t, 0.375);
  f.offset_s = f.offset_t = 0;
  st = place_on_texture(f, {1.0, -1e-17});  // clipped to [0, 1]
  EXPECT_DOUBLE_EQ(st.s, 3);
  EXPECT_DOUBLE_EQ(st.t, 0);
}

TEST(FlatTexture, ProceduralCheckerboardHasTheGivenTilesPerRepeat) {
  PreparedFlatTexture f = procedural(1, {4, 2});
  EXPECT_TRUE(near(flat_texture_colour(f, {0.1, 0.1}), {1, 1, 1}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.3, 0.1}), {0, 0, 0}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.3, 0.6}), {1, 1, 1}));
  f.tile_s = 2;  // the pattern repeats twice along s: 0.3 now falls in the third tile
  EXPECT_TRUE(near(flat_texture_colour(f, {0.3, 0.1}), {1, 1, 1}));
  f.offset_s = 0.1;  // 0.3 + 0.1 = 0.4, times 2: 0.8 -> tile 3 of 4
  EXPECT_TRUE(near(flat_texture_colour(f, {0.3, 0.1}), {0, 0, 0}));
}

TEST(FlatTexture, RadialColoursRunFromTheCentreToTheEdge) {
  const PreparedFlatTexture f = procedural(2, {1, 0, 0, 0, 0, 1});
  EXPECT_TRUE(near(flat_texture_colour(f, {0.5, 0.5}), {1, 0, 0}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.75, 0.5}), {0.5, 0, 0.5}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.5, 0}), {0, 0, 1}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.95, 0.95}), {0, 0, 1}));  // beyond the circle
}

// Texels (row 0 at the top): a b / c d.
Image two_by_two() {
  Image image(2, 2);
  image.set(0, 0, {1, 0, 0});
  image.set(1, 0, {0, 1, 0});
  image.set(0, 1, {0, 0, 1});
  image.set(1, 1, {1, 1, 1});
  return image;
}

TEST(ImageTexture, BilinearFilterOnTwoByTwoTexels) {
  const Image image = two_by_two();
  // Texel centres give the texels: t runs upwards, so the top row is at t = 3/4.
  EXPECT_TRUE(near(bilinear_lookup(image, 0.25, 0.75), {1, 0, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.75, 0.75), {0, 1, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.25, 0.25), {0, 0, 1}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.75, 0.25), {1, 1, 1}));
  // Between them, the weighted means.
  EXPECT_TRUE(near(bilinear_lookup(image, 0.5, 0.5), {0.5, 0.5, 0.5}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.5, 0.75), {0.5, 0.5, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.375, 0.75), {0.75, 0.25, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 0.25, 0.625), {0.75, 0, 0.25}));
  // The image repeats: s = 0 lies half-way between the last and the first column.
  EXPECT_TRUE(near(bilinear_lookup(image, 0, 0.75), {0.5, 0.5, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 1.25, -0.25), {1, 0, 0}));
  // Clamped, it does not: beyond the square the edge texels go on.
  EXPECT_TRUE(near(bilinear_lookup(image, 0, 0.75, true, false), {1, 0, 0}));
  EXPECT_TRUE(near(bilinear_lookup(image, 1.25, -0.25, true, true), {1, 1, 1}));
  EXPECT_TRUE(near(bilinear_lookup(image, 1.25, -0.25, false, true), {0, 0, 1}));
}

TEST(ImageTexture, TilingRepeatsTheImage) {
  const Image image = two_by_two();
  FlatTexture loaded;
  loaded.kind = FlatTexture::Kind::Image;
  loaded.tile_s = 2;
  loaded.tile_t = 2;
  const PreparedFlatTexture f = make_flat_texture(loaded, &image).value();
  // s = 0.125 and 0.625 both land on the first column's centre (0.25 of a repeat).
  EXPECT_TRUE(near(flat_texture_colour(f, {0.125, 0.375}), {1, 0, 0}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.625, 0.875}), {1, 0, 0}));
  EXPECT_TRUE(near(flat_texture_colour(f, {0.375, 0.125}), {1, 1, 1}));
}

}  // namespace
}  // namespace tessera
