// VRML's Background gradient: colours by the angle from the up axis, linear between the given
// angles, the last beyond them, and the ground over the sky within its last angle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/scene/sky_gradient.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr double kPi = std::numbers::pi;

// The unit direction at `angle` from +y, in the xy plane.
Vec3 from_up(double angle) { return {std::sin(angle), std::cos(angle), 0}; }

const Rgb kZenith{0, 0, 1}, kHorizon{1, 1, 1}, kLow{0.5, 0.5, 0.5};
const Rgb kNadir{0.2, 0.1, 0}, kGroundEdge{0, 0.6, 0};

SkyGradient sky_only() {
  SkyGradient sky;
  sky.sky_colours = {kZenith, kHorizon, kLow};
  sky.sky_angles = {kPi / 2, 3 * kPi / 4};
  return sky;
}

TEST(SkyGradient, SkyRunsLinearlyInTheAngleBetweenItsColours) {
  const SkyGradient sky = sky_only();
  expect_rgb(sky.colour(from_up(0)), kZenith);
  expect_rgb(sky.colour(from_up(kPi / 4)), kZenith * 0.5 + kHorizon * 0.5);
  expect_rgb(sky.colour(from_up(kPi / 2)), kHorizon);
  expect_rgb(sky.colour(from_up(5 * kPi / 8)), kHorizon * 0.5 + kLow * 0.5);
  // Beyond the last angle, the last colour, down to straight down.
  expect_rgb(sky.colour(from_up(7 * kPi / 8)), kLow);
  expect_rgb(sky.colour({0, -1, 0}), kLow);
}

TEST(SkyGradient, GroundCoversTheSkyWithinItsLastAngle) {
  SkyGradient sky = sky_only();
  sky.ground_colours = {kNadir, kGroundEdge};
  sky.ground_angles = {kPi / 3};
  expect_rgb(sky.colour({0, -1, 0}), kNadir);
  expect_rgb(sky.colour(from_up(kPi - kPi / 6)), kNadir * 0.5 + kGroundEdge * 0.5);
  expect_rgb(sky.colour(from_up(kPi - kPi / 3)), kGroundEdge);
  // Just above the ground's edge, the sky again.
  expect_rgb(sky.colour(from_up(kPi - kPi / 3 - 1e-9)), kHorizon * (1 - 2.0 / 3) + kLow * (2.0 / 3),
             1e-6);
}

TEST(SkyGradient, AnglesAreMeasuredFromTheBackgroundsUp) {
  SkyGradient sky = sky_only();
  sky.up = {1, 0, 0};
  expect_rgb(sky.colour({1, 0, 0}), kZenith);
  expect_rgb(sky.colour({0, 1, 0}), kHorizon);
  expect_rgb(sky.colour({-1, 0, 0}), kLow);
}

}  // namespace
}  // namespace tessera::test
