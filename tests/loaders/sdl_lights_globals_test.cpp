// Lights (§3.2.2), global scene attributes (§3.2.7) and the camera checks at the end of a load.
#include <gtest/gtest.h>

#include <string>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlLights, PointLightsAreInWorldCoordinates) {
  const Scene scene = load_text("translate 5 0 0 scale 2 2 2 light 1 2 3 0.5 0.25 1");
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.position, Vec3(1, 2, 3));  // the CT does not apply to lights
  EXPECT_EQ(light.color, Rgb(0.5, 0.25, 1));
  EXPECT_FALSE(light.is_spot);
}

TEST(SdlLights, SpotlightsHaveANormalizedDirection) {
  const Scene scene = load_text(
      "rotate 90 1 0 0 spotlight 0 5 0  1 1 1  0 -2 0  30 4\n"
      "spotlight 0 0 0 1 1 1 3 4 0 180 0\n"
      "spotlight 0 0 0 1 1 1 0 0 1e-200 90 0");
  ASSERT_EQ(scene.lights.size(), 3u);
  const Light& spot = scene.lights[0];
  EXPECT_TRUE(spot.is_spot);
  EXPECT_EQ(spot.position, Vec3(0, 5, 0));
  EXPECT_EQ(spot.spot.direction, Vec3(0, -1, 0));
  EXPECT_EQ(spot.spot.cutoff_degrees, 30);
  EXPECT_EQ(spot.spot.exponent, 4);
  EXPECT_TRUE(near(scene.lights[1].spot.direction, {0.6, 0.8, 0}));
  EXPECT_EQ(scene.lights[1].spot.cutoff_degrees, 180);
  EXPECT_EQ(scene.lights[2].spot.direction, Vec3(0, 0, 1));  // tiny, but a direction
}

TEST(SdlLights, Errors) {
  EXPECT_TRUE(fails_at("spotlight 0 0 0 1 1 1 0 0 0 30 1", 1, 23,
                       "'spotlight' needs a non-zero direction <dx> <dy> <dz>"));
  EXPECT_TRUE(fails_at("spotlight 0 0 0 1 1 1 0 0 1 0 1", 1, 29,
                       "<cut-off angle> of 'spotlight' must be in (0, 180] degrees, found '0'"));
  EXPECT_TRUE(fails_at("spotlight 0 0 0 1 1 1 0 0 1 180.5 1", 1, 29,
                       "<cut-off angle> of 'spotlight' must be in (0, 180] degrees, found "
                       "'180.5'"));
  EXPECT_TRUE(fails_at("spotlight 0 0 0 1 1 1 0 0 1 30 -1", 1, 32,
                       "<exponent> of 'spotlight' must be non-negative, found '-1'"));
  EXPECT_TRUE(
      fails_at("light 0 0 0 1 -1 1", 1, 15, "<green> of 'light' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("light 0 0 0 1 1", 1, 16,
                       "unexpected end of file, expected a number for <blue> of 'light'"));
}

TEST(SdlGlobals, CameraKeywords) {
  const Scene scene =
      load_text("eyePoint 1 2 3 viewPoint 4 5 6 upDirection 0 0 1 viewAngle 60 sphere");
  EXPECT_EQ(scene.camera.eye, Vec3(1, 2, 3));
  EXPECT_EQ(scene.camera.look_at, Vec3(4, 5, 6));
  EXPECT_EQ(scene.camera.up, Vec3(0, 0, 1));
  EXPECT_EQ(scene.camera.view_angle, 60);
}

