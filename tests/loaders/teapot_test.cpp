// The teapot of §3.3.3: the shipped mesh, its size, orientation, normals and seams, and the
// keyword.
#include "common/loaders/teapot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/loaders/loader_test_util.h"
#include "tests/loaders/mesh_checks.h"

namespace tessera::test {
namespace {

TEST(Teapot, CompiledInIsTheShippedFile) {
  std::ifstream file(TESSERA_SOURCE_DIR "/scenes/meshes/teapot.obj", std::ios::binary);
  ASSERT_TRUE(file);
  std::ostringstream text;
  text << file.rdbuf();
  EXPECT_EQ(teapot_obj(), text.str());
}

TEST(Teapot, SixThousandThreeHundredAndTwentyTriangles) {
  // 32 patches of 10 x 10 quads, less the 8 x 10 that collapse at the poles of the lid and the
  // bottom: the face count the manual gives. Vertices are welded along the patches' seams.
  const Mesh mesh = teapot_mesh();
  EXPECT_EQ(mesh.source, "teapot");
  EXPECT_EQ(mesh.triangles.size(), 6320u);
  EXPECT_EQ(mesh.positions.size(), 3241u);
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
}

TEST(Teapot, UnitizedUprightSpoutAlongX) {
  const Mesh mesh = teapot_mesh();
  Vec3 lo = mesh.positions[0], hi = lo, knob = lo, spout = lo;
  for (const Vec3& p : mesh.positions) {
    lo = min(lo, p);
    hi = max(hi, p);
    if (p.y > knob.y) knob = p;
    if (p.x > spout.x) spout = p;
  }
  // Spout tip to handle is the longest extent: x spans [-1, 1]; the others are centred.
  EXPECT_NEAR(lo.x, -1, 1e-12);
  EXPECT_NEAR(hi.x, 1, 1e-12);
  EXPECT_NEAR(lo.y + hi.y, 0, 1e-12);
  EXPECT_NEAR(lo.z + hi.z, 0, 1e-12);
  // Height 3.15 and depth 4 of the patch data over its length 6.434.
  EXPECT_NEAR(hi.y - lo.y, 2 * 3.15 / 6.434, 1e-6);
  EXPECT_NEAR(hi.z - lo.z, 2 * 4 / 6.434, 1e-6);
  // The knob is on top, above the body's axis; the spout's tip is in the upper half.
  EXPECT_NEAR(knob.x, (0 - (3.434 - 3) / 2) / 3.217, 1e-6);
  EXPECT_NEAR(knob.z, 0, 1e-12);
  EXPECT_GT(spout.y, 0.2);
}

TEST(Teapot, VertexNormalsAgreeWithTheWinding) {
  const Mesh mesh = teapot_mesh();
  for (const MeshTriangle& t : mesh.triangles) {
    const Vec3& p0 = mesh.positions[t.v[0]];
    const Vec3 geometric = cross(mesh.positions[t.v[1]] - p0, mesh.positions[t.v[2]] - p0);
    const Vec3 shading = mesh.normals[t.n[0]] + mesh.normals[t.n[1]] + mesh.normals[t.n[2]];
    EXPECT_GT(dot(geometric, shading), 0);
    EXPECT_GT(length(geometric), 0);  // no degenerate triangle left
  }
}

TEST(Teapot, SeamsAreClosedExceptTheOpenings) {
  // Every edge is used at most twice and never twice in the same direction. The edges used
  // once are the openings of the Newell teapot: the rim the lid sits in and the lid's own edge
  // (40 each), and both ends of the spout and of the handle (20 each).
  const Mesh mesh = teapot_mesh();
  int boundary = 0;
  for (const auto& [edge, use] : edge_uses(mesh)) {
    EXPECT_LE(use.forward, 1);
    EXPECT_LE(use.backward, 1);
    if (use.forward + use.backward == 1) ++boundary;
  }
  EXPECT_EQ(boundary, 160);
}

TEST(Teapot, KeywordSharesOnePhongShadedMesh) {
  const Scene scene = load_text("teapot translate 2 0 0 TEAPOT");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 6320u);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(MeshShape{0, true}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(MeshShape{0, true}));
}

}  // namespace
}  // namespace tessera::test
