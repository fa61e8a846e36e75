// Material properties (§3.2.5) and textures (§3.2.8): the current material of later shapes.
#include <gtest/gtest.h>

#include <string>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlMaterial, EveryKeywordSetsItsField) {
  const Scene scene = load_text(
      "surfaceRoughness 0.3 emissive 0.1 0.2 0.3 ambient 0.4 0.5 0.6 diffuse 0.7 0.8 0.9\n"
      "specular 1 2 3 specularExponent 50 lightBackFaces 1 reflectivity 0.25\n"
      "glossStrength 0.5 transparency 0.75 translucencyStrength 0.125 priority 3\n"
      "speedOfLight 0.66 retainAmbientColor 1 retainDiffuseColor 2 retainSpecularReflection -1\n"
      "disableRefraction 1\n"
      "sphere");
  Material expected;
  expected.surface_roughness = 0.3;
  expected.emissive = {0.1, 0.2, 0.3};
  expected.ambient = {0.4, 0.5, 0.6};
  expected.diffuse = {0.7, 0.8, 0.9};
  expected.specular = {1, 2, 3};
  expected.specular_exponent = 50;
  expected.light_back_faces = true;
  expected.reflectivity = 0.25;
  expected.gloss_strength = 0.5;
  expected.transparency = 0.75;
  expected.translucency_strength = 0.125;
  expected.priority = 3;
  expected.speed_of_light = 0.66;
  expected.retain_ambient_color = true;
  expected.retain_diffuse_color = true;
  expected.retain_specular_reflection = true;
  expected.disable_refraction = true;
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].material, expected);
}

TEST(SdlMaterial, FlagsAreFalseForZero) {
  const Scene scene = load_text(
      "lightBackFaces 1 retainAmbientColor 1 disableRefraction 1\n"
      "lightBackFaces 0 retainAmbientColor 0.0 disableRefraction -0 sphere");
  EXPECT_EQ(scene.objects[0].material, Material{});
}

TEST(SdlMaterial, TheMaterialCarriesToLaterShapesUntilChanged) {
  const Scene scene = load_text(
      "sphere diffuse 1 0 0 sphere cube\n"
      "specular 1 1 1 cone 0\n"
      "defaultMaterials cube\n"
      "DefaultMaterials diffuse 0 0 1 cube");
  ASSERT_EQ(scene.objects.size(), 6u);
  EXPECT_EQ(scene.objects[0].material, Material{});
  EXPECT_EQ(scene.objects[1].material.diffuse, Rgb(1, 0, 0));
  EXPECT_EQ(scene.objects[2].material.diffuse, Rgb(1, 0, 0));
  EXPECT_EQ(scene.objects[3].material.diffuse, Rgb(1, 0, 0));
  EXPECT_EQ(scene.objects[3].material.specular, Rgb(1, 1, 1));
  EXPECT_EQ(scene.objects[4].material, Material{});
  Material blue;
  blue.diffuse = {0, 0, 1};
  EXPECT_EQ(scene.objects[5].material, blue);
}

TEST(SdlMaterial, DefaultMaterialsAlsoClearsTextures) {
  const Scene scene = load_text(
      "solidTexture 9 0.5 imageTexture a.bmp 1 1 1 defaultMaterials sphere", {{"a.bmp", "image"}});
  EXPECT_EQ(scene.objects[0].material, Material{});
}

TEST(SdlMaterial, OutOfRangeValuesAreLocatedErrors) {
  EXPECT_TRUE(fails_at("reflectivity 1.5", 1, 14,
                       "<value> of 'reflectivity' must be in [0, 1], found '1.5'"));
  EXPECT_TRUE(fails_at("transparency -0.1", 1, 14,
                       "<value> of 'transparency' must be in [0, 1], found '-0.1'"));
  EXPECT_TRUE(
      fails_at("diffuse 1 -1 0", 1, 11, "<green> of 'diffuse' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("emissive 0 0 -0.5", 1, 14,
                       "<blue> of 'emissive' must be non-negative, found '-0.5'"));
  EXPECT_TRUE(
      fails_at("ambient -1 0 0", 1, 9, "<red> of 'ambient' must be non-negative, found '-1'"));
  EXPECT_TRUE(
      fails_at("specular 0 -1 0", 1, 12, "<green> of 'specular' must be non-negative, found '-1'"));
  EXPECT_TRUE(
      fails_at("speedOfLight 0", 1, 14, "<value> of 'speedOfLight' must be positive, found '0'"));
  EXPECT_TRUE(fails_at("specularExponent -2", 1, 18,
                       "<value> of 'specularExponent' must be non-negative, found '-2'"));
  EXPECT_TRUE(fails_at("surfaceRoughness -1", 1, 18,
                       "<value> of 'surfaceRoughness' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("glossStrength -1", 1, 15,
                       "<value> of 'glossStrength' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("translucencyStrength -1", 1, 22,
                       "<value> of 'translucencyStrength' must be non-negative, found '-1'"));
}

