// VRML colours and texture coordinates in rendered pixels: a quad's corner colours are
// interpolated over it and lit by the lighting model, per-face colours fill their faces, and
// an image lands where given or default texture coordinates and a TextureTransform put it.
// The camera sees the quad [-1, 1]^2 of the plane z = 0 exactly fill a square image, so pixel
// (i, j) of a w-pixel image looks at x = 2 (i + 1/2) / w - 1, y = 1 - 2 (j + 1/2) / w.
#include <gtest/gtest.h>

#include "common/image/image.h"
#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 40;

// The Viewpoint from which the quad fills the image: tan(fieldOfView / 2) = 1 / 5.
const std::string kView =
    "Viewpoint { position 0 0 5 fieldOfView 0.39479111969976155 }\n"
    "Background { skyColor 1 1 1 }\n";

// The quad's corners (-1 -1, 1 -1, 1 1, -1 1) as one face set, with `fields` added.
std::string quad(const std::string& appearance, const std::string& fields) {
  return "Shape { appearance Appearance { " + appearance +
         " }\n"
         "  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }\n"
         "    " +
         fields + " } }\n";
}

Scene world(const std::string& body, std::map<std::string, std::string> files = {}) {
  MemorySource source(std::move(files));
  source.add("world.wrl", "#VRML V2.0 utf8\n" + body);
  return load_vrml(source, "world.wrl");
}

TEST(VrmlColourRender, CornerColoursAreInterpolatedAndLit) {
  // Colours whose two diagonals have the same mean, (1/2, 1/2, 1/2), so that the centre has
  // the mean colour however the quad is split.
  const std::string colours =
      "coordIndex [0 1 2 3] color Color { color [1 0 0, 0 1 0, 0 1 1, 1 0 1] }";
  const Scene scene =
      world("NavigationInfo { headlight FALSE }\n" + kView +
            "DirectionalLight { direction 0 -0.6 -0.8 intensity 0.5 ambientIntensity 1 }\n" +
            quad("material Material { diffuseColor 0.1 0.9 0.3 ambientIntensity 0.2 }", colours));
  RenderStats stats;
  const Image image = render(scene, settings(kSize + 1, kSize + 1), &stats);
  // The colour replaces the diffuse colour: c x (intensity x N.L + ambientIntensity x Ia),
  // with N.L = 0.8 and the global ambient Ia = intensity x ambientIntensity = 0.5.
  const double lighting = 0.5 * 0.8 + 0.2 * 0.5;
  expect_rgb(image.get(kSize / 2, kSize / 2), Rgb::gray(0.5 * lighting));
  EXPECT_GT(stats.shadow_rays, 0u);
  const PreparedScene prepared(scene, BvhMode::Sah);
  const std::vector<std::string> names = prepared.effects().names();
  EXPECT_NE(std::find(names.begin(), names.end(), "vertex_colors"), names.end());
}

TEST(VrmlColourRender, PerFaceColoursFillTheirFaces) {
  // Two triangles split along the diagonal y = x: face 0 below it, face 1 above.
  const Scene scene = world(kView + quad("material Material {}",
                                         "coordIndex [0 1 2 -1 0 2 3] colorPerVertex FALSE\n"
                                         "    color Color { color [0.2 0.4 0.6, 0.9 0.5 0.1] }"));
  const Image image = render(scene, settings(kSize, kSize));
  // The headlight along the view: N.L = 1, intensity 1, no ambient light.
  for (const auto& [i, j] : {std::pair{30, 30}, std::pair{35, 10}, std::pair{21, 22}})
    expect_rgb(image.get(i, j), {0.2, 0.4, 0.6});
  for (const auto& [i, j] : {std::pair{10, 10}, std::pair{5, 30}, std::pair{18, 17}})
    expect_rgb(image.get(i, j), {0.9, 0.5, 0.1});
}

TEST(VrmlColourRender, ColoursWithoutMaterialShowUnlit) {
  const Scene scene = world("NavigationInfo { headlight FALSE }\n" + kView +
                            quad("",
                                 "coordIndex [0 1 2 3] colorPerVertex FALSE "
                                 "color Color { color 0.3 0.6 0.9 }"));
  expect_rgb(render(scene, settings(kSize, kSize)).get(7, 31), {0.3, 0.6, 0.9});
}

TEST(VrmlColourRender, FaceSetsWithoutColoursPayNothing) {
  const Scene scene = world(kView + quad("material Material {}", "coordIndex [0 1 2 3]"));
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_FALSE(prepared.textured());
  EXPECT_FALSE(prepared.effects().has(Effect::VertexColors));
}

// 4 x 4 texels in four 2 x 2 quadrants, as PNG bytes: between the centres of a quadrant's
// texels the bilinear filter returns the quadrant's colour exactly.
const Rgb kTopLeft{1, 0, 0}, kTopRight{0, 1, 0}, kBottomLeft{0, 0, 1};
const Rgb kBottomRight{51 / 255.0, 102 / 255.0, 204 / 255.0};

