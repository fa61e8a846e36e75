#include <gtest/gtest.h>

#include <cmath>

#include "common/geometry/shapes.h"

namespace tessera {
namespace {

const TaperedCylinder kCylinder{1, false};
const TaperedCylinder kCone{0, false};
const TaperedCylinder kTapered{0.5, false};
const TaperedCylinder kWidening{2, false};

bool finite_hit(const LocalHit& hit) {
  return std::isfinite(hit.t) && is_finite(hit.point) && is_finite(hit.point_error) &&
         is_finite(hit.normal) && length(hit.normal) > 0;
}

void expect_unit_parallel(const Vec3& n, const Vec3& expected) {
  const Vec3 a = n / length(n), b = expected / length(expected);
  EXPECT_NEAR(a.x, b.x, 1e-15);
  EXPECT_NEAR(a.y, b.y, 1e-15);
  EXPECT_NEAR(a.z, b.z, 1e-15);
}

TEST(TaperedCylinder, CylinderWallAndCaps) {
  LocalHit hit;
  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{-5, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{-1, 0, 0.5}));
  EXPECT_EQ(hit.part, 0u);
  expect_unit_parallel(hit.normal, {-1, 0, 0});

  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 5);
  EXPECT_EQ(hit.part, 1u);
  EXPECT_EQ(hit.point, (Vec3{0, 0, 0}));
  expect_unit_parallel(hit.normal, {0, 0, -1});

  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{0.3, 0.2, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.part, 2u);
  EXPECT_EQ(hit.point, (Vec3{0.3, 0.2, 1}));
  expect_unit_parallel(hit.normal, {0, 0, 1});
}

TEST(TaperedCylinder, Misses) {
  LocalHit hit;
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 0, 1.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 1.5, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 0, 0.5}, {-1, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 0, 0.5}, {1, 0, 0}}, 4, hit));
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 0, 0.5}, {0, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{-5, 0, NAN}, {1, 0, 0}}, kInfinity, hit));
  // The cone's top cap is absent: a ray down the axis from above meets the apex, not a cap.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0.01, 0, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);
  EXPECT_NEAR(hit.t, 4.01, 1e-14);
}

TEST(TaperedCylinder, RaysParallelToTheAxis) {
  LocalHit hit;
  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{0.5, 0, -1}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.part, 1u);
  EXPECT_FALSE(intersect_tapered_cylinder(kCylinder, {{1.5, 0, -1}, {0, 0, 1}}, kInfinity, hit));
  // Along the wall itself: touches the closed base cap at its rim, no NaN from A = B = 0.
  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{1, 0, -1}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.part, 1u);
  // From inside, along the axis: the top cap.
  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{0.2, 0.1, 0.25}, {0, 0, 2}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 0.375);
  EXPECT_EQ(hit.part, 2u);
  // Parallel to the axis through a cone: meets the slanted wall.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0.25, 0, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);
  EXPECT_NEAR(hit.t, 4.25, 1e-15);
  expect_unit_parallel(hit.normal, {1, 0, 1});
}

TEST(TaperedCylinder, OriginInsideFindsTheExit) {
  LocalHit hit;
  ASSERT_TRUE(intersect_tapered_cylinder(kCylinder, {{0, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.part, 0u);
  expect_unit_parallel(hit.normal, {1, 0, 0});
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 0.5);
  expect_unit_parallel(hit.normal, {1, 0, 1});
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0, 0, 0.5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 0.5);
  EXPECT_EQ(hit.part, 1u);
}

TEST(TaperedCylinder, ConeThroughTheApex) {
  LocalHit hit;
  // Down the axis onto the apex: a double root where the wall's gradient vanishes.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0, 0, 2}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_TRUE(finite_hit(hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.point, (Vec3{0, 0, 1}));
  EXPECT_GT(hit.normal.z, 0);
  // Obliquely through the apex into the cone.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{-0.2, 0, 2}, {0.2, 0, -1}}, kInfinity, hit));
  EXPECT_TRUE(finite_hit(hit));
  EXPECT_NEAR(hit.t, 1, 1e-7);
  // Along a generatrix (A = 0: the quadratic degenerates to a line).
  const bool along = intersect_tapered_cylinder(kCone, {{-1, 0, 2}, {1, 0, -1}}, kInfinity, hit);
  if (along) {
    EXPECT_TRUE(finite_hit(hit));
    EXPECT_GE(hit.t, 1 - 1e-7);
    EXPECT_LE(hit.t, 2);
  }
  // Touching only the apex from outside.
  if (intersect_tapered_cylinder(kCone, {{-2, 0, 2}, {2, 0, -1}}, kInfinity, hit)) {
    EXPECT_TRUE(finite_hit(hit));
    EXPECT_NEAR(hit.t, 1, 1e-7);
  }
  // From inside the cone up through the apex.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{0, 0, 0.5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_TRUE(finite_hit(hit));
  EXPECT_EQ(hit.t, 0.5);
  // Many rays aimed exactly at the apex from every side: never NaN.
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o{3 * std::sin(0.1 * i), 3 * std::cos(0.37 * i), 1 + 2 * std::sin(0.05 * i)};
    if (intersect_tapered_cylinder(kCone, {o, Vec3{0, 0, 1} - o}, kInfinity, hit)) {
      EXPECT_TRUE(finite_hit(hit)) << i;
    }
  }
}

