// Shapes (§3.3): geometry, flags, meshes and the keywords of later issues.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlShapes, GenericShapes) {
  const Scene scene = load_text(
      "sphere cube\n"
      "cone 1 cone 0\n"
      "cylinder 0 cylinder -2.5\n"
      "taperedCylinder 0.25 1 taperedCylinder 0 0.0");
  ASSERT_EQ(scene.objects.size(), 8u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(Sphere{}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(Cube{}));
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(TaperedCylinder{0, true}));
  EXPECT_EQ(scene.objects[3].geometry, ShapeGeometry(TaperedCylinder{0, false}));
  EXPECT_EQ(scene.objects[4].geometry, ShapeGeometry(TaperedCylinder{1, false}));
  EXPECT_EQ(scene.objects[5].geometry, ShapeGeometry(TaperedCylinder{1, true}));  // non-zero
  EXPECT_EQ(scene.objects[6].geometry, ShapeGeometry(TaperedCylinder{0.25, true}));
  EXPECT_EQ(scene.objects[7].geometry, ShapeGeometry(TaperedCylinder{0, false}));
  EXPECT_EQ(scene.objects[6].where.line, 4);
  EXPECT_EQ(scene.objects[7].where.column, 24);
}

TEST(SdlShapes, ShapeParameterErrors) {
  EXPECT_TRUE(fails_at("taperedCylinder -0.5 0", 1, 17,
                       "<small-radius> of 'taperedCylinder' must be non-negative, found '-0.5'"));
  EXPECT_TRUE(fails_at("taperedCylinder", 1, 16,
                       "unexpected end of file, expected a number for <small-radius> of "
                       "'taperedCylinder'"));
}

TEST(SdlShapes, TorusTakesTubeThenTorusRadius) {
  const Scene scene = load_text("torus 0.25 1\nTorus 1 1 torus 2 0.5\ntranslate 0 0 4 torus 1 3");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(Torus{0.25, 1}));  // ring
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(Torus{1, 1}));     // horn
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(Torus{2, 0.5}));   // spindle
  EXPECT_EQ(scene.objects[2].where.line, 2);
  EXPECT_EQ(scene.objects[2].where.column, 11);
  EXPECT_TRUE(near(scene.objects[3].transform.apply_point({0, 0, 0}), {0, 0, 4}));
}

TEST(SdlShapes, TorusParameterErrors) {
  EXPECT_TRUE(fails_at("torus 0 1", 1, 7, "<tube-radius> of 'torus' must be positive, found '0'"));
  EXPECT_TRUE(
      fails_at("torus 1 -2", 1, 9, "<torus-radius> of 'torus' must be positive, found '-2'"));
  EXPECT_TRUE(
      fails_at("torus 1\n  x", 2, 3, "expected a number for <torus-radius> of 'torus', found 'x'"));
  EXPECT_TRUE(fails_at("torus 1", 1, 8,
                       "unexpected end of file, expected a number for <torus-radius> of "
                       "'torus'"));
}

TEST(SdlShapes, AlgebraicSurfacesTakeTheirBoxExtent) {
  const std::pair<const char*, AlgebraicKind> kinds[] = {
      {"oneSheetHyperboloid", AlgebraicKind::OneSheetHyperboloid},
      {"twoSheetHyperboloid", AlgebraicKind::TwoSheetHyperboloid},
      {"ellipticCylinder", AlgebraicKind::EllipticCylinder},
      {"ellipticCone", AlgebraicKind::EllipticCone},
      {"ellipticParaboloid", AlgebraicKind::EllipticParaboloid},
      {"hyperbolicParaboloid", AlgebraicKind::HyperbolicParaboloid},
      {"pinchedSurfaceWithHoles", AlgebraicKind::PinchedSurfaceWithHoles},
      {"pinchedSurfaceWithLobe", AlgebraicKind::PinchedSurfaceWithLobe},
      {"fourLobes", AlgebraicKind::FourLobes},
      {"steinersRomanSurface", AlgebraicKind::SteinersRomanSurface},
      {"toothCube", AlgebraicKind::ToothCube}};
  for (const auto& [keyword, kind] : kinds) {
    SCOPED_TRACE(keyword);
    const Scene scene = load_text(std::string("translate 1 2 3\n  ") + keyword + " 4 5 6");
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(AlgebraicSurface{kind, {4, 5, 6}}));
    EXPECT_EQ(scene.objects[0].where.line, 2);
    EXPECT_EQ(scene.objects[0].where.column, 3);
    EXPECT_TRUE(near(scene.objects[0].transform.apply_point({0, 0, 0}), {1, 2, 3}));
    const std::string name = keyword;
    EXPECT_TRUE(fails_at(name + " 1 0 1", 1, static_cast<int>(name.size()) + 4,
                         "<box-extent-height> of '" + name + "' must be positive, found '0'"));
  }
  // Case-insensitive, like every keyword.
  EXPECT_EQ(load_text("TOOTHCUBE 1 1 1").objects[0].geometry,
            ShapeGeometry(AlgebraicSurface{AlgebraicKind::ToothCube, {1, 1, 1}}));
}

