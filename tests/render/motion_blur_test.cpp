// Motion blur in rendered pixels (§4.5): a moving emissive sphere covers a pixel for the share
// of the shutter it spends there; shadow feelers see occluders where the camera ray's time puts
// them; a zero-length shutter is a still render; the BVH never culls a fast object; a moving
// child of a boolean object moves within it.
#include <gtest/gtest.h>

#include "common/loaders/sdl_loader.h"
#include "tests/loaders/loader_test_util.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 33;
constexpr int kCentre = 16;  // the pixel whose ray is the view axis
constexpr int kTimes = 64;

// An emissive sphere of radius 0.5 seen from far along z, moving `distance` along x during a
// shutter of one frame: the centre pixel sees it while |t distance| < 0.5.
Scene sweeping_sphere(double distance, const std::string& shutter = "") {
  return load_text("eyePoint 0 0 100 viewPoint 0 0 0 viewAngle 2 background 0 0 0 " + shutter +
                   "\n"
                   "emissive 1 1 1 ambient 0 0 0 diffuse 0 0 0\n"
                   "mbTranslate " +
                   std::to_string(distance) +
                   " 0 0 mbEnable\n"
                   "scale 0.5 0.5 0.5 sphere");
}

RenderSettings blur_settings() {
  RenderSettings s = settings(kSize, kSize);
  s.time_samples = kTimes;
  return s;
}

TEST(MotionBlur, APixelSeesAMovingObjectForItsShareOfTheShutter) {
  RenderStats stats;
  const Image image = render(sweeping_sphere(4), blur_settings(), &stats);
  // |t| < 0.5 / 4 over t in [-1/2, 1/2]: a quarter of the shutter. The time samples are
  // stratified, so at most the two strata at the edges are wrong.
  EXPECT_NEAR(image.get(kCentre, kCentre).r, 0.25, 2.0 / kTimes);
  EXPECT_EQ(stats.camera_rays, static_cast<long long>(kSize) * kSize * kTimes);
  // Still, the sphere covers the pixel all the time.
  const Image still = render(sweeping_sphere(0), blur_settings());
  EXPECT_EQ(still.get(kCentre, kCentre).r, 1.0f);
}

TEST(MotionBlur, AZeroLengthShutterIsAStillRenderAndCostsNothing) {
  RenderStats blurred_stats, still_stats;
  const Image zero = render(sweeping_sphere(4, "motionBlur 0 8"), blur_settings(), &blurred_stats);
  const Image still = render(sweeping_sphere(0), blur_settings(), &still_stats);
  EXPECT_EQ(zero, still);
  EXPECT_EQ(blurred_stats.camera_rays, static_cast<long long>(kSize) * kSize);
  const Scene scene = sweeping_sphere(4, "motionBlur 0 8");
  EXPECT_FALSE(PreparedScene(scene, BvhMode::Sah).effects().has(Effect::MotionBlur));
  const Scene moving = sweeping_sphere(4);
  EXPECT_TRUE(PreparedScene(moving, BvhMode::Sah).effects().has(Effect::MotionBlur));
}

// Jitter strengths above 1 move sample positions further (docs/SERVICE.md takes up to 16), but
// the times stay inside the shutter: a sphere the centre pixel would see only just before the
// shutter opens (centre 2.6 + 4 t, seen while |2.6 + 4 t| < 0.5, t in (-0.775, -0.525)) stays
// unseen at any strength.
TEST(MotionBlur, JitterAboveOneKeepsTheTimesInsideTheShutter) {
  const Scene scene = load_text(
      "eyePoint 0 0 100 viewPoint 0 0 0 viewAngle 2 background 0 0 0\n"
      "emissive 1 1 1 ambient 0 0 0 diffuse 0 0 0\n"
      "mbTranslate 4 0 0 mbEnable translate 2.6 0 0 scale 0.5 0.5 0.5 sphere");
  for (const double jitter : {1.0, 1.5, 16.0}) {
    RenderSettings s = blur_settings();
    s.jitter = jitter;
    EXPECT_EQ(render(scene, s).get(kCentre, kCentre).r, 0.0f) << "jitter " << jitter;
  }
}

// A white floor (top face at y = 0) under a light straight above the origin, seen at a grazing
// angle from below the occluder's path; a sphere of radius 0.5 at height 2 crosses above the
// origin, moving 4 units along x in the frame.
Scene moving_occluder(bool with_occluder) {
  std::string text =
      "eyePoint 0 0.2 10 viewPoint 0 0 0 viewAngle 2 background 0 0 0\n"
      "light 0 10 0 1 1 1\n"
      "ambient 0 0 0 diffuse 1 1 1\n"
      "push translate 0 -1 0 scale 10 1 10 cube pop\n";
  if (with_occluder)
    text += "mbTranslate 4 0 0 mbEnable push translate 0 2 0 scale 0.5 0.5 0.5 sphere pop\n";
  return load_text(text);
}

