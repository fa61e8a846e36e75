// Texture coordinates of §4.3.2 at points where each shape's mapping is known by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "common/texture/texture_coordinates.h"

namespace tessera {
namespace {

::testing::AssertionResult at(TexCoord st, double s, double t, double tolerance = 1e-12) {
  if (std::fabs(st.s - s) <= tolerance && std::fabs(st.t - t) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "(" << st.s << ", " << st.t << ") vs (" << s << ", " << t << ")";
}

TEST(TextureCoordinates, SphereLongitudeAndLatitude) {
  EXPECT_TRUE(at(sphere_texture_coordinates({1, 0, 0}), 0, 0.5));
  EXPECT_TRUE(at(sphere_texture_coordinates({0, 1, 0}), 0.25, 0.5));
  EXPECT_TRUE(at(sphere_texture_coordinates({-1, 0, 0}), 0.5, 0.5));
  EXPECT_TRUE(at(sphere_texture_coordinates({0, -1, 0}), 0.75, 0.5));
  EXPECT_TRUE(at(sphere_texture_coordinates({0, 0, 1}), 0, 1));   // north pole
  EXPECT_TRUE(at(sphere_texture_coordinates({0, 0, -1}), 0, 0));  // south pole
  const double h = std::sqrt(0.5);
  EXPECT_TRUE(at(sphere_texture_coordinates({h, 0, h}), 0, 0.75));
}

TEST(TextureCoordinates, CubeFacesAsSeenFromOutside) {
  // Part numbers: -x, +x, -y, +y, -z, +z.
  EXPECT_TRUE(at(cube_texture_coordinates({0.5, -0.5, 1}, 5), 0.75, 0.25));  // +z
  EXPECT_TRUE(at(cube_texture_coordinates({0.5, 0.5, -1}, 4), 0.25, 0.75));  // -z
  EXPECT_TRUE(at(cube_texture_coordinates({1, 0.5, 0.5}, 1), 0.25, 0.75));   // +x
  EXPECT_TRUE(at(cube_texture_coordinates({-1, 0.5, 0.5}, 0), 0.75, 0.75));  // -x
  EXPECT_TRUE(at(cube_texture_coordinates({0.5, 1, 0.5}, 3), 0.75, 0.25));   // +y
  EXPECT_TRUE(at(cube_texture_coordinates({0.5, -1, 0.5}, 2), 0.75, 0.75));  // -y
  EXPECT_TRUE(at(cube_texture_coordinates({-1, -1, 1}, 5), 0, 0));           // corners
  EXPECT_TRUE(at(cube_texture_coordinates({1, 1, 1}, 5), 1, 1));
}

TEST(TextureCoordinates, TaperedCylinderWall) {
  const TaperedCylinder cone{0, false};
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(cone, {0, 1, 0}, 0), 0.25, 0));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(cone, {-0.3, 0, 0.7}, 0), 0.5, 0.7));
}

TEST(TextureCoordinates, CapsClippedOrDistorted) {
  const TaperedCylinder clip{0.5, false}, distort{0.5, true};
  const double h = std::sqrt(0.5);
  // The base (part 1, radius 1): on an axis both agree; on the diagonal the rim reaches the
  // square's corner only when distorted.
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(clip, {0.5, 0, 0}, 1), 0.75, 0.5));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(distort, {0.5, 0, 0}, 1), 0.75, 0.5));
  EXPECT_TRUE(
      at(tapered_cylinder_texture_coordinates(clip, {h, h, 0}, 1), (1 + h) / 2, (1 + h) / 2));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(distort, {h, h, 0}, 1), 1, 1, 1e-12));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(distort, {-h, h, 0}, 1), 0, 1, 1e-12));
  // Half-way out on the diagonal: half-way to the corner.
  EXPECT_TRUE(
      at(tapered_cylinder_texture_coordinates(distort, {h / 2, -h / 2, 0}, 1), 0.75, 0.25, 1e-12));
  // Eq. 4.43 in the first quadrant below the diagonal: s' = 1, t' = tan(alpha).
  const double a = 0.3, r = 0.8;
  EXPECT_TRUE(
      at(tapered_cylinder_texture_coordinates(distort, {r * std::cos(a), r * std::sin(a), 0}, 1),
         (1 + r) / 2, (1 + r * std::tan(a)) / 2, 1e-12));
  // The top cap (part 2) has the top radius 0.5; its centre is the square's centre.
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(clip, {0.25, 0, 1}, 2), 0.75, 0.5));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(distort, {0.25 * h, 0.25 * h, 1}, 2), 0.75,
                 0.75, 1e-12));
  EXPECT_TRUE(at(tapered_cylinder_texture_coordinates(distort, {0, 0, 1}, 2), 0.5, 0.5));
}

TEST(TextureCoordinates, TorusAroundTheRingAndTheTube) {
  const Torus torus{0.25, 1};
  EXPECT_TRUE(at(torus_texture_coordinates(torus, {1.25, 0, 0}), 0, 0));         // outer equator
  EXPECT_TRUE(at(torus_texture_coordinates(torus, {-0.75, 0, 0}), 0.5, 0.5));    // inner equator
  EXPECT_TRUE(at(torus_texture_coordinates(torus, {0, 1, 0.25}), 0.25, 0.75));   // top
  EXPECT_TRUE(at(torus_texture_coordinates(torus, {0, 1, -0.25}), 0.25, 0.25));  // bottom
}

TEST(TextureCoordinates, MeshesAreShrinkWrappedBySphericalCoordinates) {
  EXPECT_TRUE(at(mesh_texture_coordinates({0, 0, 3}), 0, 0));
  EXPECT_TRUE(at(mesh_texture_coordinates({0, -2, 0}), 0.75, 0.5));
  EXPECT_TRUE(at(mesh_texture_coordinates({0, 0, -0.1}), 0, 1));
  EXPECT_TRUE(at(mesh_texture_coordinates({0, 0, 0}), 0, 0));
}

TEST(TextureCoordinates, AlgebraicSurfacesAreShrinkWrappedInTheirBox) {
  EXPECT_TRUE(at(algebraic_texture_coordinates({0, 1, 0.5}, 2), 0.25, 0.25));
  EXPECT_TRUE(at(algebraic_texture_coordinates({-1, 0, -1}, 2), 0.5, 1));
  // Through an instance: the box is centred where the transform takes the origin.
  const AlgebraicSurface surface{AlgebraicKind::EllipticCylinder, {2, 2, 4}};
  const std::optional<Instance> instance =
      make_instance(surface, Affine::translation({5, 0, 0}), nullptr);
  ASSERT_TRUE(instance);
  WorldHit hit;
  hit.point = {5, -1, 1};
  EXPECT_TRUE(at(texture_coordinates(*instance, hit), 0.75, 0.25));
}

TEST(TextureCoordinates, InstancesUseTheObjectSpacePointAndPart) {
  const std::optional<Instance> cube =
      make_instance(Cube{}, Affine::translation({0, 0, -7}), nullptr);
  ASSERT_TRUE(cube);
  WorldHit hit;
  hit.object_point = {0.5, -0.5, 1};
  hit.point = hit.object_point + Vec3{0, 0, -7};
  hit.part = 5;
  EXPECT_TRUE(at(texture_coordinates(*cube, hit), 0.75, 0.25));
}

}  // namespace
}  // namespace tessera
