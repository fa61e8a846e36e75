// 3VN, 3DV and 3DM meshes (§3.3.4): layouts, 0-based indices, computed normals and errors.
#include "common/loaders/hill_mesh_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/scene/source_location.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

using Loader = Mesh (*)(std::string_view, const std::string&);

::testing::AssertionResult mesh_fails_at(Loader load, const std::string& text, int line, int column,
                                         const std::string& message) {
  try {
    load(text, "m.x");
  } catch (const SceneError& e) {
    if (e.where().file == "m.x" && e.where().line == line && e.where().column == column &&
        e.message() == message) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got " << e.what();
  }
  return ::testing::AssertionFailure() << "no error";
}

TEST(HillMesh, ThreeVnHasSeparateVertexAndNormalIndices) {
  // A square (one quad) and a triangle, with two normals.
  const Mesh mesh = load_3vn(
      "5 2 2\n"
      "0 0 0  2 0 0  2 2 0  0 2 0  0 0 3\n"
      "0 0 1  0 -1 0\n"
      "4  0 1 2 3  0 0 0 0\n"
      "3  0 1 4  1 1 0\n",
      "m.3vn");
  EXPECT_EQ(mesh.source, "m.3vn");
  ASSERT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.positions[2], (Vec3{2, 2, 0}));  // not unitized
  ASSERT_EQ(mesh.normals.size(), 2u);
  EXPECT_EQ(mesh.normals[1], (Vec3{0, -1, 0}));
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], (MeshTriangle{{0, 1, 2}, {0, 0, 0}}));
  EXPECT_EQ(mesh.triangles[1], (MeshTriangle{{0, 2, 3}, {0, 0, 0}}));
  EXPECT_EQ(mesh.triangles[2], (MeshTriangle{{0, 1, 4}, {1, 1, 0}}));
}

TEST(HillMesh, ThreeDvStoresANormalWithEveryVertex) {
  const Mesh mesh = load_3dv(
      "4 1\n"
      "0 0 0  0 0 1\n"
      "1 0 0  0 0.5 1\n"
      "1 1 0  0 0 1\n"
      "0 1 0  0 0 2\n"
      "4 3 2 1 0\n",
      "m.3dv");
  ASSERT_EQ(mesh.positions.size(), 4u);
  ASSERT_EQ(mesh.normals.size(), 4u);
  EXPECT_EQ(mesh.positions[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(mesh.normals[1], (Vec3{0, 0.5, 1}));
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], (MeshTriangle{{3, 2, 1}, {3, 2, 1}}));
  EXPECT_EQ(mesh.triangles[1], (MeshTriangle{{3, 1, 0}, {3, 1, 0}}));
}

TEST(HillMesh, ThreeDmComputesAreaWeightedVertexNormals) {
  // Two faces meeting at the edge 0-1 at a right angle: the floor (area 1/2, normal +z) and a
  // wall (area 2, normal -y).
  const Mesh mesh = load_3dm(
      "5 2\n"
      "0 0 0  1 0 0  0 1 0  0 0 2  1 0 2\n"
      "3 0 1 2\n"
      "4 0 1 4 3\n",
      "m.3dm");
  ASSERT_EQ(mesh.normals.size(), 5u);
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[1], (MeshTriangle{{0, 1, 4}, {0, 1, 4}}));
  EXPECT_TRUE(near(mesh.normals[2], {0, 0, 1}));
  EXPECT_TRUE(near(mesh.normals[3], {0, -1, 0}));
  // Weighted by area, 1/2 of +z and 2 of -y, at both ends of the shared edge.
  const Vec3 shared = Vec3{0, -4, 1} / std::sqrt(17.0);
  EXPECT_TRUE(near(mesh.normals[0], shared, 1e-15));
  EXPECT_TRUE(near(mesh.normals[1], shared, 1e-15));
}

TEST(HillMesh, WhitespaceIsFree) {
  const Mesh mesh = load_3dm("3\r\n1\t0 0 0\r1 0 0 0 1 0 3 0 1\n\n 2\n", "m.3dm");
  EXPECT_EQ(mesh.triangles.size(), 1u);
}

TEST(HillMesh, CountErrors) {
  EXPECT_TRUE(mesh_fails_at(load_3dm, "", 1, 1,
                            "unexpected end of file, expected a non-negative count for #vertices"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, "-1 0", 1, 1,
                            "expected a non-negative count for #vertices, found '-1'"));
  EXPECT_TRUE(mesh_fails_at(load_3vn, "3 x 1", 1, 3,
                            "expected a non-negative count for #normals, found 'x'"));
  EXPECT_TRUE(mesh_fails_at(load_3dv, "3 2.5", 1, 3,
                            "expected a non-negative count for #faces, found '2.5'"));
  // A count larger than the file fails at its end, not in an allocation.
  EXPECT_TRUE(mesh_fails_at(load_3dm, "1000000000000 0\n1 2 3\n", 2, 6,
                            "unexpected end of file, expected a number for x of vertex 1"));
}

TEST(HillMesh, NumberErrors) {
  EXPECT_TRUE(mesh_fails_at(load_3dm, "1 0\n0 zero 0", 2, 3,
                            "expected a number for y of vertex 0, found 'zero'"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, "1 0\n0 0 1e999", 2, 5, "number '1e999' is out of range"));
  EXPECT_TRUE(mesh_fails_at(load_3dv, "1 0\n0 0 0\n0 0", 3, 4,
                            "unexpected end of file, expected a number for z of normal 0"));
  EXPECT_TRUE(mesh_fails_at(load_3vn, "1 2 0\n0 0 0\n0 0 1\n0 1 nan", 4, 5,
                            "expected a number for z of normal 1, found 'nan'"));
}

TEST(HillMesh, FaceErrors) {
  const std::string triangle = "3 1\n0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_TRUE(mesh_fails_at(load_3dm, triangle + "2 0 1", 5, 1,
                            "face 0 needs at least 3 vertices, found 2"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, triangle + "3 0 1 3", 5, 7,
                            "vertex index 3 is out of range (3 defined, indices start at 0)"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, triangle + "3 0 -1 2", 5, 5,
                            "expected a vertex index of face 0, found '-1'"));
  EXPECT_TRUE(
      mesh_fails_at(load_3dm, triangle + "3 0 1 2 x", 5, 9, "unexpected 'x' after the last face"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, triangle + "3 0 1", 5, 6,
                            "unexpected end of file, expected a vertex index of face 0"));
  EXPECT_TRUE(mesh_fails_at(load_3dm, triangle + "x", 5, 1,
                            "expected the number of vertices of face 0, found 'x'"));
  EXPECT_TRUE(mesh_fails_at(load_3vn, "3 1 1\n0 0 0 1 0 0 0 1 0\n0 0 1\n3 0 1 2 0 1 0", 4, 11,
                            "normal index 1 is out of range (1 defined, indices start at 0)"));
}

}  // namespace
}  // namespace tessera::test
