// VRML colours and texture coordinates on the corners of face set meshes (ISO/IEC 14772-1
// §6.23, §6.15, §6.18) and the TextureTransform's map (§6.48).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/texture/mesh_corners.h"
#include "tests/loaders/vrml_test_util.h"

namespace tessera::test {
namespace {

const Rgb kRed{1, 0, 0}, kGreen{0, 1, 0}, kBlue{0, 0, 1};

const char* const kTriangle = "coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } ";
const char* const kColours = "color Color { color [1 0 0, 0 1 0, 0 0 1] } ";

const Mesh& only_mesh(const Scene& scene) {
  EXPECT_EQ(scene.meshes.size(), 1u);
  return scene.meshes.at(0);
}

// The colour on the corner of `mesh`'s triangle 0 that is vertex `v`.
Rgb colour_of_vertex(const Mesh& mesh, std::uint32_t v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.triangles.at(0).v[k] == v) return mesh.corner_colours.at(static_cast<std::size_t>(k));
  ADD_FAILURE() << "vertex " << v << " is not a corner";
  return {};
}

TEST(VrmlColour, PerVertexColoursFollowColorIndexOrCoordIndex) {
  const Scene by_vertex_scene = load_world(std::string("Shape { geometry IndexedFaceSet { ") +
                                           kTriangle + kColours + "coordIndex [0 1 2] } }");
  const Mesh& by_vertex = only_mesh(by_vertex_scene);
  ASSERT_EQ(by_vertex.corner_colours.size(), 3u);
  EXPECT_EQ(colour_of_vertex(by_vertex, 0), kRed);
  EXPECT_EQ(colour_of_vertex(by_vertex, 1), kGreen);
  EXPECT_EQ(colour_of_vertex(by_vertex, 2), kBlue);
  const Scene indexed_scene =
      load_world(std::string("Shape { geometry IndexedFaceSet { ") + kTriangle + kColours +
                 "coordIndex [1 2 0] colorIndex [0 0 2] ccw FALSE } }");
  const Mesh& indexed = only_mesh(indexed_scene);
  EXPECT_EQ(colour_of_vertex(indexed, 1), kRed);
  EXPECT_EQ(colour_of_vertex(indexed, 2), kRed);
  EXPECT_EQ(colour_of_vertex(indexed, 0), kBlue);
  EXPECT_TRUE(indexed.corner_tex_coords.empty());  // no texture: no coordinates
}

TEST(VrmlColour, PerFaceColoursFollowColorIndexOrFaceOrder) {
  const std::string faces =
      "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n"
      "coordIndex [0 1 2 -1 0 2 3 -1] colorPerVertex FALSE " +
      std::string(kColours);
  for (const auto& [index, first, second] :
       {std::tuple{"", kRed, kGreen}, std::tuple{"colorIndex [2 0]", kBlue, kRed}}) {
    SCOPED_TRACE(index);
    const Scene m_scene = load_world("Shape { geometry IndexedFaceSet { " + faces + index + " } }");
    const Mesh& m = only_mesh(m_scene);
    ASSERT_EQ(m.corner_colours.size(), 6u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(m.corner_colours[static_cast<std::size_t>(k)], first);
      EXPECT_EQ(m.corner_colours[static_cast<std::size_t>(3 + k)], second);
    }
  }
  EXPECT_TRUE(world_fails_at(std::string("Shape { geometry IndexedFaceSet { ") + kTriangle +
                                 kColours + "coordIndex [0 1 2] colorIndex [0 5 1] } }",
                             2, 158, "colorIndex 5 is out of range: the Color has 3 entries"));
}

TEST(VrmlColour, ColoursReplaceTheDiffuseColourOrShowUnlit) {
  const Scene scene = load_world(
      "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 "
      "ambientIntensity 0.5 } }\n  geometry DEF G IndexedFaceSet { " +
      std::string(kTriangle) + kColours + "coordIndex [0 1 2] } }\nShape { geometry USE G }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  const Material& lit = scene.objects[0].material;
  EXPECT_EQ(lit.diffuse, (Rgb{1, 1, 1}));
  EXPECT_EQ(lit.ambient, (Rgb{0.5, 0.5, 0.5}));
  EXPECT_FALSE(lit.corner_colours_decal);
  const Material& unlit = scene.objects[1].material;
  EXPECT_TRUE(unlit.corner_colours_decal);
  EXPECT_TRUE(unlit.emissive.is_zero());
  EXPECT_EQ(scene.meshes.size(), 1u);  // one face set, the same attributes: one mesh
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(VrmlColour, ATextureReplacesTheColoursAndBringsTextureCoordinates) {
  const Scene scene = load_world(
      "Shape { appearance Appearance { texture ImageTexture { url \"t.ppm\" } }\n"
      "  geometry DEF F IndexedFaceSet { " +
          std::string(kTriangle) + kColours +
          "coordIndex [0 1 2]\n"
          "    texCoord TextureCoordinate { point [0 0, 2 0, 0 3] } texCoordIndex [2 1 0] } }\n"
          "Shape { geometry USE F }\n",
      {{"t.ppm", kTinyPpm}});
  ASSERT_EQ(scene.meshes.size(), 2u);  // the textured face set and the coloured one
  const Mesh& textured = scene.meshes[0];
  EXPECT_TRUE(textured.corner_colours.empty());
  ASSERT_EQ(textured.corner_tex_coords.size(), 3u);
  // Vertex 0 is at slot 0 of coordIndex: texCoordIndex 2, the point (0, 3).
  const TexCoord at_origin = corner_tex_coord(textured, 0, {0, 0, 0});
  EXPECT_NEAR(at_origin.s, 0, 1e-12);
  EXPECT_NEAR(at_origin.t, 3, 1e-12);
  const TexCoord at_x = corner_tex_coord(textured, 0, {1, 0, 0});
  EXPECT_NEAR(at_x.s, 2, 1e-12);
  EXPECT_NEAR(at_x.t, 0, 1e-12);
  EXPECT_EQ(scene.meshes[1].corner_colours.size(), 3u);
  EXPECT_TRUE(scene.meshes[1].corner_tex_coords.empty());
}

TEST(VrmlColour, CornerColoursAreInterpolatedBarycentrically) {
  const Scene m_scene = load_world(std::string("Shape { geometry IndexedFaceSet { ") + kTriangle +
                                   kColours + "coordIndex [0 1 2] } }");
  const Mesh& m = only_mesh(m_scene);
  const Rgb c = corner_colour(m, 0, {0.25, 0.5, 0});
  EXPECT_NEAR(c.r, 0.25, 1e-12);
  EXPECT_NEAR(c.g, 0.25, 1e-12);
  EXPECT_NEAR(c.b, 0.5, 1e-12);
}

// The texture coordinates at `p` on the first triangle of `mesh` that holds it.
TexCoord tex_coord_at(const Mesh& mesh, const Vec3& p) {
  for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
    const std::array<double, 3> w = corner_weights(mesh, i, p);
    Vec3 on_triangle;
    for (int k = 0; k < 3; ++k) on_triangle += mesh.positions[mesh.triangles[i].v[k]] * w[k];
    if (w[0] >= -1e-12 && w[1] >= -1e-12 && w[2] >= -1e-12 && length(on_triangle - p) < 1e-9)
      return corner_tex_coord(mesh, i, p);
  }
  ADD_FAILURE() << "no triangle holds the point";
  return {};
}

::testing::AssertionResult near(TexCoord got, double s, double t) {
  if (std::fabs(got.s - s) < 1e-12 && std::fabs(got.t - t) < 1e-12)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << got.s << ", " << got.t << ") instead of (" << s << ", " << t << ")";
}

const char* const kTextured = "appearance Appearance { texture ImageTexture { url \"t.ppm\" } } ";

TEST(VrmlColour, DefaultTextureCoordinatesFollowTheLongestSides) {
  // A box 4 long in z, 2 in x, 1 in y: s along z from 0 to 1, t along x from 0 to 1/2.
  const Scene scene = load_world(
      std::string("Shape { ") + kTextured +
          "geometry IndexedFaceSet { coord Coordinate { point [0 0 -1, 2 0 -1, 2 1 3, 0 0 3] }"
          " coordIndex [0 1 2 3] } }",
      {{"t.ppm", kTinyPpm}});
  const Mesh& m = only_mesh(scene);
  EXPECT_TRUE(near(tex_coord_at(m, {0, 0, -1}), 0, 0));
  EXPECT_TRUE(near(tex_coord_at(m, {2, 0, -1}), 0, 0.5));
  EXPECT_TRUE(near(tex_coord_at(m, {2, 1, 3}), 1, 0.5));
}

TEST(VrmlColour, ElevationGridHasColoursPerQuadAndDefaultTextureCoordinates) {
  const std::string grid =
      "ElevationGrid { xDimension 3 zDimension 2 xSpacing 1 zSpacing 2 height [0 0 0, 0 0 0]\n";
  const Scene coloured = load_world("Shape { geometry " + grid +
                                    " colorPerVertex FALSE color Color { color [1 0 0, 0 0 1] } "
                                    "} }");
  const Mesh& c = only_mesh(coloured);
  // Quad i covers x in [i, i + 1] and has colour i.
  ASSERT_EQ(c.triangles.size(), 4u);
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    double x = 0;
    for (const std::uint32_t v : c.triangles[i].v) x += c.positions[v].x / 3;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(c.corner_colours[3 * i + k], x < 1 ? kRed : kBlue);
  }
  const Scene t_scene = load_world(std::string("Shape { ") + kTextured + "geometry " + grid + "} }",
                                   {{"t.ppm", kTinyPpm}});
  const Mesh& t = only_mesh(t_scene);
  // (0, 0) at the first point, (1, 1) at the last: s along x, t along z.
  EXPECT_TRUE(near(tex_coord_at(t, {0, 0, 0}), 0, 0));
  EXPECT_TRUE(near(tex_coord_at(t, {1, 0, 1}), 0.5, 0.5));
  EXPECT_TRUE(near(tex_coord_at(t, {2, 0, 2}), 1, 1));
}

TEST(VrmlColour, ExtrusionTextureCoordinatesRunAlongSectionAndSpine) {
  // The default square section (2 x 2, 8 long) along a spine 0 to 1 to 3 in y.
  const Scene m_scene = load_world(
      std::string("Shape { ") + kTextured + "geometry Extrusion { spine [0 0 0, 0 1 0, 0 3 0] } }",
      {{"t.ppm", kTinyPpm}});
  const Mesh& m = only_mesh(m_scene);
  ASSERT_EQ(m.corner_tex_coords.size(), 3 * m.triangles.size());
  // The side's first edge runs from (1, y, 1) to (1, y, -1): s from 0 to 1/4.
  EXPECT_TRUE(near(tex_coord_at(m, {1, 1, 0}), 0.125, 1.0 / 3));
  EXPECT_TRUE(near(tex_coord_at(m, {1, 3, 1}), 0, 1));
}

TEST(VrmlColour, TextureTransformMapsCoordinatesAsSpecified) {
  const auto transform = [](const std::string& fields) {
    const Scene scene = load_world(
        "Shape { appearance Appearance { texture ImageTexture { url \"t.ppm\" }\n"
        "  textureTransform TextureTransform { " +
            fields + " } } geometry Box {} }",
        {{"t.ppm", kTinyPpm}});
    return scene.objects.at(0).material.flat_texture.transform.value();
  };
  const auto apply = [](const std::array<double, 6>& m, double s, double t) {
    return TexCoord{m[0] * s + m[1] * t + m[2], m[3] * s + m[4] * t + m[5]};
  };
  EXPECT_TRUE(near(apply(transform(""), 0.3, 0.7), 0.3, 0.7));
  EXPECT_TRUE(near(apply(transform("scale 2 3"), 0.5, 0.5), 1, 1.5));
  EXPECT_TRUE(near(apply(transform("translation 0.5 0.25"), 0.1, 0.2), 0.6, 0.45));
  // Tc' = -C S R C T Tc: T first, then C, then R (a quarter turn), then S, then -C.
  const TexCoord turned =
      apply(transform("translation 0.1 0 center 0.5 0.5 rotation 1.5707963267948966 scale 2 1"),
            0.2, 0.3);
  // (0.2, 0.3) + T + C = (0.8, 0.8); turned: (-0.8, 0.8); scaled: (-1.6, 0.8); less C.
  EXPECT_TRUE(near(turned, -2.1, 0.3));
}

}  // namespace
}  // namespace tessera::test