std::string quadrant_png() {
  Image image(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      image.set(x, y,
                y < 2 ? (x < 2 ? kTopLeft : kTopRight) : (x < 2 ? kBottomLeft : kBottomRight));
  // In memory: a file of one name shared by the tests that run side by side raced.
  return encode_image(image, "png");
}

// The quad with the quadrant image, lit head-on by the headlight (so a texel shows as it is).
Image textured_quad(const std::string& texture_transform, const std::string& fields) {
  const std::string look =
      "material Material {} texture ImageTexture { url \"quadrants.png\" } " + texture_transform;
  return render(world(kView + quad(look, fields), {{"quadrants.png", quadrant_png()}}),
                settings(kSize, kSize));
}

TEST(VrmlColourRender, TextureCoordinatesPlaceTheImage) {
  // Turned a quarter: (s, t) = ((1 - y) / 2, (x + 1) / 2).
  const Image image =
      textured_quad("",
                    "coordIndex [0 1 2 3] texCoord TextureCoordinate { point [1 0, 1 1, 0 1, "
                    "0 0] }");
  expect_rgb(image.get(10, 10), kBottomLeft);  // x < 0, y > 0: s < 1/2, t < 1/2
  expect_rgb(image.get(30, 10), kTopLeft);
  expect_rgb(image.get(10, 30), kBottomRight);
  expect_rgb(image.get(30, 30), kTopRight);
  // The same through texCoordIndex, with the coordinates listed in another order.
  const Image indexed = textured_quad(
      "",
      "coordIndex [0 1 2 3] texCoord TextureCoordinate { point [0 0, 1 1, 0 1, 1 0] }\n"
      "    texCoordIndex [3 1 2 0]");
  for (const auto& [i, j] : {std::pair{10, 10}, std::pair{30, 10}, std::pair{30, 30}})
    EXPECT_EQ(indexed.get(i, j), image.get(i, j));
}

TEST(VrmlColourRender, DefaultTextureCoordinatesSpanTheBoundingBox) {
  // No texCoord: s along x and t along y, each from 0 to 1 across the square.
  const Image image = textured_quad("", "coordIndex [0 1 2 3]");
  expect_rgb(image.get(10, 10), kTopLeft);
  expect_rgb(image.get(30, 10), kTopRight);
  expect_rgb(image.get(10, 30), kBottomLeft);
  expect_rgb(image.get(30, 30), kBottomRight);
}

TEST(VrmlColourRender, RepeatFalseStretchesTheImagesEdge) {
  // s runs from 0 to 2 across the quad: the right half repeats the image, unless repeatS is
  // FALSE, when its right column goes on.
  const std::string fields =
      "coordIndex [0 1 2 3] texCoord TextureCoordinate { point [0 0, 2 0, 2 1, 0 1] }";
  const auto image = [&](const std::string& repeat) {
    const std::string look =
        "material Material {} texture ImageTexture { url \"quadrants.png\" " + repeat + " }";
    return render(world(kView + quad(look, fields), {{"quadrants.png", quadrant_png()}}),
                  settings(kSize, kSize));
  };
  expect_rgb(image("").get(24, 10), kTopLeft);  // s = 1.225, t = 0.7375
  expect_rgb(image("repeatS FALSE").get(24, 10), kTopRight);
  expect_rgb(image("repeatS FALSE").get(4, 30), kBottomLeft);  // inside the square: as ever
}

TEST(VrmlColourRender, TextureTransformScalesAndTranslatesTheCoordinates) {
  // Scale 2: the image twice across the quad. Row 4 has t = 0.8875, 2t = 1.775: the top row.
  const Image tiled =
      textured_quad("textureTransform TextureTransform { scale 2 2 }", "coordIndex [0 1 2 3]");
  expect_rgb(tiled.get(4, 4), kTopLeft);  // s = 0.1125, 2s = 0.225
  expect_rgb(tiled.get(14, 4), kTopRight);
  expect_rgb(tiled.get(24, 4), kTopLeft);  // 2s = 1.225
  expect_rgb(tiled.get(34, 4), kTopRight);
  // Translation by half the image each way: the quadrants swap diagonally.
  const Image moved = textured_quad("textureTransform TextureTransform { translation 0.5 0.5 }",
                                    "coordIndex [0 1 2 3]");
  expect_rgb(moved.get(10, 10), kBottomRight);
  expect_rgb(moved.get(30, 10), kBottomLeft);
  expect_rgb(moved.get(10, 30), kTopRight);
  expect_rgb(moved.get(30, 30), kTopLeft);
}

TEST(VrmlColourRender, IntensityTexturesModulateTheColourUnderThem) {
  // A 2 x 2 one-channel PGM of 102 / 255 = 0.4 everywhere, lit head-on by the headlight.
  const std::string grey = "P5\n2 2\n255\n" + std::string(4, static_cast<char>(102));
  const std::string look =
      "material Material { diffuseColor 1 0.5 0.25 } texture ImageTexture { url \"grey.pgm\" }";
  const auto centre = [&](const std::string& appearance, const std::string& fields) {
    return render(world(kView + quad(appearance, fields), {{"grey.pgm", grey}}),
                  settings(kSize, kSize))
        .get(kSize / 2, kSize / 2);
  };
  // I x diffuseColor; with a Color, I x the colour (§4.14.2, table 4.5).
  expect_rgb(centre(look, "coordIndex [0 1 2 3]"), {0.4, 0.2, 0.1});
  expect_rgb(centre(look,
                    "coordIndex [0 1 2 3] color Color { color 0.5 1 0.75 } "
                    "colorPerVertex FALSE"),
             {0.2, 0.4, 0.3});
  // Without a Material the shape is unlit and shows the intensity itself.
  expect_rgb(centre("texture ImageTexture { url \"grey.pgm\" }", "coordIndex [0 1 2 3]"),
             Rgb::gray(0.4));
}

}  // namespace
}  // namespace tessera::test
