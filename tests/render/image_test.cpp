// Whole images against analytic expectations: silhouettes, the background rule, transparency.
#include <gtest/gtest.h>

#include <cmath>

#include "common/loaders/polyhedra.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

int count_pixels_not(const Image& image, double value) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.get(x, y).r != value ? 1 : 0;
  return n;
}

TEST(Image, SphereSilhouetteAreaMatchesPerspectiveProjection) {
  Material m = black_material();
  m.emissive = {1, 1, 1};
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Sphere{}, Affine::identity(), m));
  const int size = 256;
  // Seen from distance 5, the unit sphere subtends asin(1/5); on the image plane at distance 1
  // its outline is a circle of radius tan(asin(1/5)) = 1/sqrt(24).
  const double radius_px = (1 / std::sqrt(24.0)) / std::tan(M_PI / 12) * size / 2;
  const double expected = M_PI * radius_px * radius_px;
  const int covered = count_pixels_not(render(scene, settings(size, size)), 0.0);
  EXPECT_NEAR(covered, expected, 0.005 * expected);
}

TEST(Image, CubeSilhouetteIsASquareOfKnownSide) {
  Material m = black_material();
  m.emissive = {1, 1, 1};
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Cube{}, Affine::identity(), m));
  const int size = 200;
  // The front face z = 1 is nearest: half-side 1 at distance 4 on the image plane: 1/4.
  const double side_px = 0.25 / std::tan(M_PI / 12) * size;
  const int covered = count_pixels_not(render(scene, settings(size, size)), 0.0);
  EXPECT_NEAR(covered, side_px * side_px, 2 * side_px + 4);
}

TEST(Image, OctahedronSeenAlongAnAxisIsASquareOfKnownArea) {
  Material m = black_material();
  m.emissive = {1, 1, 1};
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.meshes.push_back(polyhedron_mesh(Polyhedron::Octahedron));
  scene.objects.push_back(object(MeshShape{0, false}, Affine::identity(), m));
  const int size = 200;
  // The outline is the equator, the square of vertices (+-1, 0, 0) and (0, +-1, 0) at distance
  // 5: half-diagonals of 1/5 on the image plane at distance 1, an area of 2 (1/5)^2.
  const double half_diagonal_px = 0.2 / std::tan(M_PI / 12) * size / 2;
  const double expected = 2 * half_diagonal_px * half_diagonal_px;
  const int covered = count_pixels_not(render(scene, settings(size, size)), 0.0);
  EXPECT_NEAR(covered, expected, 0.01 * expected);
}

TEST(Image, MissesShowTheBackgroundButReflectedMissesAreBlack) {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.globals.background = {0.2, 0.4, 0.6};
  Material mirror = black_material();
  mirror.reflectivity = 1;
  scene.objects.push_back(object(Sphere{}, Affine::identity(), mirror));
  const Image image = render(scene, settings(65, 65));
  EXPECT_EQ(image.get(0, 0).b, double(0.6f));  // corner: background (eq. 4.2)
  EXPECT_EQ(image.get(32, 32).b, 0.0);         // the mirror reflects into emptiness: black
}

TEST(Image, BackgroundSeenThroughTransparentSphereAtSpeedOne) {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.globals.background = {0.2, 0.4, 0.8};
  Material glass = black_material();
  glass.transparency = 0.5;  // speed of light 1: no bending
  scene.objects.push_back(object(Sphere{}, Affine::identity(), glass));
  // Two surfaces, each passing half: 0.25 of the background (eq. 4.17).
  EXPECT_NEAR(render(scene, settings(65, 65)).get(32, 32).b, 0.25 * 0.8, 1e-6);
}

TEST(Image, RefractionThroughGlassSphereInvertsTheScene) {
  // A glass ball acts as a lens: an emissive square above the axis appears below it.
  Scene scene;
  scene.camera = camera_on_z(20);
  Material glass = black_material();
  glass.transparency = 1;
  glass.speed_of_light = 1 / 1.5;
  scene.objects.push_back(object(Sphere{}, Affine::identity(), glass));
  Material lamp = black_material();
  lamp.emissive = {1, 1, 1};
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, 3, -20}) * Affine::scaling({4, 3, 0.1}), lamp));
  const Image image = render(scene, settings(65, 65));
  const double above = image.get(32, 26).r;  // inside the ball, upper half
  const double below = image.get(32, 38).r;  // inside the ball, lower half
  EXPECT_EQ(above, 0.0);
  EXPECT_EQ(below, 1.0);
}

}  // namespace
}  // namespace tessera::test