TEST(SdlMaterial, PriorityIsAnIntegerOfAtLeastOne) {
  EXPECT_EQ(load_text("priority 2.0 sphere").objects[0].material.priority, 2);
  EXPECT_EQ(load_text("priority 1e1 sphere").objects[0].material.priority, 10);
  EXPECT_TRUE(fails_at("priority 0", 1, 10, "<value> of 'priority' must be at least 1, found '0'"));
  EXPECT_TRUE(fails_at("priority 1.5", 1, 10,
                       "expected an integer for <value> of 'priority', found '1.5'"));
  EXPECT_TRUE(fails_at("priority 1e10", 1, 10,
                       "<value> of 'priority' must be at most 2147483647, found '1e10'"));
}

TEST(SdlTextures, SolidTexturesTakeTheirTypesParameterCount) {
  const Scene scene = load_text(
      "solidTexture 1 2 3 4 sphere\n"
      "solidTexture 4 2 0.5 sphere\n"
      "solidTexture 5 1 3 2 3 sphere\n"
      "solidTexture 6 1 1 2 3 sphere\n"
      "solidTexture 7 1 2 3 4 5 6 7 8 9 10 11 sphere\n"
      "solidTexture 8 0 5 1 1 1 sphere\n"
      "solidTexture 9 0.5 sphere\n"
      "solidTexture 0 sphere\n"
      "solidTexture 2 1 1 1 solidTexture 3 2 2 2 sphere");
  ASSERT_EQ(scene.objects.size(), 9u);
  const auto solid = [&](std::size_t i) { return scene.objects[i].material.solid_texture; };
  EXPECT_EQ(solid(0), (SolidTexture{1, {2, 3, 4}}));
  EXPECT_EQ(solid(1), (SolidTexture{4, {2, 0.5}}));
  EXPECT_EQ(solid(2), (SolidTexture{5, {1, 3, 2, 3}}));
  EXPECT_EQ(solid(3), (SolidTexture{6, {1, 1, 2, 3}}));
  EXPECT_EQ(solid(4), (SolidTexture{7, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}}));
  EXPECT_EQ(solid(5), (SolidTexture{8, {0, 5, 1, 1, 1}}));
  EXPECT_EQ(solid(6), (SolidTexture{9, {0.5}}));
  EXPECT_EQ(solid(7), SolidTexture{});
  EXPECT_EQ(solid(8), (SolidTexture{3, {2, 2, 2}}));
}

TEST(SdlTextures, SolidTextureErrors) {
  EXPECT_TRUE(fails_at("solidTexture 10", 1, 14,
                       "<type> of 'solidTexture' must be between 0 and 9, found '10'"));
  EXPECT_TRUE(fails_at("solidTexture 1.5", 1, 14,
                       "expected an integer for <type> of 'solidTexture', found '1.5'"));
  EXPECT_TRUE(fails_at("solidTexture 4 3 1", 1, 16,
                       "<coordinate> of 'solidTexture' must be between 0 and 2, found '3'"));
  EXPECT_TRUE(fails_at("solidTexture 5 0 4 1 1", 1, 18,
                       "<distance-measure> of 'solidTexture' must be between 0 and 3, found '4'"));
  EXPECT_TRUE(fails_at("solidTexture 9", 1, 15,
                       "unexpected end of file, expected a number for <threshold> of "
                       "'solidTexture'"));
  EXPECT_TRUE(fails_at("solidTexture 1 1 1 sphere", 1, 20,
                       "expected a number for <scale-z> of 'solidTexture', found 'sphere'"));
}

TEST(SdlTextures, ImageTextureStoresTheResolvedPath) {
  const Scene scene = load_text(
      "imageTexture textures/wood.bmp 0 2 3 sphere\n"
      "imageTexture ./textures/../marble.bmp 1 1 0.5 sphere\n"
      "include sub/part.sdl",
      {{"sub/part.sdl", "imageTexture tex.bmp 1 1 1 cube"},
       {"textures/wood.bmp", "wood"},
       {"marble.bmp", "marble"},
       {"sub/tex.bmp", "tex"}});
  ASSERT_EQ(scene.objects.size(), 3u);
  const FlatTexture& wood = scene.objects[0].material.flat_texture;
  EXPECT_EQ(wood.kind, FlatTexture::Kind::Image);
  EXPECT_EQ(wood.image_file, "textures/wood.bmp");
  EXPECT_TRUE(wood.decal);
  EXPECT_EQ(wood.tile_s, 2);
  EXPECT_EQ(wood.tile_t, 3);
  const FlatTexture& marble = scene.objects[1].material.flat_texture;
  EXPECT_EQ(marble.image_file, "marble.bmp");
  EXPECT_FALSE(marble.decal);
  EXPECT_EQ(marble.tile_t, 0.5);
  EXPECT_EQ(scene.objects[2].material.flat_texture.image_file, "sub/tex.bmp");
}