TEST(MotionBlur, ShadowFeelersCarryTheCameraRaysTime) {
  const Image lit = render(moving_occluder(false), blur_settings());
  const Image blurred = render(moving_occluder(true), blur_settings());
  const double unshadowed = lit.get(kCentre, kCentre).r;
  ASSERT_NEAR(unshadowed, 1.0, 1e-3);  // N.L = 1 straight under the light
  // The feeler from the origin to the light meets the sphere while |4 t| < 0.5: a quarter of
  // the shutter. Feelers at time 0 would find it every time and leave the pixel black.
  EXPECT_NEAR(blurred.get(kCentre, kCentre).r, 0.75 * unshadowed, 2.0 / kTimes);
}

TEST(MotionBlur, TheBvhNeverCullsAFastObject) {
  std::string text = "eyePoint 0 0 30 viewPoint 0 0 0 light 5 5 30 1 1 1 diffuse 0.7 0.5 0.3\n";
  for (int i = 0; i < 12; ++i) {
    const double x = -6 + i, y = (i % 3) - 1.0;
    text += "mbRotate " + std::to_string(180 * i) + " 0 1 1 mbTranslate " + std::to_string(3 - i) +
            " " + std::to_string(i % 4) + " 0 mbScale 1.5 0.5 1 mbEnable push translate " +
            std::to_string(x) + " " + std::to_string(y) + " 0 scale 0.6 0.9 0.4 " +
            (i % 2 ? "cube" : "torus 0.3 1") + " pop\n";
  }
  const Scene scene = load_text(text);
  RenderSettings s = settings(48, 36);
  s.time_samples = 4;
  const Image with_bvh = render(scene, s);
  s.bvh = BvhMode::None;
  EXPECT_EQ(render(scene, s), with_bvh);
  // And the same pixels from 1 thread or 2.
  s.bvh = BvhMode::Sah;
  EXPECT_EQ(render(scene, s, nullptr, 2), with_bvh);
}

// A red slab whose front face (z = 1) faces the camera, minus a green ball of radius 0.5
// centred on that face and moving 4 units along x during the frame: the centre pixel looks
// into the hole, at the ball's far wall, while |4 t| < 0.5.
Scene slab_with_moving_hole(double distance) {
  return load_text(
      "eyePoint 0 0 100 viewPoint 0 0 0 viewAngle 2 background 0 0 0\n"
      "ambient 0 0 0 diffuse 0 0 0\n"
      "difference\n"
      "  push emissive 1 0 0 scale 3 3 1 cube pop\n"
      "  mbTranslate " +
      std::to_string(distance) +
      " 0 0 mbEnable push emissive 0 1 0 translate 0 0 1 scale 0.5 0.5 0.5 sphere pop\n");
}

TEST(MotionBlur, AMovingChildOfABooleanObjectCutsItsHoleWhereItIsAtEachTime) {
  const Image image = render(slab_with_moving_hole(4), blur_settings());
  const Rgb centre = image.get(kCentre, kCentre);
  // A quarter of the shutter in the hole (the ball's inside, green), the rest on the slab.
  EXPECT_NEAR(centre.g, 0.25, 2.0 / kTimes);
  EXPECT_NEAR(centre.r, 0.75, 2.0 / kTimes);
  EXPECT_NEAR(centre.r + centre.g, 1.0, 1e-6);  // never the background: no hole through the slab
  EXPECT_EQ(centre.b, 0.0);
  // Still, the pixel looks into the hole all the time.
  const Image still = render(slab_with_moving_hole(0), blur_settings());
  EXPECT_EQ(still.get(kCentre, kCentre).g, 1.0f);
  EXPECT_EQ(still.get(kCentre, kCentre).r, 0.0f);
}

TEST(MotionBlur, TheBvhBoundsABooleanObjectOverItsChildsWholeSweep) {
  // A still ball at the origin united with one that sweeps 12 units along x: pixels far to the
  // right see only the moving child, at the end of the frame.
  const Scene scene = load_text(
      "eyePoint 0 0 40 viewPoint 0 0 0 viewAngle 8.6 background 0 0 0\n"
      "ambient 0 0 0 diffuse 0 0 0 emissive 1 1 1\n"
      "union sphere mbTranslate 12 0 0 mbEnable sphere\n"
      "push translate -8 0 0 sphere pop\n");  // a third object, so that the BVH has a tree
  RenderSettings s = settings(48, 16);
  s.time_samples = 8;
  const Image with_bvh = render(scene, s);
  // The image spans x in [-9, 9] at the balls' distance; the moving ball reaches x = 6 at the
  // end of the frame, so the right quarter (x > 4.5) sees it for part of the shutter.
  double right_side = 0;
  for (int x = 36; x < 48; ++x) right_side += with_bvh.get(x, 8).r;
  EXPECT_GT(right_side, 0.0);
  s.bvh = BvhMode::None;
  EXPECT_EQ(render(scene, s), with_bvh);
}

}  // namespace
}  // namespace tessera::test