TEST(TaperedCylinder, SlantedWalls) {
  LocalHit hit;
  // Cone: radius 1 - z.
  ASSERT_TRUE(intersect_tapered_cylinder(kCone, {{-5, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4.5);
  EXPECT_EQ(hit.point, (Vec3{-0.5, 0, 0.5}));
  expect_unit_parallel(hit.normal, {-1, 0, 1});
  // Tapered, top radius 0.5: radius 1 - z / 2.
  ASSERT_TRUE(intersect_tapered_cylinder(kTapered, {{-5, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4.25);
  expect_unit_parallel(hit.normal, {-1, 0, 0.5});
  ASSERT_TRUE(intersect_tapered_cylinder(kTapered, {{0, 0.4, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 2u);  // inside the top cap's radius 0.5
  ASSERT_TRUE(intersect_tapered_cylinder(kTapered, {{0, 0.6, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);  // outside it: the wall at radius 0.6, z = 0.8
  EXPECT_NEAR(hit.t, 4.2, 1e-15);
  EXPECT_NEAR(hit.point.y, 0.6, 1e-15);
  // Widening, top radius 2: radius 1 + z.
  ASSERT_TRUE(intersect_tapered_cylinder(kWidening, {{0, -5, 0.5}, {0, 1, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 3.5);
  expect_unit_parallel(hit.normal, {0, -1, -1});
  ASSERT_TRUE(intersect_tapered_cylinder(kWidening, {{1.5, 0, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 2u);
}

TEST(TaperedCylinder, TangentRays) {
  LocalHit hit;
  if (intersect_tapered_cylinder(kCylinder, {{1, -5, 0.5}, {0, 1, 0}}, kInfinity, hit)) {
    EXPECT_TRUE(finite_hit(hit));
    EXPECT_NEAR(hit.point.x, 1, 1e-15);
    EXPECT_NEAR(hit.point.y, 0, 1e-7);
  }
  EXPECT_FALSE(
      intersect_tapered_cylinder(kCylinder, {{1 + 1e-12, -5, 0.5}, {0, 1, 0}}, kInfinity, hit));
  ASSERT_TRUE(
      intersect_tapered_cylinder(kCylinder, {{1 - 1e-12, -5, 0.5}, {0, 1, 0}}, kInfinity, hit));
  EXPECT_NEAR(hit.t, 5, 2e-6);
}

TEST(TaperedCylinder, WallPointIsOnTheWall) {
  LocalHit hit;
  for (const TaperedCylinder& shape : {kCylinder, kCone, kTapered, kWidening}) {
    for (int i = 1; i < 300; ++i) {
      const Vec3 o{6 * std::sin(0.1 * i) * std::cos(0.77 * i),
                   6 * std::sin(0.1 * i) * std::sin(0.77 * i), 0.5 + 6 * std::cos(0.1 * i)};
      const double z = 0.5 + 0.4 * std::sin(0.7 * i);
      const double radius = 1 + (shape.top_radius - 1) * z;
      const Vec3 target{0.6 * radius * std::sin(i), 0.6 * radius * std::cos(1.3 * i), z};
      ASSERT_TRUE(intersect_tapered_cylinder(shape, {o, target - o}, kInfinity, hit));
      EXPECT_LT(dot(hit.normal, target - o), 0);
      if (hit.part != 0) continue;
      const double k = shape.top_radius - 1;
      const double w = 1 + k * hit.point.z;
      EXPECT_NEAR(std::hypot(hit.point.x, hit.point.y), w, 4e-16);
      EXPECT_LE(max_component(hit.point_error), 4e-15);
      EXPECT_GE(hit.point.z, 0);
      EXPECT_LE(hit.point.z, 1);
    }
  }
}

}  // namespace
}  // namespace tessera
