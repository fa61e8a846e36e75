// Nested media (common/render/media.h, tracer.cpp): a surface whose crossing leaves the
// governing medium unchanged is a false interface and neither shades nor refracts; glass of
// lower priority inside glass of higher priority is invisible, also when their boundaries
// coincide.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Material glass(double speed, int priority) {
  Material m = black_material();
  m.transparency = 1;
  m.speed_of_light = speed;
  m.priority = priority;
  return m;
}

Rgb trace_one(const Scene& scene, const Ray& ray) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  return trace_ray(prepared, ray);
}

// A slab of glass with the speed of air but priority 2 (it bends nothing), holding a ball of
// slow glass; a small green lamp lies on the straight line of an oblique ray through both.
// The ray crosses the ball's surface inside the slab: a false interface, so it goes straight
// on and sees the lamp. Were the ball to refract, the ray would bend and miss it.
Scene slab_holding_a_ball(int ball_priority) {
  Scene scene;
  scene.globals.background = {};
  scene.objects.push_back(
      object(Cube{}, Affine::scaling({10, 10, 1}), glass(1, 2)));  // z in [-1, 1]
  Material ball = glass(0.5, ball_priority);
  ball.emissive = {1, 0, 0};  // would show if the false interface were shaded
  scene.objects.push_back(object(Sphere{}, Affine::scaling({0.6, 0.6, 0.6}), ball));
  scene.objects.push_back(
      object(Sphere{}, Affine::translation({-0.9, 0, -4}) * Affine::scaling({0.1, 0.1, 0.1}),
             glowing({0, 1, 0})));
  return scene;
}

// Through (0.3, 0, 0), 0.29 from the ball's centre: it crosses the ball's surface obliquely.
const Ray kObliqueRay{{1.5, 0, 4}, normalize_or({-0.3, 0, -1}, {})};

TEST(NestedMedia, FalseInterfaceInsideHigherPriorityGlassNeitherRefractsNorShades) {
  EXPECT_EQ(trace_one(slab_holding_a_ball(1), kObliqueRay), (Rgb{0, 1, 0}));
  // The control: the same ball at a higher priority than the slab does refract.
  const Rgb governed = trace_one(slab_holding_a_ball(3), kObliqueRay);
  EXPECT_EQ(governed.g, 0);
  EXPECT_GT(governed.r, 0);
}

// Glass of lower priority inside glass of higher priority is invisible: the image equals the
// image without it, pixel for pixel, also when the two boundaries coincide exactly (the same
// sphere twice), whichever of the two is listed first.
Scene lit_backdrop() {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.globals.background = {0.1, 0.1, 0.3};
  Material floor;
  floor.diffuse = {0.8, 0.8, 0.8};
  scene.objects.push_back(
      object(Cube{}, Affine::translation({0, -1.5, 0}) * Affine::scaling({5, 0.2, 5}), floor));
  scene.objects.push_back(
      object(Sphere{}, Affine::translation({1.2, 0.8, -3}), glowing({0.9, 0.6, 0.1})));
  scene.lights.push_back(point_light({2, 5, 5}, {1, 1, 1}));
  return scene;
}

// Pixels with a channel differing by more than 1e-5 (or not finite).
int pixels_differing(const Image& a, const Image& b) {
  int count = 0;
  for (std::size_t i = 0; i < a.rgb.size(); i += 3) {
    bool differs = false;
    for (std::size_t c = i; c < i + 3; ++c)
      differs = differs || !(std::fabs(double(a.rgb[c]) - b.rgb[c]) <= 1e-5);
    count += differs ? 1 : 0;
  }
  return count;
}

TEST(NestedMedia, LowerPriorityGlassInsideHigherPriorityGlassIsInvisible) {
  const RenderSettings s = settings(64, 48);
  Scene alone = lit_backdrop();
  const SceneObject outer = object(Sphere{}, Affine::scaling({1.2, 1.2, 1.2}), glass(0.67, 2));
  alone.objects.push_back(outer);
  const Image expected = render(alone, s);

  Scene nested = alone;
  nested.objects.push_back(
      object(Sphere{}, Affine::translation({0.2, 0, 0}) * Affine::scaling({0.7, 0.9, 0.7}),
             glass(0.4, 1)));
  EXPECT_EQ(pixels_differing(expected, render(nested, s)), 0) << "contained";

  for (bool inner_first : {false, true}) {
    Scene coincident = lit_backdrop();
    const SceneObject inner = object(Sphere{}, outer.transform, glass(0.4, 1));
    coincident.objects.push_back(inner_first ? inner : outer);
    coincident.objects.push_back(inner_first ? outer : inner);
    EXPECT_EQ(pixels_differing(expected, render(coincident, s)), 0)
        << "coincident, inner listed " << (inner_first ? "first" : "second");
  }
}

// Flush faces computed through different transforms round differently: a glass box of
// lower priority filling the bottom half of a rotated glass cube shares five of its faces.
TEST(NestedMedia, FlushFacesOfLowerPriorityGlassAreInvisible) {
  const RenderSettings s = settings(64, 48);
  const Affine turn = *Affine::rotation(27, normalize_or({1, 2, 0.5}, {}));
  Scene alone = lit_backdrop();
  alone.objects.push_back(object(Cube{}, turn * Affine::scaling({0.9, 0.9, 0.9}), glass(0.67, 2)));
  const Image expected = render(alone, s);
  Scene flush = alone;
  flush.objects.push_back(
      object(Cube{}, turn * Affine::translation({0, -0.45, 0}) * Affine::scaling({0.9, 0.45, 0.9}),
             glass(0.4, 1)));
  EXPECT_EQ(pixels_differing(expected, render(flush, s)), 0);
}

// Interpenetrating glass of different priorities: in the overlap the higher priority governs
// whichever object is listed first, so the image does not depend on the order.
TEST(NestedMedia, InterpenetratingGlassDoesNotDependOnListingOrder) {
  const RenderSettings s = settings(64, 48);
  Material water = glass(0.75, 3);
  water.diffuse = {0.02, 0.03, 0.05};
  Material crystal = glass(0.6, 2);
  crystal.transparency = 0.9;
  crystal.diffuse = {0.05, 0.02, 0.02};
  const SceneObject a = object(Sphere{}, Affine::translation({-0.4, 0, 0}), water);
  const SceneObject b =
      object(Cube{},
             Affine::translation({0.5, 0.1, 0.2}) * *Affine::rotation(30, {1, 1, 0}) *
                 Affine::scaling({0.7, 0.7, 0.7}),
             crystal);
  Scene ab = lit_backdrop(), ba = lit_backdrop();
  ab.objects.push_back(a);
  ab.objects.push_back(b);
  ba.objects.push_back(b);
  ba.objects.push_back(a);
  RenderStats stats;
  const Image first = render(ab, s, &stats);
  EXPECT_GT(stats.refraction_rays, 1000u);
  EXPECT_EQ(pixels_differing(first, render(ba, s)), 0);
}

}  // namespace
}  // namespace tessera::test
