// Hill's SDL (F.S. Hill, "Computer Graphics Using OpenGL"), the dialect the manual extends:
// `square`, `torus` without parameters, `cone`, `cylinder` and `taperedCylinder` without the
// <distort-texture> flag, `mesh` without <interpolate-normals>, meshes told by their content,
// `.dat` scene files. Shapes are probed with rays parallel to an axis, so that where a ray hits
// follows from the shape's definition without a camera's perspective.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/loaders/scene_loader.h"
#include "tests/loaders/loader_test_util.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

// Whether a ray from `origin` along `direction` hits anything: the scene's shapes glow white
// over a black background and there is no light, so a ray sees 1 or 0.
class Probe {
 public:
  explicit Probe(const std::string& shapes)
      : scene_(load_text("background 0 0 0 globalAmbient 0 0 0 emissive 1 1 1 " + shapes)),
        prepared_(scene_, BvhMode::Sah) {}

  bool hits(const Vec3& origin, const Vec3& direction) const {
    return trace_ray(prepared_, Ray{origin, direction}).r > 0.5;
  }

 private:
  Scene scene_;  // PreparedScene refers to it
  PreparedScene prepared_;
};

const Vec3 kDown{0, 0, -1};  // from z = 5 towards the XY-plane
const Vec3 kLeft{-1, 0, 0};  // from x = 5 towards the YZ-plane

TEST(SdlHillDialect, SquareIsTheUnitSquareOfThePlaneZZero) {
  const Probe probe("square");
  // Its silhouette seen along z: the area of [-1, 1]², sampled at the centres of a grid of
  // 0.05 cells over [-2, 2]².
  int inside = 0;
  for (int i = 0; i < 80; ++i) {
    for (int j = 0; j < 80; ++j) {
      if (probe.hits({-2 + 0.05 * (i + 0.5), -2 + 0.05 * (j + 0.5), 5}, kDown)) ++inside;
    }
  }
  EXPECT_EQ(inside, 40 * 40);
  // Flat: a ray in the plane z = 0 off to the side, or one along x above or below, misses.
  EXPECT_FALSE(probe.hits({5, 0, 0.01}, kLeft));
  EXPECT_FALSE(probe.hits({5, 0, -0.01}, kLeft));
}

TEST(SdlHillDialect, SquareFacesPlusZ) {
  const Scene scene = load_text("square");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Mesh& mesh = scene.meshes.at(std::get<MeshShape>(scene.objects[0].geometry).mesh);
  for (const MeshTriangle& t : mesh.triangles) {
    const Vec3 normal = cross(mesh.positions[t.v[1]] - mesh.positions[t.v[0]],
                              mesh.positions[t.v[2]] - mesh.positions[t.v[0]]);
    EXPECT_GT(normal.z, 0);
  }
}

TEST(SdlHillDialect, ConeStandsOnZZeroWithItsApexAtZOne) {
  // Seen along -x at y = 0.5, the cone's radius 1 - z is over 0.5 only below z = 0.5.
  const Probe probe("cone");
  EXPECT_TRUE(probe.hits({5, 0.5, 0.45}, kLeft));
  EXPECT_FALSE(probe.hits({5, 0.5, 0.55}, kLeft));
  EXPECT_TRUE(probe.hits({5, 0, 0.95}, kLeft));    // near the apex
  EXPECT_FALSE(probe.hits({5, 0, 1.05}, kLeft));   // past it
  EXPECT_FALSE(probe.hits({5, 0, -0.05}, kLeft));  // below the base
  EXPECT_TRUE(probe.hits({0.95, 0, 5}, kDown));    // the base's rim, seen from above
}

TEST(SdlHillDialect, CylinderHasRadiusOneFromZZeroToOne) {
  const Probe probe("cylinder");
  EXPECT_TRUE(probe.hits({5, 0.95, 0.95}, kLeft));
  EXPECT_FALSE(probe.hits({5, 1.05, 0.5}, kLeft));
  EXPECT_FALSE(probe.hits({5, 0, 1.05}, kLeft));
}

