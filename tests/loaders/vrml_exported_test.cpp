// A world in the style modelling tools export (scenes/vrml/exported.wrl.gz, written by
// scripts/make_exported_vrml.py): gzip-compressed, DEF'd Transforms nested 25 deep, a large
// face set with its own normals and texture coordinates, materials and meshes shared with
// DEF/USE, an image texture and animation routes. It loads with the shapes, meshes and
// transforms the file describes; that it renders with every pixel finite is
// tests/render/sample_scenes_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "common/loaders/scene_loader.h"
#include "tests/loaders/vrml_test_util.h"

namespace tessera::test {
namespace {

Scene exported_world() {
  return load_scene_file(std::filesystem::path(TESSERA_SOURCE_DIR) / "scenes/vrml/exported.wrl.gz");
}

TEST(VrmlExported, EveryShapeLoadsAndUseSharesMeshes) {
  const Scene scene = exported_world();
  // The ground, the globe, twelve arm links and eight fence posts (one DEF'd, seven USEs).
  EXPECT_EQ(scene.objects.size(), 22u);
  // Three face sets: the ground, the globe and the link all twelve links USE.
  EXPECT_EQ(scene.meshes.size(), 3u);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].path, "textures/gradient.bmp");
  // The animation is ignored in one warning, the lights all taken.
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("OrientationInterpolator (1), ROUTE (2), TimeSensor (1)"),
            std::string::npos)
      << scene.warnings[0];
  EXPECT_EQ(scene.lights.size(), 2u);  // the sun and the fill light; no headlight
}

TEST(VrmlExported, LargeFaceSetIsTheSphereItTessellates) {
  const Scene scene = exported_world();
  const auto globe = std::max_element(
      scene.meshes.begin(), scene.meshes.end(),
      [](const Mesh& a, const Mesh& b) { return a.triangles.size() < b.triangles.size(); });
  // 40 rings of 80: a triangle at each pole, two per quad between.
  ASSERT_EQ(globe->triangles.size(), 2u * 80 + 2u * 38 * 80);
  // Inscribed in the sphere of radius 1.5: a little less than its area, by about the square of
  // the angle a facet spans.
  const double sphere = 4 * std::numbers::pi * 1.5 * 1.5;
  EXPECT_LT(mesh_area(*globe), sphere);
  EXPECT_GT(mesh_area(*globe), sphere * (1 - 0.01));
  // Given normals, one per corner: unit and radial.
  ASSERT_FALSE(globe->normals.empty());
  for (std::size_t i = 0; i < globe->positions.size(); ++i)
    EXPECT_NEAR(dot(globe->normals[i], globe->positions[i] / 1.5), 1, 1e-3);
  EXPECT_EQ(globe->corner_tex_coords.size(), 3 * globe->triangles.size());
}

TEST(VrmlExported, NestedTransformsCompose) {
  const Scene scene = exported_world();
  // The arm's links, in file order after the ground and the globe: link k (0-based) is k + 1
  // joints deep, each turning about z, and scaled to 0.5 x 0.8^k wide; the whole arm stands
  // at z = -0.5. The file gives the widths to four decimals.
  for (int k = 0; k < 12; ++k) {
    SCOPED_TRACE(k);
    const Affine& link = scene.objects.at(2 + static_cast<std::size_t>(k)).transform;
    EXPECT_NEAR(length(link.apply_vector({1, 0, 0})), 0.5 * std::pow(0.8, k), 0.5e-4);
    EXPECT_NEAR(link.apply_vector({1, 0, 0}).z, 0, 1e-12);
    EXPECT_NEAR(link.apply_point({0, 0, 0}).z, -0.5, 1e-12);
  }
}

}  // namespace
}  // namespace tessera::test