TEST(SdlShapes, AlgebraicSurfaceParameterErrors) {
  EXPECT_TRUE(fails_at("ellipticCone 0 1 1", 1, 14,
                       "<box-extent-width> of 'ellipticCone' must be positive, found '0'"));
  EXPECT_TRUE(fails_at("fourLobes 1 -1 1", 1, 13,
                       "<box-extent-height> of 'fourLobes' must be positive, found '-1'"));
  EXPECT_TRUE(fails_at("sphere\ntoothCube 1 1 z", 2, 15,
                       "expected a number for <box-extent-depth> of 'toothCube', found 'z'"));
  EXPECT_TRUE(fails_at("steinersRomanSurface 1 1", 1, 25,
                       "unexpected end of file, expected a number for <box-extent-depth> of "
                       "'steinersRomanSurface'"));
}

TEST(SdlShapes, MeshLoadsAnObjFileResolvedRelativeToTheScene) {
  const Scene scene =
      load_text("mesh models/tri.obj 1\nmesh models/tri.obj 0", {{"models/tri.obj", kTriangleObj}});
  ASSERT_EQ(scene.meshes.size(), 1u);  // loaded once, shared
  EXPECT_EQ(scene.meshes[0].source, "models/tri.obj");
  EXPECT_EQ(scene.meshes[0].triangles.size(), 1u);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(MeshShape{0, true}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(MeshShape{0, false}));
}

TEST(SdlShapes, DifferentSpellingsOfOneMeshPathShareIt) {
  const Scene scene = load_text(
      "mesh a/tri.obj 0  mesh ./a/../a/tri.obj 0  mesh a/other.OBJ 0",
      {{"a/tri.obj", kTriangleObj}, {"a/other.OBJ", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3"}});
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(std::get<MeshShape>(scene.objects[1].geometry).mesh, 0u);
  EXPECT_EQ(std::get<MeshShape>(scene.objects[2].geometry).mesh, 1u);
  EXPECT_EQ(scene.meshes[1].source, "a/other.OBJ");
}

TEST(SdlShapes, MeshNamesInIncludedFilesAreRelativeToThatFile) {
  const Scene scene =
      load_text("include parts/car.sdl", {{"parts/car.sdl", "mesh wheel.obj 0\nmesh ../body.obj 0"},
                                          {"parts/wheel.obj", kTriangleObj},
                                          {"body.obj", kTriangleObj}});
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].source, "parts/wheel.obj");
  EXPECT_EQ(scene.meshes[1].source, "body.obj");
}

TEST(SdlShapes, MeshUsesTheCtAndMaterial) {
  const Scene scene =
      load_text("diffuse 0 1 0 translate 0 0 4 mesh tri.obj 0", {{"tri.obj", kTriangleObj}});
  EXPECT_EQ(scene.objects[0].material.diffuse, Rgb(0, 1, 0));
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({0, 0, 0}), {0, 0, 4}));
}

TEST(SdlShapes, MeshFormatGoesByTheExtensionInAnyCase) {
  const std::string square3vn = "4 1 1\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1\n4 0 1 2 3 0 0 0 0\n";
  const std::string square3dv = "3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  const std::string square3dm = "3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const Scene scene = load_text(
      "mesh a.3VN 1 mesh b.3Dv 0 mesh c.3dm 1 mesh d.Obj 0",
      {{"a.3VN", square3vn}, {"b.3Dv", square3dv}, {"c.3dm", square3dm}, {"d.Obj", kTriangleObj}});
  ASSERT_EQ(scene.meshes.size(), 4u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 2u);
  EXPECT_EQ(scene.meshes[0].normals.size(), 1u);
  EXPECT_EQ(scene.meshes[1].normals.size(), 3u);
  EXPECT_EQ(scene.meshes[2].normals.size(), 3u);  // computed
  // Only OBJ is unitized: the 3DM triangle keeps its coordinates.
  EXPECT_EQ(scene.meshes[2].positions[1], (Vec3{1, 0, 0}));
  EXPECT_EQ(scene.meshes[3].positions[1], (Vec3{1, -1, 0}));
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(MeshShape{0, true}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(MeshShape{1, false}));
}

