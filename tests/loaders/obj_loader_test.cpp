// Wavefront OBJ: statements, corner forms, indices, triangulation, unitizing and errors.
#include <gtest/gtest.h>

#include <string>

#include "common/loaders/obj_loader.h"
#include "common/scene/source_location.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

constexpr auto kNo = MeshTriangle::kNoNormal;

::testing::AssertionResult obj_fails_at(const std::string& text, int line, int column,
                                        const std::string& message) {
  try {
    load_obj(text, "m.obj");
  } catch (const SceneError& e) {
    if (e.where().file == "m.obj" && e.where().line == line && e.where().column == column &&
        e.message() == message) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got " << e.what();
  }
  return ::testing::AssertionFailure() << "no error";
}

// Four corners of the square [0, 2]^2 at z = 0 (unitized to [-1, 1]^2), and two normals.
const std::string kSquare = "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nvn 0 0 1\nvn 0 0 -1\n";

TEST(ObjLoader, AllCornerForms) {
  const Mesh mesh = load_obj(kSquare +
                                 "vt 0 0\nvt 1 0\nvt 1 1\n"
                                 "f 1 2 3\n"
                                 "f 1/1 2/2 3/3\n"
                                 "f 1//2 2//1 3//2\n"
                                 "f 1/1/1 2/2/2 3/3/1\n"
                                 "f 4 1/1 2//2\n",
                             "m.obj");
  ASSERT_EQ(mesh.triangles.size(), 5u);
  EXPECT_EQ(mesh.source, "m.obj");
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.normals.size(), 2u);
  const MeshTriangle plain{{0, 1, 2}, {kNo, kNo, kNo}};
  EXPECT_EQ(mesh.triangles[0], plain);
  EXPECT_EQ(mesh.triangles[1], plain);  // texture coordinates are not used
  EXPECT_EQ(mesh.triangles[2], (MeshTriangle{{0, 1, 2}, {1, 0, 1}}));
  EXPECT_EQ(mesh.triangles[3], (MeshTriangle{{0, 1, 2}, {0, 1, 0}}));
  EXPECT_EQ(mesh.triangles[4], (MeshTriangle{{3, 0, 1}, {kNo, kNo, 1}}));
}

TEST(ObjLoader, NegativeIndicesAreRelativeToTheVerticesSoFar) {
  const Mesh mesh = load_obj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
      "f -3//-1 -2//-1 -1//-1\n"
      "v 0 0 1\n"
      "f -4 -1 -2\n",
      "m.obj");
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (MeshTriangle{{0, 1, 2}, {0, 0, 0}}));
  EXPECT_EQ(mesh.triangles[1].v, (std::array<std::uint32_t, 3>{0, 3, 2}));
}

TEST(ObjLoader, PolygonsAreFanTriangulated) {
  const Mesh quad = load_obj(kSquare + "f 1 2 3 4\n", "m.obj");
  ASSERT_EQ(quad.triangles.size(), 2u);
  EXPECT_EQ(quad.triangles[0].v, (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(quad.triangles[1].v, (std::array<std::uint32_t, 3>{0, 2, 3}));
  const Mesh pentagon = load_obj(kSquare + "v 1 3 0\nf 1//1 2//1 3//2 5//2 4//1\n", "m.obj");
  ASSERT_EQ(pentagon.triangles.size(), 3u);
  EXPECT_EQ(pentagon.triangles[2], (MeshTriangle{{0, 4, 3}, {0, 1, 0}}));
}

TEST(ObjLoader, UnitizesOnTheBoundingBox) {
  // Box [0, 4] x [0, 2] x [-1, 1]: centre (2, 1, 0), largest extent 4 -> scale 1/2.
  const Mesh mesh = load_obj("v 0 0 -1\nv 4 0 0\nv 0 2 1\nvn 0 0 5\nf 1 2 3\n", "m.obj");
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], Vec3(-1, -0.5, -0.5));
  EXPECT_EQ(mesh.positions[1], Vec3(1, -0.5, 0));
  EXPECT_EQ(mesh.positions[2], Vec3(-1, 0.5, 0.5));
  EXPECT_EQ(mesh.normals[0], Vec3(0, 0, 5));  // unchanged by a uniform scale
}

TEST(ObjLoader, UnitizesLargeAndOffsetModels) {
  const Mesh mesh = load_obj("v 1000 -500 7\nv 1010 -500 7\nv 1000 -490 8\nf 1 2 3\n", "m.obj");
  EXPECT_EQ(mesh.positions[0], Vec3(-1, -1, -0.1));
  EXPECT_EQ(mesh.positions[1], Vec3(1, -1, -0.1));
  EXPECT_EQ(mesh.positions[2], Vec3(-1, 1, 0.1));
  const Mesh huge = load_obj("v -1e308 0 0\nv 1e308 0 0\nv 0 1e308 0\nf 1 2 3\n", "m.obj");
  EXPECT_EQ(huge.positions[0], Vec3(-1, -0.5, 0));
  EXPECT_EQ(huge.positions[1], Vec3(1, -0.5, 0));
}

