// The cones of gloss, translucency and soft shadows (§4.1.4): where their rays point.
#include "common/render/cone.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tessera::test {
namespace {

// The table of rim sines and cosines holds exactly what computing them would give, and counts
// past it are computed.
TEST(Cone, RimSinCosAreTheSinCosOfTheRimAngle) {
  for (int count = 2; count <= kTabledConeRays + 3; ++count) {
    for (int k = 1; k < count; ++k) {
      const SinCos expected = tessera::sincos(rim_angle(k, count));
      const SinCos rim = rim_sincos(k, count);
      ASSERT_EQ(rim.sin, expected.sin) << k << " of " << count;
      ASSERT_EQ(rim.cos, expected.cos) << k << " of " << count;
    }
  }
}

TEST(Cone, RimRaysLieAtTheJitteredRadiusAroundTheAxis) {
  const double r_c = 0.25;
  const double lo = std::atan(r_c * (1 - std::sqrt(2.0) / 8));
  const double hi = std::atan(r_c * (1 + std::sqrt(2.0) / 8));
  for (const Vec3 axis : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{1, 0, 0},
                          normalize_or({1, -2, 3}, {}), normalize_or({0.3, 0.4, -1e-9}, {})}) {
    const Cone cone(axis, r_c);
    SampleStream rng(1, 2, 3, 4);
    Vec3 mean{};
    for (int k = 1; k < 9; ++k) {
      const Vec3 d = cone.rim_direction(k, 9, rng);
      EXPECT_NEAR(length(d), 1, 1e-15);
      const double angle = std::acos(std::clamp(dot(d, axis), -1.0, 1.0));
      EXPECT_GE(angle, lo - 1e-12);
      EXPECT_LE(angle, hi + 1e-12);
      mean = mean + d;
    }
    // Spread evenly around the rim: their mean points along the axis.
    EXPECT_GT(dot(normalize_or(mean, {}), axis), std::cos(r_c / 4));
  }
}

TEST(Cone, MeanTracesTheAxisFirstUnjitteredThenTheRim) {
  const Vec3 axis{0, 1, 0};
  const Cone cone(axis, 0.5);
  SampleStream rng(0, 0, 0, 0);
  std::vector<Vec3> traced;
  const double mean = cone.mean<double>(5, rng, [&](const Vec3& d) {
    traced.push_back(d);
    return d.y;
  });
  ASSERT_EQ(traced.size(), 5u);
  EXPECT_EQ(traced[0], axis);
  double sum = 0;
  for (const Vec3& d : traced) sum += d.y;
  EXPECT_DOUBLE_EQ(mean, sum / 5);
  SampleStream one(0, 0, 0, 0);
  EXPECT_EQ(cone.mean<double>(1, one, [](const Vec3& d) { return d.y; }), 1.0);
}

}  // namespace
}  // namespace tessera::test