TEST(SdlShapes, OnlyTheFileNamesExtensionCounts) {
  // `dir.obj/car` has no extension: it is read as a Hill mesh, by its content.
  EXPECT_EQ(load_text("mesh dir.obj/car 0", {{"dir.obj/car", "3 1\n0 0 0 1 0 0 0 1 0\n3 0 1 2\n"}})
                .meshes.size(),
            1u);
}

TEST(SdlShapes, MeshFileErrors) {
  EXPECT_TRUE(fails_at("sphere\nmesh  nope.obj 0", 2, 7, "mesh file 'nope.obj' not found"));
  EXPECT_TRUE(fails_at("mesh ../up.obj 0", 1, 6, "mesh '../up.obj' leaves the scene's folder"));
  EXPECT_TRUE(fails_at("mesh /etc/x.obj 0", 1, 6, "mesh '/etc/x.obj' leaves the scene's folder"));
  EXPECT_TRUE(fails_at("mesh empty.obj 0", 1, 6, "mesh 'empty.obj' has no triangles",
                       {{"empty.obj", "v 0 0 0\nv 1 0 0\n# no faces\n"}}));
  EXPECT_TRUE(fails_at("mesh", 1, 5,
                       "unexpected end of file, expected a file name for <filename> of 'mesh'"));
}

TEST(SdlShapes, ObjErrorsAreLocatedInTheObjFile) {
  EXPECT_TRUE(fails_with("mesh m/bad.obj 0", "m/bad.obj", 2, 5,
                         "vertex index 7 is out of range (1 defined so far)",
                         {{"m/bad.obj", "v 0 0 0\nf 1 7 1\n"}}));
}

TEST(SdlShapes, HillMeshErrorsAreLocatedInTheMeshFile) {
  EXPECT_TRUE(fails_with("mesh m/bad.3dm 0", "m/bad.3dm", 3, 3,
                         "vertex index 3 is out of range (3 defined, indices start at 0)",
                         {{"m/bad.3dm", "3 1\n0 0 0 1 0 0 0 1 0\n3 3 1 2\n"}}));
}

TEST(SdlShapes, MeshWithASingularCtIsAnError) {
  EXPECT_TRUE(fails_at("scale 0 1 1 mesh tri.obj 0", 1, 13,
                       "'mesh' has a singular transform (zero scale?)",
                       {{"tri.obj", kTriangleObj}}));
}

TEST(SdlShapes, PolyhedraAreFlatShadedMeshesSharedByTheirInstances) {
  const Scene scene = load_text(
      "buckyball diamond dodecahedron icosahedron octahedron pyramid tetrahedron\n"
      "translate 1 2 3 Octahedron");
  ASSERT_EQ(scene.objects.size(), 8u);
  ASSERT_EQ(scene.meshes.size(), 7u);  // one per polyhedron, not per instance
  const char* names[] = {"buckyball",  "diamond", "dodecahedron", "icosahedron",
                         "octahedron", "pyramid", "tetrahedron"};
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(scene.objects[i].geometry, ShapeGeometry(MeshShape{i, false}));
    EXPECT_EQ(scene.meshes[i].source, names[i]);
  }
  EXPECT_EQ(scene.objects[7].geometry, ShapeGeometry(MeshShape{4, false}));
  EXPECT_TRUE(near(scene.objects[7].transform.apply_point({0, 0, 0}), {1, 2, 3}));
  EXPECT_EQ(scene.objects[7].where.line, 2);
  EXPECT_EQ(scene.objects[7].where.column, 17);
}

TEST(SdlShapes, PolyhedraShareMeshesWithNoMeshFile) {
  // A mesh file named like a polyhedron is a different mesh.
  const Scene scene =
      load_text("mesh octahedron.obj 0 octahedron", {{"octahedron.obj", kTriangleObj}});
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 1u);
  EXPECT_EQ(scene.meshes[1].triangles.size(), 8u);
}

}  // namespace
}  // namespace tessera::test