TEST(SdlHillDialect, TorusWithoutParametersIsHillsTube02Ring1) {
  // Around the z axis: the tube, radius 0.2, runs around the circle of radius 1 in z = 0.
  const Probe probe("torus");
  EXPECT_TRUE(probe.hits({1.15, 0, 5}, kDown));
  EXPECT_FALSE(probe.hits({1.25, 0, 5}, kDown));
  EXPECT_TRUE(probe.hits({0.85, 0, 5}, kDown));
  EXPECT_FALSE(probe.hits({0.75, 0, 5}, kDown));
  EXPECT_TRUE(probe.hits({5, 0, 0.15}, kLeft));
  EXPECT_FALSE(probe.hits({5, 0, 0.25}, kLeft));
  EXPECT_EQ(load_text("torus").objects.at(0).geometry, ShapeGeometry(Torus{0.2, 1}));
}

TEST(SdlHillDialect, TrailingParametersMayBeLeftOut) {
  const Scene scene = load_text(
      "cone translate 1 0 0 cylinder\n"
      "taperedCylinder 0.5 sphere\n"
      "cone 1 cylinder 2 taperedCylinder 0.5 1\n"
      "torus square\n");
  ASSERT_EQ(scene.objects.size(), 9u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(TaperedCylinder{0, false}));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({0, 0, 0}), {1, 0, 0}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(TaperedCylinder{1, false}));
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(TaperedCylinder{0.5, false}));
  EXPECT_EQ(scene.objects[3].geometry, ShapeGeometry(Sphere{}));
  // Written, the manual's flag is read as before.
  EXPECT_EQ(scene.objects[4].geometry, ShapeGeometry(TaperedCylinder{0, true}));
  EXPECT_EQ(scene.objects[5].geometry, ShapeGeometry(TaperedCylinder{1, true}));
  EXPECT_EQ(scene.objects[6].geometry, ShapeGeometry(TaperedCylinder{0.5, true}));
  EXPECT_EQ(scene.objects[8].where.line, 4);
}

TEST(SdlHillDialect, ALeftOutParameterMayFollowAMacroReplay) {
  const Scene scene = load_text("def c { cone } use c 1 use c sphere");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(TaperedCylinder{0, true}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(TaperedCylinder{0, false}));
}

TEST(SdlHillDialect, AWordAfterAShapeIsTheNextStatement) {
  // Not a parameter: the next keyword, so a misspelt flag is reported as a keyword.
  EXPECT_TRUE(fails_at("cylinder yes", 1, 10, "unknown keyword 'yes'"));
  EXPECT_TRUE(fails_at("torus 1", 1, 8,
                       "unexpected end of file, expected a number for <torus-radius> of 'torus'"));
}

const char* const kSquare3vn = "4 1 1\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1\n4 0 1 2 3 0 0 0 0\n";
const char* const kTriangle3dv = "3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
const char* const kTriangle3dm = "3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST(SdlHillDialect, MeshWithoutTheFlagInterpolatesTheFilesNormals) {
  const Scene scene = load_text("mesh a.3vn sphere mesh a.3vn 0", {{"a.3vn", kSquare3vn}});
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(MeshShape{0, true}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(Sphere{}));
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(MeshShape{0, false}));
}

TEST(SdlHillDialect, HillMeshesAreToldByTheirContentWhateverTheirName) {
  const Scene scene = load_text(
      "mesh a.txt mesh b.dat mesh c mesh D.TXT",
      {{"a.txt", kSquare3vn}, {"b.dat", kTriangle3dv}, {"c", kTriangle3dm}, {"D.TXT", kSquare3vn}});
  ASSERT_EQ(scene.meshes.size(), 4u);
  // 3VN: one normal shared by the square's four corners, two triangles.
  EXPECT_EQ(scene.meshes[0].normals.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 2u);
  // 3DV: a normal per vertex, read from the file.
  EXPECT_EQ(scene.meshes[1].normals.size(), 3u);
  EXPECT_EQ(scene.meshes[1].normals[2], (Vec3{0, 0, 1}));
  // 3DM: normals computed from the face (area-weighted, then normalized).
  EXPECT_EQ(scene.meshes[2].normals.size(), 3u);
  EXPECT_TRUE(near(scene.meshes[2].normals[0], {0, 0, 1}));
  EXPECT_EQ(scene.meshes[3].triangles.size(), 2u);
}

