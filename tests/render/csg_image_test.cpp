// Boolean objects in whole images: an analytic silhouette with a drilled hole whose flush faces
// leave no speckles, A u A and A n A identical to A, A - A empty, a glass lens, the effect flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

// Adds a boolean object over the two objects just added.
void add_csg(Scene& scene, CsgOperation operation) {
  const auto n = static_cast<std::uint32_t>(scene.objects.size());
  scene.objects.push_back(
      object(CsgShape{operation, n - 2, n - 1}, Affine::identity(), Material{}));
}

Material emissive_white() {
  Material m = black_material();
  m.emissive = {1, 1, 1};
  return m;
}

TEST(CsgImage, DrilledCubeHeadOnIsASquareMinusTheSeeThroughDisk) {
  Scene scene;
  scene.camera = camera_on_z(30);
  // The cube [-s, s]^3, moved by c along z, minus a cylinder of radius s/2 along z whose caps
  // are flush with the cube's front and back faces. The two transforms round differently, so
  // the flush faces' t differ by a few ulps, not by nothing.
  const double s = 0.7, c = 0.3;
  const Affine scale = Affine::translation({0, 0, c}) * Affine::scaling({s, s, s});
  scene.objects.push_back(object(Cube{}, scale, emissive_white()));
  scene.objects.push_back(object(
      TaperedCylinder{1, false},
      scale * Affine::translation({0, 0, -1}) * Affine::scaling({0.5, 0.5, 2}), emissive_white()));
  add_csg(scene, CsgOperation::Difference);
  const int size = 200;
  const Image image = render(scene, settings(size, size));

  // In image-plane units at distance 1 from the eye: the front face is at distance 5 - c - s,
  // the back opening at 5 - c + s. Rays through the back opening's outline see the background; rays
  // between it and the front opening's outline meet the hole's wall.
  const double px_per_unit = size / 2 / std::tan(M_PI / 12);
  const double half_side = s / (5 - c - s) * px_per_unit;
  const double hole = s / 2 / (5 - c + s) * px_per_unit;
  int covered = 0, speckles = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool lit = image.get(x, y).r != 0;
      covered += lit ? 1 : 0;
      const double dx = x + 0.5 - size / 2.0, dy = y + 0.5 - size / 2.0;
      const double r = std::hypot(dx, dy);
      const double edge = half_side - std::max(std::fabs(dx), std::fabs(dy));
      // Away from every outline by more than a pixel, a pixel is lit exactly on the solid.
      if (std::fabs(edge) < 1.5 || std::fabs(r - hole) < 1.5) continue;
      speckles += lit != (edge > 0 && r > hole) ? 1 : 0;
    }
  EXPECT_EQ(speckles, 0);
  const double expected = 4 * half_side * half_side - M_PI * hole * hole;
  // Pixel centres decide coverage: off by at most half the outlines' length.
  EXPECT_NEAR(covered, expected, 4 * half_side + M_PI * hole + 4);
}

// A lit scene with shadows: a floor and, after it, what `add_solid` adds.
template <typename AddSolid>
Image lit_scene(AddSolid add_solid, BvhMode bvh = BvhMode::Sah) {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.lights.push_back(point_light({3, 4, 5}, {1, 1, 1}));
  Material floor;
  floor.diffuse = {0.6, 0.6, 0.6};
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, -2, 0}) * Affine::scaling({4, 0.5, 4}), floor));
  Material shiny;
  shiny.diffuse = {0.8, 0.3, 0.2};
  shiny.specular = {0.5, 0.5, 0.5};
  shiny.specular_exponent = 20;
  add_solid(scene, shiny);
  RenderSettings s = settings(96, 96);
  s.bvh = bvh;
  return render(scene, s);
}

const Affine kPlacement = Affine::translation({0.2, -0.3, 0}) * Affine::scaling({1, 0.8, 1.2});

TEST(CsgImage, AUnionAAndAIntersectionAAreBitIdenticalToA) {
  for (const ShapeGeometry& g :
       {ShapeGeometry(Sphere{}), ShapeGeometry(Cube{}), ShapeGeometry(Torus{0.4, 0.9})}) {
    SCOPED_TRACE(g.index());
    const Image alone = lit_scene([&](Scene& scene, const Material& m) {
      scene.objects.push_back(object(g, kPlacement, m));
    });
    for (const CsgOperation op : {CsgOperation::Union, CsgOperation::Intersection}) {
      const auto twice = [&](Scene& scene, const Material& m) {
        scene.objects.push_back(object(g, kPlacement, m));
        scene.objects.push_back(object(g, kPlacement, m));
        add_csg(scene, op);
      };
      EXPECT_TRUE(lit_scene(twice) == alone);
      EXPECT_TRUE(lit_scene(twice, BvhMode::None) == alone);
    }
  }
}

TEST(CsgImage, AMinusAIsEmpty) {
  const Image floor_only = lit_scene([](Scene&, const Material&) {});
  const Image a_minus_a = lit_scene([](Scene& scene, const Material& m) {
    scene.objects.push_back(object(Sphere{}, kPlacement, m));
    scene.objects.push_back(object(Sphere{}, kPlacement, m));
    add_csg(scene, CsgOperation::Difference);
  });
  EXPECT_TRUE(a_minus_a == floor_only);
}

TEST(CsgImage, GlassLensPassesTheBackgroundTwiceAttenuated) {
  Scene scene;
  scene.camera = camera_on_z(30);
  scene.globals.background = {0.2, 0.4, 0.8};
  Material glass = black_material();
  glass.transparency = 0.5;
  glass.speed_of_light = 0.6;
  // Two spheres' intersection: a lens 0.8 thick, its axis along the view.
  scene.objects.push_back(object(Sphere{}, Affine::translation({0, 0, -0.6}), glass));
  scene.objects.push_back(object(Sphere{}, Affine::translation({0, 0, 0.6}), glass));
  add_csg(scene, CsgOperation::Intersection);
  // Along the axis the ray is not bent: in through one sphere, out through the other, each
  // surface passing half.
  EXPECT_NEAR(render(scene, settings(65, 65)).get(32, 32).b, 0.25 * 0.8, 1e-6);
}

TEST(CsgImage, CsgEffectOnlyWithABooleanObject) {
  Scene scene;
  scene.objects.push_back(object(Sphere{}, Affine::identity(), Material{}));
  scene.objects.push_back(object(Cube{}, Affine::identity(), Material{}));
  EXPECT_FALSE(PreparedScene(scene, BvhMode::Sah).effects().has(Effect::Csg));
  add_csg(scene, CsgOperation::Union);
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_TRUE(prepared.effects().has(Effect::Csg));
  // The children are reached through the boolean object only.
  EXPECT_EQ(prepared.bvh().primitive_order, (std::vector<std::uint32_t>{2}));
}

}  // namespace
}  // namespace tessera::test
