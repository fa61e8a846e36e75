// showExtents (§3.2.7): every object's world bounds drawn as white bars, besides the objects.
#include <gtest/gtest.h>

#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

Scene ball(bool show_extents) {
  Scene scene;
  scene.camera = camera_on_z(40);
  scene.globals.show_extents = show_extents;
  scene.objects.push_back(
      object(Sphere{}, Affine::identity(), glowing({0.6, 0, 0})));  // bounds [-1, 1]^3
  return scene;
}

Rgb seen_towards(const Scene& scene, const Vec3& target) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  const Vec3 eye = scene.camera.eye;
  return trace_ray(prepared, {eye, normalize_or(target - eye, Vec3{}), 0});
}

TEST(ShowExtents, AddsTwelveBarsPerObjectAndReportsTheEffect) {
  const Scene plain = ball(false), shown = ball(true);
  const PreparedScene without(plain, BvhMode::Sah), with(shown, BvhMode::Sah);
  EXPECT_FALSE(without.effects().has(Effect::ShowExtents));
  EXPECT_EQ(without.scene().objects.size(), 1u);
  EXPECT_TRUE(with.effects().has(Effect::ShowExtents));
  EXPECT_EQ(with.scene().objects.size(), 13u);
  EXPECT_EQ(with.instances().size(), 13u);
  EXPECT_TRUE(with.unsupported().empty());
}

TEST(ShowExtents, TheBoxEdgesGlowWhiteAndTheObjectStaysVisible) {
  // (0, 1, 1) is the middle of the bounding box's top front edge, outside the ball.
  EXPECT_EQ(seen_towards(ball(false), {0, 1, 1}), Rgb{});
  EXPECT_EQ(seen_towards(ball(true), {0, 1, 1}), (Rgb{1, 1, 1}));
  EXPECT_EQ(seen_towards(ball(true), {0, 0, 0}), (Rgb{0.6, 0, 0}));
}

TEST(ShowExtents, BooleanObjectsKeepTheirChildren) {
  // The bars are instances added after the scene's: the boolean object's pointers to its
  // children's instances must survive them (the sanitizer build checks the memory).
  Scene scene = ball(true);
  scene.objects.push_back(object(Sphere{}, Affine::translation({0.5, 0, 0}), glowing({0, 0.6, 0})));
  scene.objects.push_back(
      object(CsgShape{CsgOperation::Difference, 0, 1}, Affine::identity(), glowing({0, 0, 0})));
  const PreparedScene prepared(scene, BvhMode::Sah);
  EXPECT_EQ(prepared.instances().size(), 3u + 3 * 12);
  // Along x = 0 the left ball's front is outside the subtracted one: seen. Along x = 0.4 the
  // subtracted ball holds all of the left one's chord: the ray passes through to the black.
  EXPECT_EQ(trace_ray(prepared, {{0, 0, 5}, Vec3{0, 0, -1}, 0}), (Rgb{0.6, 0, 0}));
  EXPECT_EQ(trace_ray(prepared, {{0.4, 0, 5}, Vec3{0, 0, -1}, 0}), Rgb{});
}

}  // namespace
}  // namespace tessera::test
