#include <gtest/gtest.h>

#include <cmath>

#include "common/geometry/shapes.h"

namespace tessera {
namespace {

TEST(Sphere, HitsAtTheExactRoot) {
  LocalHit hit;
  ASSERT_TRUE(intersect_sphere({{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{0, 0, -1}));
  EXPECT_EQ(hit.normal, (Vec3{0, 0, -1}));
  EXPECT_EQ(hit.shading_normal, hit.normal);
  // t is in units of the (unnormalized) direction.
  ASSERT_TRUE(intersect_sphere({{0, 0, -5}, {0, 0, 2}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 2);
  ASSERT_TRUE(intersect_sphere({{3, 0, 0}, {-0.5, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{1, 0, 0}));
}

TEST(Sphere, MissesAndRespectsTMax) {
  LocalHit hit;
  EXPECT_FALSE(intersect_sphere({{0, 1.5, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_FALSE(intersect_sphere({{0, 0, 5}, {0, 0, 1}}, kInfinity, hit));  // behind
  EXPECT_FALSE(intersect_sphere({{0, 0, -5}, {0, 0, 1}}, 4, hit));         // t in (0, t_max)
  EXPECT_TRUE(intersect_sphere({{0, 0, -5}, {0, 0, 1}}, 4.0000001, hit));
  EXPECT_FALSE(intersect_sphere({{0, 0, -5}, {0, 0, 0}}, kInfinity, hit));  // no direction
  EXPECT_FALSE(intersect_sphere({{0, 0, -5}, {0, NAN, 1}}, kInfinity, hit));
}

TEST(Sphere, OriginInsideFindsTheExit) {
  LocalHit hit;
  ASSERT_TRUE(intersect_sphere({{0, 0, 0}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.point, (Vec3{1, 0, 0}));
  EXPECT_EQ(hit.normal, (Vec3{1, 0, 0}));  // outward, even from inside
  ASSERT_TRUE(intersect_sphere({{0.5, 0, 0}, {-1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1.5);
}

TEST(Sphere, OriginOnTheSurface) {
  LocalHit hit;
  // Leaving outward: the root at t = 0 is not a hit.
  EXPECT_FALSE(intersect_sphere({{1, 0, 0}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_sphere({{1, 0, 0}, {0.3, 1, 0}}, kInfinity, hit));
  // Going inward: the far side, never t ~ 0.
  ASSERT_TRUE(intersect_sphere({{1, 0, 0}, {-1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 2);
  ASSERT_TRUE(intersect_sphere({{0, 1, 0}, {0, -1, -1}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 1, 1e-15);
  EXPECT_NEAR(hit.point.z, -1, 1e-15);
}

TEST(Sphere, TangentAndGrazingRays) {
  LocalHit hit;
  // Exactly tangent: touches at one point (counted as a hit, with a finite result).
  ASSERT_TRUE(intersect_sphere({{1, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 5);
  EXPECT_EQ(hit.point, (Vec3{1, 0, 0}));
  EXPECT_FALSE(intersect_sphere({{1 + 1e-12, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  ASSERT_TRUE(intersect_sphere({{1 - 1e-12, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 5, 2e-6);
  EXPECT_NEAR(length(hit.point), 1, 1e-15);
}

TEST(Sphere, SmallSphereFarAwayKeepsItsDigits) {
  // b^2 - 4ac would cancel ~18 digits here; the distance-to-line discriminant does not.
  LocalHit hit;
  for (double distance : {1e6, 1e9, 1e12}) {
    SCOPED_TRACE(distance);
    ASSERT_TRUE(intersect_sphere({{0, 0.5, -distance}, {0, 0, 1}}, kInfinity, hit));
    EXPECT_NEAR(hit.point.y, 0.5, 1e-12);
    EXPECT_NEAR(hit.point.z, -std::sqrt(0.75), 1e-12);
    EXPECT_NEAR(hit.t, distance - std::sqrt(0.75), distance * 1e-15);
    EXPECT_FALSE(intersect_sphere({{0, 1.0000001, -distance}, {0, 0, 1}}, kInfinity, hit));
    ASSERT_TRUE(intersect_sphere({{0, 0.9999999, -distance}, {0, 0, 1}}, kInfinity, hit));
  }
}

TEST(Sphere, PointIsReprojectedWithItsErrorBound) {
  LocalHit hit;
  for (int i = 1; i < 200; ++i) {
    const Vec3 o{-3.1 + 0.01 * i, 1.7 - 0.013 * i, -4.9};
    const Vec3 target{0.37 * std::sin(i), 0.41 * std::cos(i), 0.2};
    ASSERT_TRUE(intersect_sphere({o, target - o}, kInfinity, hit));
    const Vec3 e = hit.point_error;
    EXPECT_NEAR(length(hit.point), 1, 4e-16);
    EXPECT_GT(e.x + e.y + e.z, 0);
    EXPECT_LT(max_component(e), 1e-15);
  }
}

}  // namespace
}  // namespace tessera
