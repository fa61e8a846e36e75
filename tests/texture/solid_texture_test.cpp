// The solid textures of §3.2.8 at points where their formulas (docs/SDL.md §4.5) give known
// colours.
#include <gtest/gtest.h>

#include <cmath>

#include "common/texture/perlin_noise.h"
#include "common/texture/solid_texture.h"

namespace tessera {
namespace {

Rgb colour(int type, std::vector<double> params, const Vec3& p) {
  const std::optional<SolidPattern> pattern = make_solid_pattern({type, std::move(params)});
  EXPECT_TRUE(pattern.has_value());
  return pattern ? solid_texture_colour(*pattern, p) : Rgb{-1, -1, -1};
}

::testing::AssertionResult near(const Rgb& a, const Rgb& b, double tolerance = 1e-12) {
  if (std::fabs(a.r - b.r) <= tolerance && std::fabs(a.g - b.g) <= tolerance &&
      std::fabs(a.b - b.b) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "(" << a.r << ", " << a.g << ", " << a.b << ") vs ("
                                       << b.r << ", " << b.g << ", " << b.b << ")";
}

const Rgb kWhite{1, 1, 1}, kBlack{0, 0, 0};

TEST(SolidTexture, TypeZeroIsNone) { EXPECT_FALSE(make_solid_pattern({0, {}}).has_value()); }

TEST(SolidTexture, CheckerboardAlternatesByCell) {
  const std::vector<double> cells{0.5, 1, 2};                        // cell sizes along x, y, z
  EXPECT_TRUE(near(colour(1, cells, {0.25, 0.5, 1}), kWhite));       // cell (0, 0, 0)
  EXPECT_TRUE(near(colour(1, cells, {0.75, 0.5, 1}), kBlack));       // (1, 0, 0)
  EXPECT_TRUE(near(colour(1, cells, {0.75, 1.5, 1}), kWhite));       // (1, 1, 0)
  EXPECT_TRUE(near(colour(1, cells, {0.75, 1.5, 2.5}), kBlack));     // (1, 1, 1)
  EXPECT_TRUE(near(colour(1, cells, {-0.25, 0.5, 1}), kBlack));      // (-1, 0, 0)
  EXPECT_TRUE(near(colour(1, {0, 1, 1}, {7.3, 0.5, 0.5}), kWhite));  // a zero scale: x is 0
}

TEST(SolidTexture, ColourBarsStackRedGreenAndBlueBars) {
  EXPECT_TRUE(near(colour(2, {1, 1, 1}, {0.5, 0.5, 0.5}), kWhite));
  EXPECT_TRUE(near(colour(2, {1, 1, 1}, {1.5, 0.5, 0.5}), {0, 1, 1}));
  EXPECT_TRUE(near(colour(2, {1, 1, 1}, {0.5, -0.5, 0.5}), {1, 0, 1}));
  EXPECT_TRUE(near(colour(2, {1, 1, 2}, {0.5, 0.5, 3}), {1, 1, 0}));
}

TEST(SolidTexture, RgbCubesRunThroughTheColourCubeInEveryCell) {
  EXPECT_TRUE(near(colour(3, {2, 2, 2}, {0.5, 1, 1.5}), {0.25, 0.5, 0.75}));
  EXPECT_TRUE(near(colour(3, {2, 2, 2}, {2.5, -1, 5.5}), {0.25, 0.5, 0.75}));
}

TEST(SolidTexture, ContoursOfOneCoordinateAreWhiteOnMultiplesOfTheScale) {
  EXPECT_TRUE(near(colour(4, {1, 0.5}, {9, 1.0, 9}), kWhite));                    // y = 2 scales
  EXPECT_TRUE(near(colour(4, {1, 0.5}, {9, 0.75, 9}), kBlack));                   // half-way
  EXPECT_TRUE(near(colour(4, {2, 0.5}, {0, 0, 0.125}), {0.5, 0.5, 0.5}, 1e-12));  // a quarter
}

TEST(SolidTexture, ContoursOfTwoCoordinatesByEachDistanceMeasure) {
  // Plane 1 is Y and Z; Euclid: a circle of radius 5 passes through (y, z) = (3, 4).
  EXPECT_TRUE(near(colour(5, {1, 0, 1, 1}, {100, 3, 4}), kWhite));
  EXPECT_TRUE(
      near(colour(5, {1, 0, 1, 1}, {100, 3, 4.5}), colour(4, {0, 1}, {std::hypot(3, 4.5), 0, 0})));
  // Manhattan in the XZ plane (2): |0.25| + |-0.25| = 0.5, a dark band.
  EXPECT_TRUE(near(colour(5, {2, 1, 1, 1}, {0.25, 9, -0.25}), kBlack));
  // sin.sin in the XY plane: sin(2pi 1/4) sin(2pi 1/4) = 1, a contour line.
  EXPECT_TRUE(near(colour(5, {0, 2, 1, 1}, {0.25, 0.25, 0}), kWhite));
  // sin.cos: sin(pi/2) cos(pi/2) = 0, also a line; sin(pi/6) cos(0) = 1/2, a dark band.
  EXPECT_TRUE(near(colour(5, {0, 3, 1, 1}, {0.25, 0.25, 0}), kWhite, 1e-12));
  EXPECT_TRUE(near(colour(5, {0, 3, 1, 1}, {1.0 / 12, 0, 0}), kBlack, 1e-12));
}

TEST(SolidTexture, ContoursOfThreeCoordinates) {
  EXPECT_TRUE(near(colour(6, {0, 1, 1, 1}, {2, 3, 6}), kWhite));     // Euclid: 7
  EXPECT_TRUE(near(colour(6, {1, 1, 1, 1}, {0.5, -1, 0}), kBlack));  // Manhattan: 1.5
  EXPECT_TRUE(near(colour(6, {1, 2, 2, 2}, {1, -1, 2}), kWhite));    // Manhattan: 4 / 2
}

TEST(SolidTexture, WoodGrainRingsAroundTheZAxis) {
  const Rgb light{0.9, 0.7, 0.4}, dark{0.5, 0.3, 0.1};
  // Ring thickness 0.5, no wobble: ring index floor(r / 0.5).
  const std::vector<double> plain{0.5, 0, 0, 0, 0.9, 0.7, 0.4, 0.5, 0.3, 0.1, 0};
  EXPECT_TRUE(near(colour(7, plain, {0.2, 0, 5}), light));
  EXPECT_TRUE(near(colour(7, plain, {0, 0.7, -5}), dark));
  EXPECT_TRUE(near(colour(7, plain, {0, -1.1, 0}), light));  // q = 2.2
  std::vector<double> smooth = plain;
  smooth[10] = 1;
  EXPECT_TRUE(near(colour(7, smooth, {0.5, 0, 0}), dark));                   // q = 1
  EXPECT_TRUE(near(colour(7, smooth, {0.25, 0, 0}), (light + dark) * 0.5));  // q = 1/2
  // Wobble 0.5 with 4 wobbles at theta = pi/8: q = r / 0.5 + 0.5 sin(pi/2) = q + 0.5.
  std::vector<double> wobbly = plain;
  wobbly[1] = 0.5;
  wobbly[2] = 4;
  const double r = 0.4;
  const Vec3 p{r * std::cos(M_PI / 8), r * std::sin(M_PI / 8), 0};
  EXPECT_TRUE(near(colour(7, wobbly, p), dark));  // 0.8 + 0.5 = 1.3
  // A twist of pi/2 per unit of z moves the wobble: at z = 1 the sine is sin(pi) = 0.
  wobbly[3] = M_PI / 2;
  EXPECT_TRUE(near(colour(7, wobbly, p + Vec3{0, 0, 1}), light));  // 0.8
}

TEST(SolidTexture, MarbleIsASineAlongItsAxisDisturbedByTurbulence) {
  EXPECT_TRUE(near(colour(8, {0, 0, 1, 0.8, 0.6}, {0.25, 3, 3}), {1, 0.8, 0.6}));
  EXPECT_TRUE(near(colour(8, {2, 0, 1, 0.8, 0.6}, {3, 3, 0.75}), kBlack));
  // Off the lattice, turbulence of six octaves, summed here from the noise itself (pinned by
  // known answers in perlin_noise_test.cpp), shifts the phase by 5 times its value. Five or
  // seven octaves would give another colour.
  const Vec3 p{0.1, 0.2, 0.3};
  const auto marble = [&](int octaves) {
    double sum = 0;
    for (int i = 0; i < octaves; ++i)
      sum += std::fabs(perlin_noise(p * std::ldexp(1.0, i))) / (1 << i);
    const double v = (1 + std::sin(2 * M_PI * 0.2 + 5 * sum)) / 2;
    return Rgb{v, v, v};
  };
  EXPECT_TRUE(near(colour(8, {1, 5, 1, 1, 1}, p), marble(6)));
  EXPECT_FALSE(near(marble(6), marble(5), 1e-6));
  EXPECT_FALSE(near(marble(6), marble(7), 1e-6));
}

TEST(SolidTexture, CowSpotsAreBlackWhereTheNoiseExceedsTheThreshold) {
  // Noise is 0 on the lattice, 1/2 once mapped to [0, 1].
  EXPECT_TRUE(near(colour(9, {0.4}, {0, 0, 0}), kBlack));
  EXPECT_TRUE(near(colour(9, {0.6}, {0, 0, 0}), kWhite));
  int black = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p{std::sin(i * 1.3), std::cos(i * 0.7), std::sin(i * 2.9)};
    const Rgb c = colour(9, {0.5}, p);
    ASSERT_TRUE(c == kBlack || c == kWhite);
    black += c == kBlack;
    EXPECT_TRUE(near(colour(9, {1}, p), kWhite));
  }
  EXPECT_GT(black, 200);  // about half
  EXPECT_LT(black, 800);
}

}  // namespace
}  // namespace tessera
