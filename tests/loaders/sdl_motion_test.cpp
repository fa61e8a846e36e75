// Motion-blur keywords (§3.2.6): the next shape's motion, taken only with mbEnable and cleared
// by every shape; motionBlur's shutter and time samples.
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlMotion, TheNextEnabledShapeTakesTheMotionAndEveryShapeClearsIt) {
  const Scene scene = load_text(
      "mbScale 2 1 1 mbRotate 90 0 0 1 mbTranslate 1 2 3 mbEnable\n"
      "sphere\n"
      "cube");
  ASSERT_EQ(scene.objects.size(), 2u);
  ASSERT_TRUE(scene.objects[0].motion.has_value());
  const ObjectMotion& m = *scene.objects[0].motion;
  EXPECT_EQ(m.scale, (Vec3{2, 1, 1}));
  EXPECT_EQ(m.angle_degrees, 90);
  EXPECT_EQ(m.axis, (Vec3{0, 0, 1}));
  EXPECT_EQ(m.translation, (Vec3{1, 2, 3}));
  EXPECT_FALSE(scene.objects[1].motion.has_value());
}

TEST(SdlMotion, WithoutMbEnableNothingMovesAndTheMotionIsStillCleared) {
  const Scene scene = load_text("mbTranslate 1 0 0 sphere mbEnable cube");
  EXPECT_FALSE(scene.objects[0].motion.has_value());
  ASSERT_TRUE(scene.objects[1].motion.has_value());
  EXPECT_EQ(*scene.objects[1].motion, ObjectMotion{});  // the sphere cleared the translation
  EXPECT_FALSE(scene.objects[1].motion->moves());
}

TEST(SdlMotion, MbClearForgetsTheMotionAndTheEnable) {
  const Scene scene = load_text("mbTranslate 1 0 0 mbEnable mbClear sphere");
  EXPECT_FALSE(scene.objects[0].motion.has_value());
}

TEST(SdlMotion, MotionBlurSetsTheShutterAndAZeroShutterIsAllowed) {
  const Scene scene = load_text("motionBlur 0 4");
  EXPECT_EQ(scene.globals.motion_blur_frame_length, 0);
  EXPECT_EQ(scene.globals.motion_blur_time_samples, 4);
  const Scene defaults = load_text("sphere");
  EXPECT_EQ(defaults.globals.motion_blur_frame_length, 1);
  EXPECT_EQ(defaults.globals.motion_blur_time_samples, 8);
}

TEST(SdlMotion, Errors) {
  EXPECT_TRUE(fails_at("mbScale 1 0 1", 1, 11, "<sy> of 'mbScale' must be positive, found '0'"));
  EXPECT_TRUE(fails_at("mbRotate 30 0 0 0", 1, 13, "'mbRotate' needs a non-zero axis"));
  EXPECT_TRUE(fails_at("mbTranslate 1 2", 1, 16,
                       "unexpected end of file, expected a number for <dz> of 'mbTranslate'"));
  EXPECT_TRUE(fails_at("mbEnable\nellipticCone 2 2 2", 2, 1,
                       "'ellipticCone' cannot move: algebraic surfaces do not take motion blur"));
}

}  // namespace
}  // namespace tessera::test
