// The current transform (CT): each keyword post-multiplies it, push and pop save and restore it.
#include <gtest/gtest.h>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

const Vec3 kOrigin{0, 0, 0};

TEST(SdlTransform, LastWrittenAppliesToTheShapeFirst) {
  // translate then scale: the sphere is scaled by 2 about its centre, then moved to x = 1.
  const Scene scene = load_text("translate 1 0 0  scale 2 2 2  sphere");
  ASSERT_EQ(scene.objects.size(), 1u);
  const Affine& m = scene.objects[0].transform;
  EXPECT_TRUE(near(m.apply_point(kOrigin), {1, 0, 0}));
  EXPECT_TRUE(near(m.apply_point({1, 0, 0}), {3, 0, 0}));  // radius 2
  EXPECT_TRUE(near(m.apply_point({0, 1, 0}), {1, 2, 0}));
}

TEST(SdlTransform, ScaleThenTranslateScalesTheTranslation) {
  const Scene scene = load_text("scale 2 3 4  translate 1 1 1  cube");
  const Affine& m = scene.objects[0].transform;
  EXPECT_TRUE(near(m.apply_point(kOrigin), {2, 3, 4}));
  EXPECT_TRUE(near(m.apply_point({1, 1, 1}), {4, 6, 8}));
}

TEST(SdlTransform, RotateIsInDegreesAboutTheAxis) {
  const Scene scene = load_text(
      "rotate 90 0 0 1 sphere identityAffine\n"
      "rotate 90 0 0 5 sphere identityAffine\n"  // the axis need not be unit length
      "translate 5 0 0 rotate 90 0 0 1 sphere identityAffine\n"
      "rotate 90 0 0 1 translate 5 0 0 sphere identityAffine\n"
      "rotate -90 1 0 0 sphere");
  ASSERT_EQ(scene.objects.size(), 5u);
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({1, 0, 0}), {0, 1, 0}));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({1, 0, 0}), {0, 1, 0}));
  EXPECT_TRUE(near(scene.objects[2].transform.apply_point({1, 0, 0}), {5, 1, 0}));
  EXPECT_TRUE(near(scene.objects[3].transform.apply_point({1, 0, 0}), {0, 6, 0}));
  EXPECT_TRUE(near(scene.objects[4].transform.apply_point({0, 1, 0}), {0, 0, -1}));
}

TEST(SdlTransform, TransformTakesTheImagesOfTheAxesAsColumns) {
  // x -> (1 0 0), y -> (1 1 0) (a shear), z -> (0 0 2).
  const Scene scene = load_text("translate 0 0 1 transform 1 0 0  1 1 0  0 0 2 sphere");
  const Affine& m = scene.objects[0].transform;
  EXPECT_TRUE(near(m.apply_point(kOrigin), {0, 0, 1}));
  EXPECT_TRUE(near(m.apply_point({1, 0, 0}), {1, 0, 1}));
  EXPECT_TRUE(near(m.apply_point({0, 1, 0}), {1, 1, 1}));
  EXPECT_TRUE(near(m.apply_point({0, 0, 1}), {0, 0, 3}));
}

TEST(SdlTransform, IdentityAffineResetsTheCtButNotTheStack) {
  const Scene scene =
      load_text("translate 1 2 3 push identityAffine sphere translate 0 5 0 pop sphere");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].transform, Affine::identity());
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point(kOrigin), {1, 2, 3}));
}

TEST(SdlTransform, PushAndPopRestoreTheCt) {
  const Scene scene = load_text(
      "translate 1 0 0\n"
      "push translate 0 1 0\n"
      "  push scale 2 2 2 sphere pop\n"
      "  sphere\n"
      "pop\n"
      "sphere");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({1, 0, 0}), {3, 1, 0}));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({1, 0, 0}), {2, 1, 0}));
  EXPECT_TRUE(near(scene.objects[2].transform.apply_point({1, 0, 0}), {2, 0, 0}));
}

TEST(SdlTransform, PushSavesOnlyTheCtNotTheMaterial) {
  const Scene scene = load_text("push diffuse 1 0 0 translate 9 9 9 pop sphere");
  EXPECT_EQ(scene.objects[0].material.diffuse, Rgb(1, 0, 0));
  EXPECT_EQ(scene.objects[0].transform, Affine::identity());
}

TEST(SdlTransform, UnbalancedPushAtEndOfFileIsFine) {
  EXPECT_EQ(load_text("push push sphere").objects.size(), 1u);
}

TEST(SdlTransform, PopWithoutPushIsAnError) {
  EXPECT_TRUE(fails_at("push pop\n  pop", 2, 3, "'pop' without a matching 'push'"));
}

TEST(SdlTransform, RotateAboutAZeroAxisIsAnError) {
  EXPECT_TRUE(fails_at("rotate 30 0 0 0", 1, 11, "'rotate' needs a non-zero axis <ux> <uy> <uz>"));
}

TEST(SdlTransform, ShapesWithASingularCtAreErrors) {
  EXPECT_TRUE(
      fails_at("scale 1 0 1\n sphere", 2, 2, "'sphere' has a singular transform (zero scale?)"));
  EXPECT_TRUE(fails_at("transform 1 0 0 2 0 0 0 0 1 Cube", 1, 29,
                       "'cube' has a singular transform (zero scale?)"));
  // A singular CT with no shape under it is harmless, and identityAffine repairs it.
  EXPECT_EQ(load_text("scale 0 0 0 identityAffine sphere").objects.size(), 1u);
}

TEST(SdlTransform, ShapesWithANonFiniteCtAreErrors) {
  EXPECT_TRUE(fails_at("scale 1e200 1 1 scale 1e200 1 1 cone 0", 1, 33,
                       "'cone' has a transform that is not finite (too large?)"));
}

TEST(SdlTransform, TransformParametersAreNamed) {
  EXPECT_TRUE(
      fails_at("rotate 10 0 1 q", 1, 15, "expected a number for <uz> of 'rotate', found 'q'"));
  EXPECT_TRUE(fails_at("scale 1 1", 1, 10,
                       "unexpected end of file, expected a number for <sz> of 'scale'"));
  EXPECT_TRUE(fails_at("transform 1 0 0 0 1 0 0 0 z", 1, 27,
                       "expected a number for <z3> of 'transform', found 'z'"));
}

}  // namespace
}  // namespace tessera::test
