// Debug views: the normals view shows a sphere's normals as colours, and the cost view is
// brightest where the most intersection tests were made.
#include "common/render/debug_views.h"

#include <gtest/gtest.h>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

constexpr int kSize = 33;
constexpr int kCentre = 16;  // the pixel whose ray is the view axis

Scene sphere_scene() {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.objects.push_back(object(Sphere{}, Affine::identity(), Material{}));
  scene.lights.push_back(point_light({0, 5, 5}, {1, 1, 1}));
  return scene;
}

TEST(DebugViews, NormalsAreColoursOfTheFirstHitsNormal) {
  const Scene scene = sphere_scene();
  const PreparedScene prepared(scene, BvhMode::Sah);
  const Image image = render_normals(prepared, settings(kSize, kSize));
  // Head on, the sphere's normal is +z: (0.5, 0.5, 1).
  const Rgb centre = image.get(kCentre, kCentre);
  EXPECT_NEAR(centre.r, 0.5, 1e-6);
  EXPECT_NEAR(centre.g, 0.5, 1e-6);
  EXPECT_NEAR(centre.b, 1.0, 1e-6);
  // Above the centre the normal leans towards +y: more green, no more red.
  const Rgb upper = image.get(kCentre, kCentre - 6);
  EXPECT_GT(upper.g, 0.55);
  EXPECT_NEAR(upper.r, 0.5, 1e-6);
  EXPECT_EQ(image.get(0, 0), Rgb{});  // the corner misses the sphere
}

TEST(DebugViews, CostIsWhiteWhereTheMostTestsWereMade) {
  const Scene scene = sphere_scene();
  const PreparedScene prepared(scene, BvhMode::Sah);
  std::uint64_t largest = 0;
  const Image image = render_cost(prepared, settings(kSize, kSize), largest);
  // A pixel on the sphere tests the sphere for the camera ray and its shadow feeler; a pixel
  // beside it only for the camera ray (if the BVH lets it through at all).
  EXPECT_GE(largest, 2u);
  const Rgb centre = image.get(kCentre, kCentre), corner = image.get(0, 0);
  EXPECT_GT(centre.r + centre.g + centre.b, corner.r + corner.g + corner.b);
  double brightest = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) brightest = std::max(brightest, image.get(x, y).b);
  EXPECT_EQ(brightest, 1.0);  // the most expensive pixel is white
}

}  // namespace
}  // namespace tessera::test