TEST(SdlHillDialect, AMeshOfUnknownContentIsAnErrorInTheMeshFile) {
  EXPECT_TRUE(fails_with("mesh car.ply", "car.ply", 1, 1,
                         "the format of the mesh is unknown: OBJ files are named .obj, and "
                         "3VN, 3DV and 3DM files start with a count of vertices",
                         {{"car.ply", "ply\nformat ascii 1.0\n"}}));
  // Numbers that fit no layout: the error of the one that read furthest (here 3VN, whose face
  // names a normal that is not there).
  EXPECT_TRUE(
      fails_with("mesh bad.txt", "bad.txt", 4, 17,
                 "normal index 1 is out of range (1 defined, indices start at 0)",
                 {{"bad.txt", "4 1 1\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1\n4 0 1 2 3 0 0 0 1\n"}}));
}

TEST(SdlHillDialect, HillsTextureKeywordsAreReadAndIgnoredWithAWarning) {
  const Scene scene = load_text(
      "makePixmap 1 neat.bmp\n"
      "texture 1 parameters 4 -1 -1 1 1 specularFraction 0.5\n"
      "square texture -2 sphere");
  ASSERT_EQ(scene.objects.size(), 2u);  // the parameters are read, not taken for statements
  EXPECT_EQ(scene.objects[0].material, Material{});
  const std::string textures = "Tessera has its own textures (solidTexture, imageTexture)";
  EXPECT_EQ(scene.warnings,
            (std::vector<std::string>{
                "scene.sdl:1:1: Hill's 'makePixmap' is ignored: " + textures,
                "scene.sdl:2:1: Hill's 'texture' is ignored: " + textures,
                "scene.sdl:2:11: Hill's 'parameters' is ignored: " + textures,
                "scene.sdl:2:34: Hill's 'specularFraction' is ignored: Tessera shades with "
                "Phong's model, not Cook-Torrance's",
                "scene.sdl:3:8: Hill's 'texture' is ignored: " + textures}));
  EXPECT_TRUE(fails_at("parameters 11", 1, 12,
                       "<count> of 'parameters' must be between 0 and 10, found '11'"));
  EXPECT_TRUE(fails_at("texture", 1, 8,
                       "unexpected end of file, expected a number for <type> of 'texture'"));
}

// Reproductions of what stops scene files from courses built on Hill's book: keywords their own
// copies of his parser added, and his infinite plane (docs/SDL.md §4.12, §8).
TEST(SdlHillDialect, KeywordsThatAreNotHillsStayErrors) {
  EXPECT_TRUE(fails_at("specular 1 1 1\nexponent 50", 2, 1, "unknown keyword 'exponent'"));
  EXPECT_TRUE(fails_at("push extrude hlArch2.dat pop", 1, 6, "unknown keyword 'extrude'"));
  EXPECT_TRUE(fails_at("taperedTube 1.0 .05", 1, 1, "unknown keyword 'taperedTube'"));
  EXPECT_TRUE(fails_at("plane", 1, 1, "unknown keyword 'plane'"));
}

TEST(SdlHillDialect, DatFilesAreSdlScenes) {
  EXPECT_EQ(scene_format_of("scenes/hill.dat"), SceneFormat::Sdl);
  EXPECT_EQ(scene_format_of("SCENE.DAT"), SceneFormat::Sdl);
  MemorySource source;
  source.add("scene.dat", "square cone");
  EXPECT_EQ(load_scene(source, "scene.dat", scene_format_of("scene.dat")).objects.size(), 2u);
}

}  // namespace
}  // namespace tessera::test