// The loader reads each image file once, so that it travels in the scene's bundle; the
// renderer decodes it.
TEST(SdlTextures, ImageFilesAreReadOncePerPath) {
  const Scene scene = load_text(
      "imageTexture a.bmp 0 1 1 sphere\n"
      "imageTexture ./a.bmp 1 2 2 cube\n"
      "imageTexture sub/b.png 1 1 1 cube",
      {{"a.bmp", "AAA"}, {"sub/b.png", "BB"}});
  ASSERT_EQ(scene.images.size(), 2u);
  EXPECT_EQ(scene.images[0].path, "a.bmp");
  EXPECT_EQ(scene.images[0].bytes, "AAA");
  EXPECT_EQ(scene.images[0].where.line, 1);
  EXPECT_EQ(scene.images[0].where.column, 14);
  EXPECT_EQ(scene.images[1].path, "sub/b.png");
  EXPECT_EQ(scene.images[1].bytes, "BB");
}

TEST(SdlTextures, ImageTextureErrors) {
  EXPECT_TRUE(
      fails_at("sphere\nimageTexture nope.bmp 0 1 1", 2, 14, "image file 'nope.bmp' not found"));
  EXPECT_TRUE(fails_at("imageTexture ../x.bmp 0 1 1", 1, 14,
                       "imageTexture '../x.bmp' leaves the scene's folder"));
  EXPECT_TRUE(fails_at("imageTexture x.bmp 0 0 1", 1, 22,
                       "<tile-s> of 'imageTexture' must be positive, found '0'"));
  EXPECT_TRUE(fails_at("imageTexture x.bmp 0 1", 1, 23,
                       "unexpected end of file, expected a number for <tile-t> of "
                       "'imageTexture'"));
}

TEST(SdlTextures, ProceduralTextures) {
  const Scene scene = load_text(
      "proceduralTexture 1 0 4 8 sphere\n"
      "proceduralTexture 2 1 1 0 0 0 0 1 sphere\n"
      "proceduralTexture 0 1 sphere");
  const FlatTexture& checker = scene.objects[0].material.flat_texture;
  EXPECT_EQ(checker.kind, FlatTexture::Kind::Procedural);
  EXPECT_EQ(checker.procedural_type, 1);
  EXPECT_EQ(checker.params, (std::vector<double>{4, 8}));
  EXPECT_TRUE(checker.decal);
  const FlatTexture& radial = scene.objects[1].material.flat_texture;
  EXPECT_EQ(radial.procedural_type, 2);
  EXPECT_EQ(radial.params, (std::vector<double>{1, 0, 0, 0, 0, 1}));
  EXPECT_FALSE(radial.decal);
  EXPECT_EQ(scene.objects[2].material.flat_texture.kind, FlatTexture::Kind::None);
  EXPECT_TRUE(fails_at("proceduralTexture 3 0", 1, 19,
                       "<type> of 'proceduralTexture' must be between 0 and 2, found '3'"));
  EXPECT_TRUE(fails_at("proceduralTexture 2 0 1 1 1 1 1", 1, 32,
                       "unexpected end of file, expected a number for <outside-blue> of "
                       "'proceduralTexture'"));
}

TEST(SdlTextures, ImageAndProceduralTexturesReplaceEachOtherButKeepOffsets) {
  const Scene scene = load_text(
      "flatTextureOffset 0.25 0.5 imageTexture a.bmp 1 2 2 proceduralTexture 1 1 3 3 sphere\n"
      "imageTexture b.bmp 0 4 4 solidTexture 9 0.5 sphere",
      {{"a.bmp", "a"}, {"b.bmp", "b"}});
  const Material& first = scene.objects[0].material;
  EXPECT_EQ(first.flat_texture.kind, FlatTexture::Kind::Procedural);
  EXPECT_EQ(first.flat_texture.image_file, "");
  EXPECT_EQ(first.flat_texture.tile_s, 1);
  EXPECT_EQ(first.flat_texture.offset_s, 0.25);
  EXPECT_EQ(first.flat_texture.offset_t, 0.5);
  const Material& second = scene.objects[1].material;
  EXPECT_EQ(second.flat_texture.kind, FlatTexture::Kind::Image);
  EXPECT_EQ(second.flat_texture.image_file, "b.bmp");
  EXPECT_TRUE(second.flat_texture.params.empty());
  EXPECT_EQ(second.flat_texture.offset_t, 0.5);
  EXPECT_EQ(second.solid_texture, (SolidTexture{9, {0.5}}));  // solid textures combine
}

TEST(SdlTextures, FlatTextureOffsetsLieInTheUnitInterval) {
  EXPECT_TRUE(fails_at("flatTextureOffset 0 1.5", 1, 21,
                       "<t-offset> of 'flatTextureOffset' must be in [0, 1], found '1.5'"));
}

}  // namespace
}  // namespace tessera::test
