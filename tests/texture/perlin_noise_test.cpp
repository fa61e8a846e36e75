// Perlin noise: Perlin's reference values, zero on the lattice, bounded, and a pure function of
// the point (no seed, no state), so every worker computes the same texture.
#include <gtest/gtest.h>

#include <cmath>

#include "common/texture/perlin_noise.h"

namespace tessera {
namespace {

TEST(PerlinNoise, MatchesPerlinsReferenceImplementation) {
  // ImprovedNoise.noise(3.14, 42, 7) of Perlin's Java reference.
  EXPECT_NEAR(perlin_noise({3.14, 42, 7}), 0.13691995878400012, 1e-15);
}

TEST(PerlinNoise, IsZeroOnTheIntegerLattice) {
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) EXPECT_EQ(perlin_noise({double(x), double(y), double(z)}), 0.0);
}

TEST(PerlinNoise, IsDeterministicBoundedAndVaried) {
  double lo = 1, hi = -1, sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Vec3 p{i * 0.1371, i * 0.0713 - 50, std::sin(i * 1.7) * 20};
    const double v = perlin_noise(p);
    ASSERT_EQ(v, perlin_noise(p));
    ASSERT_GE(v, -1.0);
    ASSERT_LE(v, 1.0);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    sum += v;
  }
  EXPECT_LT(lo, -0.5);
  EXPECT_GT(hi, 0.5);
  EXPECT_NEAR(sum / n, 0.0, 0.05);  // gradient noise has mean zero
}

TEST(PerlinNoise, RepeatsEvery256CellsAndSurvivesHugeCoordinates) {
  const Vec3 p{0.3, 1.7, -2.2};
  EXPECT_NEAR(perlin_noise(p), perlin_noise(p + Vec3{256, -512, 1024}), 1e-12);
  EXPECT_TRUE(std::isfinite(perlin_noise({1e300, -1e300, 3.5})));
  EXPECT_EQ(perlin_noise({NAN, 0, 0}), 0.0);
}

TEST(PerlinNoise, TurbulenceSumsOctavesOfAbsoluteNoise) {
  const Vec3 p{0.3, 1.7, -2.2};
  EXPECT_DOUBLE_EQ(turbulence(p, 1), std::fabs(perlin_noise(p)));
  EXPECT_DOUBLE_EQ(turbulence(p, 2),
                   std::fabs(perlin_noise(p)) + std::fabs(perlin_noise(p * 2)) / 2);
  for (int i = 0; i < 1000; ++i) {
    const double t = turbulence({i * 0.37, i * 0.11, -i * 0.05}, 6);
    ASSERT_GE(t, 0.0);
    ASSERT_LT(t, 2.0);
  }
}

}  // namespace
}  // namespace tessera
