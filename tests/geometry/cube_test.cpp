#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/geometry/shapes.h"

namespace tessera {
namespace {

TEST(Cube, HitsEachFaceWithItsIndex) {
  // Parts: -x, +x, -y, +y, -z, +z.
  const Vec3 directions[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (std::uint32_t face = 0; face < 6; ++face) {
    SCOPED_TRACE(face);
    const Vec3 d = directions[face];
    LocalHit hit;
    ASSERT_TRUE(intersect_cube({d * -5 + Vec3{0.1, 0.2, 0.3}, d}, kInfinity, hit));
    EXPECT_EQ(hit.part, face);
    EXPECT_EQ(hit.normal, -d);
    EXPECT_EQ(hit.shading_normal, -d);
    EXPECT_DOUBLE_EQ(hit.t, 4 - dot(d, Vec3{0.1, 0.2, 0.3}));
    // The face coordinate is exact and carries no error.
    const int axis = static_cast<int>(face / 2);
    EXPECT_EQ(hit.point[axis], face % 2 ? 1 : -1);
    EXPECT_EQ(hit.point_error[axis], 0);
  }
}

TEST(Cube, ExactRootAndMisses) {
  LocalHit hit;
  ASSERT_TRUE(intersect_cube({{0, 0, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{0, 0, -1}));
  EXPECT_FALSE(intersect_cube({{0, 1.5, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_FALSE(intersect_cube({{0, 0, 5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_FALSE(intersect_cube({{0, 0, -5}, {0, 0, 1}}, 4, hit));
  EXPECT_FALSE(intersect_cube({{0, 0, -5}, {0, 0, 0}}, kInfinity, hit));
  EXPECT_FALSE(intersect_cube({{-2.5, 0, -5}, {1, 0, 1}}, kInfinity, hit));  // passes the edge
  EXPECT_TRUE(intersect_cube({{-3, 0, -5}, {1, 0, 1}}, kInfinity, hit));     // touches the edge
  EXPECT_EQ(hit.point, (Vec3{1, 0, -1}));
  EXPECT_FALSE(intersect_cube({{0, 0, -5}, {NAN, 0, 1}}, kInfinity, hit));
}

TEST(Cube, OriginInsideFindsTheExit) {
  LocalHit hit;
  ASSERT_TRUE(intersect_cube({{0.5, 0, 0}, {1, 0, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 0.5);
  EXPECT_EQ(hit.part, 1u);
  EXPECT_EQ(hit.normal, (Vec3{1, 0, 0}));
  ASSERT_TRUE(intersect_cube({{0, 0, 0}, {0.5, -1, 0.25}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.part, 2u);
  EXPECT_EQ(hit.point, (Vec3{0.5, -1, 0.25}));
}

TEST(Cube, OriginOnAFace) {
  LocalHit hit;
  EXPECT_FALSE(intersect_cube({{1, 0.3, 0.2}, {1, 0.5, 0}}, kInfinity, hit));  // leaving
  ASSERT_TRUE(intersect_cube({{1, 0.3, 0.2}, {-1, 0, 0}}, kInfinity, hit));    // far side
  EXPECT_EQ(hit.t, 2);
  EXPECT_EQ(hit.part, 0u);
}

TEST(Cube, RaysAlongEdgesAndThroughCorners) {
  LocalHit hit;
  // Along an edge, parallel to it: the closed box is touched at the edge's end.
  ASSERT_TRUE(intersect_cube({{1, 1, -5}, {0, 0, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 4);
  EXPECT_EQ(hit.point, (Vec3{1, 1, -1}));
  EXPECT_EQ(hit.part, 4u);
  EXPECT_FALSE(intersect_cube({{1, std::nextafter(1.0, 2.0), -5}, {0, 0, 1}}, kInfinity, hit));
  // Through a corner along the diagonal.
  ASSERT_TRUE(intersect_cube({{-2, -2, -2}, {1, 1, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.point, (Vec3{-1, -1, -1}));
  // Grazing a face plane (the ray lies in x = 1).
  ASSERT_TRUE(intersect_cube({{1, -5, 0.5}, {0, 1, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.point, (Vec3{1, -1, 0.5}));
  // Across an edge diagonally: enters exactly at the edge.
  ASSERT_TRUE(intersect_cube({{-2, -2, 0.5}, {1, 1, 0}}, kInfinity, hit));
  EXPECT_EQ(hit.t, 1);
  EXPECT_EQ(hit.point, (Vec3{-1, -1, 0.5}));
}

TEST(Cube, TiesGoToTheFirstAxis) {
  // Through a corner: the three slabs are entered (and left) at the same t; the hit and both
  // crossings name the x faces, as they always have (a texture's face depends on it).
  LocalHit hit;
  ASSERT_TRUE(intersect_cube({{-2, -2, -2}, {1, 1, 1}}, kInfinity, hit));
  EXPECT_EQ(hit.part, 0u);
  EXPECT_EQ(hit.normal, (Vec3{-1, 0, 0}));
  ASSERT_TRUE(intersect_cube({{0, 0, 0}, {-1, 1, 1}}, kInfinity, hit));  // from inside
  EXPECT_EQ(hit.part, 0u);
  const std::vector<LocalHit> crossings = cube_crossings({{2, -2, 2}, {-1, 1, -1}}, kInfinity);
  ASSERT_EQ(crossings.size(), 2u);
  EXPECT_EQ(crossings[0].part, 1u);
  EXPECT_EQ(crossings[1].part, 0u);
  EXPECT_EQ(crossings[1].point, (Vec3{-1, 1, -1}));
}

TEST(Cube, PointStaysOnTheCube) {
  LocalHit hit;
  for (int i = 1; i < 500; ++i) {
    const Vec3 o{6 * std::sin(0.1 * i) * std::cos(0.77 * i),
                 6 * std::sin(0.1 * i) * std::sin(0.77 * i), 6 * std::cos(0.1 * i)};
    const Vec3 target{0.9 * std::sin(i), 0.9 * std::cos(1.3 * i), 0.9 * std::sin(0.7 * i)};
    ASSERT_TRUE(intersect_cube({o, target - o}, kInfinity, hit));
    EXPECT_LE(max_component(abs(hit.point)), 1);
    EXPECT_EQ(max_component(abs(hit.point)), 1);
    EXPECT_LT(max_component(hit.point_error), 1e-14);
    EXPECT_LT(dot(hit.normal, target - o), 0);
  }
}

}  // namespace
}  // namespace tessera
