// The polyhedra of §3.3.1: closed, outward-wound, convex, of the documented size.
#include "common/loaders/polyhedra.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/loaders/mesh_checks.h"

namespace tessera::test {
namespace {

struct Expected {
  Polyhedron kind;
  const char* name;
  std::size_t vertices;
  std::size_t triangles;  // polygons fan-triangulated: an n-gon gives n - 2
  bool all_on_unit_sphere;
};

constexpr Expected kAll[] = {
    {Polyhedron::Tetrahedron, "tetrahedron", 4, 4, true},
    {Polyhedron::Octahedron, "octahedron", 6, 8, true},
    {Polyhedron::Icosahedron, "icosahedron", 12, 20, true},
    {Polyhedron::Dodecahedron, "dodecahedron", 20, 12 * 3, true},
    {Polyhedron::Buckyball, "buckyball", 60, 12 * 3 + 20 * 4, true},  // pentagons, hexagons
    {Polyhedron::Pyramid, "pyramid", 5, 4 + 2, true},
    {Polyhedron::Diamond, "diamond", 17, 6 + 8 * 2 + 8, false},  // table, crown, pavilion
};

TEST(Polyhedra, CountsAndNames) {
  for (const Expected& e : kAll) {
    const Mesh mesh = polyhedron_mesh(e.kind);
    EXPECT_EQ(mesh.source, e.name);
    EXPECT_EQ(mesh.positions.size(), e.vertices) << e.name;
    EXPECT_EQ(mesh.triangles.size(), e.triangles) << e.name;
    EXPECT_TRUE(mesh.normals.empty()) << e.name;  // flat shaded
  }
}

TEST(Polyhedra, ClosedOrientedSpheres) {
  for (const Expected& e : kAll) {
    const Mesh mesh = polyhedron_mesh(e.kind);
    EXPECT_TRUE(is_closed_and_oriented(mesh));
    EXPECT_EQ(euler_characteristic(mesh), 2) << e.name;
  }
}

TEST(Polyhedra, ConvexWithOutwardNormals) {
  // Every vertex lies on or behind the plane of every triangle, as seen along its geometric
  // normal: the normals point out and the solid is convex.
  for (const Expected& e : kAll) {
    const Mesh mesh = polyhedron_mesh(e.kind);
    for (const MeshTriangle& t : mesh.triangles) {
      const Vec3& p0 = mesh.positions[t.v[0]];
      const Vec3 n =
          normalize_or(cross(mesh.positions[t.v[1]] - p0, mesh.positions[t.v[2]] - p0), Vec3{});
      ASSERT_GT(length(n), 0.5) << e.name << ": degenerate triangle";
      for (const Vec3& p : mesh.positions) EXPECT_LE(dot(n, p - p0), 1e-12) << e.name;
    }
  }
}

TEST(Polyhedra, FitTheUnitSphere) {
  for (const Expected& e : kAll) {
    const Mesh mesh = polyhedron_mesh(e.kind);
    double farthest = 0;
    for (const Vec3& p : mesh.positions) {
      farthest = std::max(farthest, length(p));
      if (e.all_on_unit_sphere) {
        EXPECT_NEAR(length(p), 1, 1e-15) << e.name;
      }
    }
    EXPECT_NEAR(farthest, 1, 1e-15) << e.name;
  }
}

TEST(Polyhedra, KnownVolumes) {
  // Circumradius 1: the octahedron |x| + |y| + |z| <= 1, the tetrahedron of edge 4 / sqrt(6),
  // the pyramid of base area 2 and height 1, the icosahedron of edge 1 / sin(2 pi / 5).
  EXPECT_NEAR(enclosed_volume(polyhedron_mesh(Polyhedron::Octahedron)), 4.0 / 3, 1e-14);
  EXPECT_NEAR(enclosed_volume(polyhedron_mesh(Polyhedron::Tetrahedron)),
              8 * std::numbers::sqrt3 / 27, 1e-14);
  EXPECT_NEAR(enclosed_volume(polyhedron_mesh(Polyhedron::Pyramid)), 2.0 / 3, 1e-14);
  const double a = 1 / std::sin(2 * std::numbers::pi / 5);
  EXPECT_NEAR(enclosed_volume(polyhedron_mesh(Polyhedron::Icosahedron)),
              5.0 / 12 * (3 + std::sqrt(5.0)) * a * a * a, 1e-14);
}

TEST(Polyhedra, PyramidAndDiamondStandOnTheZAxis) {
  const Mesh pyramid = polyhedron_mesh(Polyhedron::Pyramid);
  EXPECT_EQ(pyramid.positions.back(), (Vec3{0, 0, 1}));  // apex
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(pyramid.positions[i].z, 0);
    // Base edges along x and y: every corner at (+-1/sqrt2, +-1/sqrt2).
    EXPECT_NEAR(std::fabs(pyramid.positions[i].x), 1 / std::numbers::sqrt2, 1e-15);
    EXPECT_NEAR(std::fabs(pyramid.positions[i].y), 1 / std::numbers::sqrt2, 1e-15);
  }
  const Mesh diamond = polyhedron_mesh(Polyhedron::Diamond);
  double top = -1, bottom = 1;
  for (const Vec3& p : diamond.positions) {
    top = std::max(top, p.z);
    bottom = std::min(bottom, p.z);
  }
  EXPECT_NEAR(top, 0.35, 1e-15);      // the table
  EXPECT_NEAR(bottom, -0.85, 1e-15);  // the culet
}

}  // namespace
}  // namespace tessera::test