TEST(ObjLoader, DegenerateTrianglesAndSinglePointsAreKept) {
  const Mesh mesh = load_obj("v 3 3 3\nf 1 1 1\n", "m.obj");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.positions[0], Vec3(0, 0, 0));  // centred; no extent to scale
}

TEST(ObjLoader, IgnoredStatementsCommentsAndLayout) {
  const Mesh mesh = load_obj(
      "# a comment\r\n"
      "mtllib scene.mtl\r\n"
      "o thing\r\ng group\r\ns 1\r\nusemtl red\r\n"
      "\r\n"
      "   v 0 0 0   # trailing comment\r\n"
      "\tv 1 0 0 1\r\n"          // with w
      "v 0 1 0 0.5 0.5 0.5\r\n"  // with a vertex colour
      "l 1 2\r\np 1\r\n"
      "f 1 2 3# no space before the comment",
      "m.obj");
  EXPECT_EQ(mesh.positions.size(), 3u);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_TRUE(mesh.normals.empty());
}

TEST(ObjLoader, EmptyTextGivesAnEmptyMesh) {
  const Mesh mesh = load_obj("", "m.obj");
  EXPECT_TRUE(mesh.positions.empty());
  EXPECT_TRUE(mesh.triangles.empty());
}

TEST(ObjLoader, IndexErrors) {
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1 2 5\n", 7, 7,
                           "vertex index 5 is out of range (4 defined so far)"));
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1 -5 2\n", 7, 5,
                           "vertex index -5 is out of range (4 defined so far)"));
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1 0 2\n", 7, 5,
                           "vertex index 0 is not valid (indices start at 1)"));
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1//1 2//3 3//1\n", 7, 11,
                           "normal index 3 is out of range (2 defined so far)"));
  EXPECT_TRUE(obj_fails_at(kSquare + "vt 0 0\nf 1/1 2/2 3/1\n", 8, 9,
                           "texture coordinate index 2 is out of range (1 defined so far)"));
  EXPECT_TRUE(obj_fails_at("f 1 2 3\nv 0 0 0\n", 1, 3,
                           "vertex index 1 is out of range (0 defined so far)"));
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1 2.5 3\n", 7, 5, "expected a vertex index, found '2.5'"));
  EXPECT_TRUE(obj_fails_at(kSquare + "f 1 2 99999999999999999999\n", 7, 7,
                           "expected a vertex index, found '99999999999999999999'"));
}

TEST(ObjLoader, CornerAndFaceErrors) {
  for (const std::string corner : {"1/1/1/1", "1/", "/1", "1//", "//1", "1/2/"}) {
    EXPECT_TRUE(
        obj_fails_at(kSquare + "vt 0 0\nf 1 2 " + corner + "\n", 8, 7,
                     "malformed face corner '" + corner + "' (expected v, v/vt, v//vn or v/vt/vn)"))
        << corner;
  }
  EXPECT_TRUE(
      obj_fails_at(kSquare + "  f 1 2\n", 7, 3, "a face needs at least 3 corners, found 2"));
}

TEST(ObjLoader, StatementErrors) {
  EXPECT_TRUE(obj_fails_at("v 0 0 0\n\n  vp 1 2\n", 3, 3, "unknown OBJ statement 'vp'"));
  EXPECT_TRUE(obj_fails_at("V 0 0 0\n", 1, 1, "unknown OBJ statement 'V'"));
  EXPECT_TRUE(obj_fails_at("v 0 zero 0\n", 1, 5, "expected a number for <y> of 'v', found 'zero'"));
  EXPECT_TRUE(obj_fails_at("v 0 nan 0\n", 1, 5, "expected a number for <y> of 'v', found 'nan'"));
  EXPECT_TRUE(obj_fails_at("v 0 1  # z is missing\n", 1, 6,
                           "unexpected end of line, expected a number for <z> of 'v'"));
  EXPECT_TRUE(obj_fails_at("v 0 0 0 1 1\n", 1, 11,
                           "too many values for 'v' (expected x y z [w] or x y z r g b)"));
  EXPECT_TRUE(obj_fails_at("v 0 0 0 1 1 1 1\n", 1, 15,
                           "too many values for 'v' (expected x y z [w] or x y z r g b)"));
  EXPECT_TRUE(obj_fails_at("vn 0 0 1 0\n", 1, 10, "too many values for 'vn' (expected x y z)"));
  EXPECT_TRUE(
      obj_fails_at("vn 0 0\n", 1, 7, "unexpected end of line, expected a number for <z> of 'vn'"));
  EXPECT_TRUE(obj_fails_at("v 1e999 0 0\n", 1, 3, "number '1e999' is out of range"));
}

}  // namespace
}  // namespace tessera::test
