// A tapered cylinder with parts left out (VRML's Cylinder and Cone side, bottom, top FALSE):
// rays pass where a part is missing and still meet the parts that remain.
#include <gtest/gtest.h>

#include "common/geometry/shapes.h"

namespace tessera {
namespace {

TaperedCylinder parts(double top_radius, bool wall, bool base, bool top) {
  TaperedCylinder shape{top_radius, false};
  shape.wall = wall;
  shape.base_cap = base;
  shape.top_cap = top;
  return shape;
}

TEST(TaperedCylinderParts, OpenTubeIsSeenThroughAlongItsAxis) {
  const TaperedCylinder tube = parts(1, true, false, false);
  LocalHit hit;
  // Along the axis: no caps, so nothing.
  EXPECT_FALSE(intersect_tapered_cylinder(tube, {{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  // Slanted through the open base: the far wall from inside.
  ASSERT_TRUE(intersect_tapered_cylinder(tube, {{0, 0, -1}, {1, 0, 1.5}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);
  EXPECT_NEAR(hit.point.x, 1, 1e-12);
  EXPECT_NEAR(hit.point.z, 0.5, 1e-12);
  EXPECT_TRUE(tapered_cylinder_crossings(tube, {{0, 0, -5}, {0, 0, 1}}, kInfinity).empty());
}

TEST(TaperedCylinderParts, CapsAloneAreDiscs) {
  const TaperedCylinder caps = parts(1, false, true, true);
  LocalHit hit;
  // Across the wall's height: no wall.
  EXPECT_FALSE(intersect_tapered_cylinder(caps, {{-5, 0, 0.5}, {1, 0, 0}}, kInfinity, hit));
  ASSERT_TRUE(intersect_tapered_cylinder(caps, {{0.3, 0.2, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 2u);
  EXPECT_EQ(hit.t, 4);
  // The base alone: from above, the ray passes the missing top and meets the base.
  const TaperedCylinder base = parts(1, false, true, false);
  ASSERT_TRUE(intersect_tapered_cylinder(base, {{0.3, 0.2, 5}, {0, 0, -1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 1u);
  EXPECT_EQ(hit.t, 5);
}

TEST(TaperedCylinderParts, ConeWithoutItsBaseShowsItsInside) {
  const TaperedCylinder cone = parts(0, true, false, true);
  LocalHit hit;
  // From below through the open base: the wall from inside, at radius 1 - z.
  ASSERT_TRUE(intersect_tapered_cylinder(cone, {{0.5, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);
  EXPECT_NEAR(hit.point.z, 0.5, 1e-12);
  const TaperedCylinder whole{0, false};
  ASSERT_TRUE(intersect_tapered_cylinder(whole, {{0.5, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 1u);  // the base, when it is drawn
}

}  // namespace
}  // namespace tessera
