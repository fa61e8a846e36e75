// Boolean objects (§3.2.4): children with their own transforms and materials, nesting, and
// located errors.
#include <gtest/gtest.h>

#include <string>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlCsg, ChildrenKeepTheirOwnTransformAndMaterial) {
  const Scene scene = load_text(
      "translate 0 0 -1\n"
      "difference\n"
      "  push translate 1 0 0 diffuse 1 0 0 cube pop\n"
      "  push scale 0.5 0.5 0.5 diffuse 0 0 1 sphere pop\n"
      "sphere");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.objects[0].geometry, ShapeGeometry(Cube{}));
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(Sphere{}));
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(CsgShape{CsgOperation::Difference, 0, 1}));
  EXPECT_EQ(scene.objects[3].geometry, ShapeGeometry(Sphere{}));
  // The CT before the boolean object applies to both children, each adds its own.
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({0, 0, 0}), {1, 0, -1}));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({2, 0, 0}), {1, 0, -1}));
  EXPECT_TRUE(near(scene.objects[3].transform.apply_point({0, 0, 0}), {0, 0, -1}));
  EXPECT_EQ(scene.objects[0].material.diffuse, (Rgb{1, 0, 0}));
  EXPECT_EQ(scene.objects[1].material.diffuse, (Rgb{0, 0, 1}));
  // Materials are not scoped by push and pop: the sphere after it keeps the last one.
  EXPECT_EQ(scene.objects[3].material.diffuse, (Rgb{0, 0, 1}));
  // The boolean object is located at its keyword.
  EXPECT_EQ(scene.objects[2].where.line, 2);
  EXPECT_EQ(scene.objects[2].where.column, 1);
}

TEST(SdlCsg, NestsToAnyDepthOnEitherSide) {
  const Scene scene = load_text("UNION intersection sphere cube difference cone 0 torus 0.1 1");
  ASSERT_EQ(scene.objects.size(), 7u);
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(CsgShape{CsgOperation::Intersection, 0, 1}));
  EXPECT_EQ(scene.objects[5].geometry, ShapeGeometry(CsgShape{CsgOperation::Difference, 3, 4}));
  EXPECT_EQ(scene.objects[6].geometry, ShapeGeometry(CsgShape{CsgOperation::Union, 2, 5}));
}

TEST(SdlCsg, ChildrenMayComeFromMacrosAndIncludes) {
  const Scene scene = load_text(
      "def hole { push scale 0.5 0.5 2 cylinder 0 pop }\n"
      "difference include box.sdl use hole",
      {{"box.sdl", "cube"}});
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[1].geometry, ShapeGeometry(TaperedCylinder{1, false}));
  EXPECT_EQ(scene.objects[2].geometry, ShapeGeometry(CsgShape{CsgOperation::Difference, 0, 1}));
}

TEST(SdlCsg, MissingChildIsAnErrorAtTheEnd) {
  EXPECT_TRUE(fails_at("sphere\nunion\n  sphere\n", 4, 1,
                       "unexpected end of file, expected the second child of 'union' at "
                       "scene.sdl:2:1"));
  EXPECT_TRUE(fails_at("intersection push", 1, 18,
                       "unexpected end of file, expected a first child of 'intersection' at "
                       "scene.sdl:1:1"));
  // The innermost open boolean object is named.
  EXPECT_TRUE(fails_at("union sphere difference cube", 1, 29,
                       "unexpected end of file, expected the second child of 'difference' at "
                       "scene.sdl:1:14"));
}

TEST(SdlCsg, ChildThatIsNotAnObjectIsAnError) {
  EXPECT_TRUE(fails_at("union sphere\n  light 0 0 0 1 1 1 sphere", 2, 3,
                       "expected a shape or a boolean object as the next child of 'union' at "
                       "scene.sdl:1:1, found 'light'"));
  EXPECT_TRUE(fails_at("difference background 0 0 0 cube sphere", 1, 12,
                       "expected a shape or a boolean object as the next child of 'difference' "
                       "at scene.sdl:1:1, found 'background'"));
  // Lights and global attributes are fine once both children are read.
  EXPECT_NO_THROW(load_text("union sphere cube light 0 0 0 1 1 1 background 0 0 0"));
}

TEST(SdlCsg, AlgebraicSurfacesAreRefusedAsChildren) {
  EXPECT_TRUE(fails_at("union sphere\ntoothCube 2 2 2", 2, 1,
                       "'toothCube' cannot be a child of 'union' at scene.sdl:1:1: an algebraic "
                       "surface is clipped to a box in world space, not a solid"));
  EXPECT_NO_THROW(load_text("union sphere cube toothCube 2 2 2"));
}

TEST(SdlCsg, NestingDepthIsLimited) {
  std::string text;
  for (int i = 0; i < 300; ++i) text += "union ";
  EXPECT_TRUE(
      fails_at(text, 1, 1 + 6 * 256,
               "boolean objects are nested too deeply (more than 256 levels) (limit csg_depth)"));
}

}  // namespace
}  // namespace tessera::test