TEST(SdlGlobals, DefaultsWhenNothingIsWritten) {
  const Scene scene = load_text("sphere");
  EXPECT_EQ(scene.camera, Camera{});
  EXPECT_EQ(scene.globals, SceneGlobals{});
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(SdlGlobals, EveryAttributeSetsItsField) {
  const Scene scene = load_text(
      "background 0.1 0.2 0.3 globalAmbient 0.4 0.5 0.6 lightAttenuation 1 0.5 0.25\n"
      "atmosphericAttenuation 1 0.9 10 0.1 0.5 0.5 0.6\n"
      "fog 2 20 0.7 0.7 0.7\n"
      "shadowFeelerEpsilon 1e-4 reflectivityEpsilon 2e-4 transparencyEpsilon 3e-4\n"
      "meshEpsilon 4e-4 adaptedShadowComputation 1 minReflectivity 0.05 minTransparency 0.06\n"
      "maxRecursionDepth 12 showExtents 1 motionBlur 2.5 16");
  SceneGlobals expected;
  expected.background = {0.1, 0.2, 0.3};
  expected.global_ambient = {0.4, 0.5, 0.6};
  expected.light_attenuation = {1, 0.5, 0.25};
  expected.atmospheric_attenuation = AtmosphericAttenuation{1, 0.9, 10, 0.1, {0.5, 0.5, 0.6}};
  expected.fog = Fog{2, 20, {0.7, 0.7, 0.7}};
  expected.shadow_feeler_epsilon = 1e-4;
  expected.reflectivity_epsilon = 2e-4;
  expected.transparency_epsilon = 3e-4;
  expected.mesh_epsilon = 4e-4;
  expected.adapted_shadow_computation = true;
  expected.min_reflectivity = 0.05;
  expected.min_transparency = 0.06;
  expected.max_recursion_depth = 12;
  expected.show_extents = true;
  expected.motion_blur_frame_length = 2.5;
  expected.motion_blur_time_samples = 16;
  EXPECT_EQ(scene.globals, expected);
}

TEST(SdlGlobals, LaterValuesReplaceEarlierOnes) {
  const Scene scene = load_text("showExtents 1 showExtents 0 background 1 1 1 background 0 0 1");
  EXPECT_FALSE(scene.globals.show_extents);
  EXPECT_EQ(scene.globals.background, Rgb(0, 0, 1));
}

TEST(SdlGlobals, RangeErrors) {
  EXPECT_TRUE(fails_at("viewAngle 0", 1, 11,
                       "<value> of 'viewAngle' must be strictly between 0 and 180 degrees, "
                       "found '0'"));
  EXPECT_TRUE(fails_at("viewAngle 180", 1, 11,
                       "<value> of 'viewAngle' must be strictly between 0 and 180 degrees, "
                       "found '180'"));
  EXPECT_TRUE(fails_at("background 0 0 -1", 1, 16,
                       "<blue> of 'background' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("globalAmbient -1 0 0", 1, 15,
                       "<red> of 'globalAmbient' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("lightAttenuation 1 -1 0", 1, 20,
                       "<linear-factor> of 'lightAttenuation' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("sphere\n  lightAttenuation 0 0 0", 2, 3,
                       "'lightAttenuation' needs at least one non-zero factor"));
  // Eq. 4.20 blends by the scales: outside [0, 1] it would extrapolate to negative colours.
  EXPECT_TRUE(fails_at("atmosphericAttenuation 1 2 5 0 0 0 0", 1, 26,
                       "<front-scale> of 'atmosphericAttenuation' must be in [0, 1], found '2'"));
  EXPECT_TRUE(fails_at("atmosphericAttenuation 1 1 5 -0.5 0 0 0", 1, 30,
                       "<back-scale> of 'atmosphericAttenuation' must be in [0, 1], found '-0.5'"));
  EXPECT_TRUE(fails_at("atmosphericAttenuation 5 1 5 0 0 0 0", 1, 28,
                       "'atmosphericAttenuation' needs <back-plane> different from "
                       "<front-plane>"));
  EXPECT_TRUE(fails_at("atmosphericAttenuation 1 1 5 0 0 0", 1, 35,
                       "unexpected end of file, expected a number for <blue> of "
                       "'atmosphericAttenuation'"));
  EXPECT_TRUE(fails_at("fog 3 3 0 0 0", 1, 7, "'fog' needs <fog-end> different from <fog-start>"));
  EXPECT_TRUE(
      fails_at("fog 1 3 0 -0.5 0", 1, 11, "<green> of 'fog' must be non-negative, found '-0.5'"));
  EXPECT_TRUE(fails_at("meshEpsilon -1e-6", 1, 13,
                       "<value> of 'meshEpsilon' must be non-negative, found '-1e-6'"));
  EXPECT_TRUE(fails_at("shadowFeelerEpsilon -1", 1, 21,
                       "<value> of 'shadowFeelerEpsilon' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("minReflectivity 2", 1, 17,
                       "<value> of 'minReflectivity' must be in [0, 1], found '2'"));
  EXPECT_TRUE(fails_at("maxRecursionDepth -1", 1, 19,
                       "<value> of 'maxRecursionDepth' must be at least 0, found '-1'"));
  EXPECT_TRUE(fails_at("maxRecursionDepth 2.5", 1, 19,
                       "expected an integer for <value> of 'maxRecursionDepth', found '2.5'"));
  EXPECT_TRUE(fails_at("motionBlur 1 0", 1, 14,
                       "<#time-samples> of 'motionBlur' must be between 1 and 256, found '0'"));
  EXPECT_TRUE(fails_at("motionBlur -1 8", 1, 12,
                       "<frame-length> of 'motionBlur' must be non-negative, found '-1'"));
  EXPECT_TRUE(fails_at("motionBlur 1 257", 1, 14,
                       "<#time-samples> of 'motionBlur' must be between 1 and 256, found '257'"));
}

TEST(SdlCamera, EyeEqualToViewPointIsAnErrorAtTheLastOfTheTwo) {
  EXPECT_TRUE(fails_at("eyePoint 1 2 3\nviewPoint 1 2 3\nsphere", 2, 1,
                       "eyePoint and viewPoint are the same point"));
  EXPECT_TRUE(fails_at("viewPoint 1 2 3\n  eyePoint 1 2 3", 2, 3,
                       "eyePoint and viewPoint are the same point"));
  // The default eye is (0, 0, 5).
  EXPECT_TRUE(
      fails_at("sphere viewPoint 0 0 5", 1, 8, "eyePoint and viewPoint are the same point"));
  // Moving them apart again is fine: only the final camera is checked.
  EXPECT_NO_THROW(load_text("viewPoint 0 0 5 viewPoint 0 0 0"));
}

TEST(SdlCamera, UpParallelToTheViewDirectionIsAnError) {
  EXPECT_TRUE(fails_at("sphere\nupDirection 0 0 2", 2, 1,
                       "upDirection is zero or parallel to the view direction"));
  EXPECT_TRUE(
      fails_at("upDirection 0 0 0", 1, 1, "upDirection is zero or parallel to the view direction"));
  // Without upDirection, the error is at the eye or view point that made them parallel.
  EXPECT_TRUE(fails_at("sphere eyePoint 0 7 0", 1, 8,
                       "upDirection is zero or parallel to the view direction"));
  EXPECT_NO_THROW(load_text("eyePoint 0 7 0 upDirection 1e-3 0 1"));
  EXPECT_NO_THROW(load_text("upDirection 0 1e-200 0"));
  EXPECT_NO_THROW(load_text("eyePoint 0 0 1e308 viewPoint 0 0 -1e308"));
}

TEST(SdlCamera, CameraErrorsInsideAMacroPointIntoTheDef) {
  EXPECT_TRUE(fails_at("def cam {\n  viewPoint 0 0 5 }\nuse cam", 2, 3,
                       "eyePoint and viewPoint are the same point"));
}

}  // namespace
}  // namespace tessera::test
