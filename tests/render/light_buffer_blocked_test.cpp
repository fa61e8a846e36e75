// The light buffer's far side (inscribed_balls.h): a feeler it settles as blocked is one that
// the opaque solid's own occlusion test blocks. Random tori (ring, horn and spindle) and spheres
// under random rotations, scales (some not uniform) and translations, random lights (some in a
// torus's hole, inside its tube, or just outside its box), and feelers grazing the balls' cones,
// leaving the solids' own surfaces, and from anywhere near.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/math/float_error.h"
#include "common/render/inscribed_balls.h"
#include "common/render/light_buffer.h"
#include "common/scene/scene.h"
#include "common/stats/intersection_counters.h"
#include "tests/render/random_placement.h"

namespace tessera {
namespace {

struct Shape {
  Instance instance;
  // A point inside the solid (the sphere's centre, a point of the torus's balls' circle) and one
  // in the torus's hole, in object space.
  Vec3 inside, hole;
};

Shape random_shape(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  ShapeGeometry geometry = Sphere{};
  Shape shape;
  if (unit(rng) < 0.8) {
    const double big_r = 0.3 + 2 * unit(rng);
    const double kind = unit(rng);
    // Ring (thin to fat), horn, spindle (some with r >= 2R, whose core circle lies outside).
    const double r = kind < 0.6    ? big_r * (0.02 + 0.9 * unit(rng))
                     : kind < 0.75 ? big_r
                                   : big_r * (1 + 2.5 * unit(rng));
    geometry = Torus{r, big_r};
    shape.inside = {std::max(big_r, r), 0, 0};
    shape.hole = {0, 0, 0};
  }
  const Affine transform = random_placement(rng);
  shape.instance = *make_instance(geometry, transform, nullptr);
  return shape;
}

// Whether some shape's own occlusion test blocks the feeler from `origin` to `light`, as the
// tracer forms it (t_max 1, on the light).
bool walk_blocks(const std::vector<Shape>& shapes, const Vec3& origin, const Vec3& light) {
  IntersectionCounters counters;
  for (const Shape& s : shapes) {
    std::uint32_t object = 0;
    if (occluded_instance(s.instance, Ray{origin, light - origin, 0}, 1.0, object, counters))
      return true;
  }
  return false;
}

struct Tally {
  int feelers = 0, blocked = 0, grazing_blocked = 0, own_surface_blocked = 0;
};

void check_random_scene(std::mt19937_64& rng, Tally& tally) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Shape> shapes;
  const int count = 1 + static_cast<int>(unit(rng) * 3);
  for (int i = 0; i < count; ++i) shapes.push_back(random_shape(rng));
  const Instance& first = shapes[0].instance;
  const Vec3 centre = first.to_world.apply_point({0, 0, 0});
  const Vec3 extent = first.world_bounds.diagonal();
  const double size = length(extent);
  // The light: mostly around the first shape; sometimes in its hole, inside it, or just
  // outside its box.
  Vec3 light = centre + random_unit(rng) * size * (0.7 + 4 * unit(rng));
  const double where = unit(rng);
  const auto* torus = std::get_if<Torus>(&first.geometry);
  if (where < 0.1) {
    light = first.to_world.apply_point(shapes[0].hole + random_unit(rng) * 0.05);
  } else if (where < 0.2) {
    light = first.to_world.apply_point(shapes[0].inside + random_unit(rng) * 0.01);
  } else if (where < 0.3 && torus) {
    const double e = torus->torus_radius + torus->tube_radius;
    light = first.to_world.apply_point(
        {(2 * unit(rng) - 1) * e, (2 * unit(rng) - 1) * e, torus->tube_radius * (1 + 2e-6)});
  }
  std::vector<Bounds3> bounds;
  std::vector<std::uint32_t> ids;
  std::vector<InscribedBall> balls;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    bounds.push_back(shapes[i].instance.world_bounds);
    ids.push_back(static_cast<std::uint32_t>(i));
    for (const InscribedBall& b : inscribed_balls(shapes[i].instance, light)) balls.push_back(b);
  }
  const LightBuffer buffer(light, bounds, ids, balls);
  const auto check = [&](const Vec3& origin, int* kind) {
    ++tally.feelers;
    const LightBuffer::Candidates answer = buffer.candidates(origin);
    if (!answer.walk && !answer.blocked) {
      // With the balls' bounds in the cells, the candidates still hold every blocker.
      for (std::size_t i = 0; i < shapes.size(); ++i) {
        if (std::find(answer.ids, answer.ids + answer.count, i) != answer.ids + answer.count)
          continue;
        EXPECT_FALSE(walk_blocks({shapes[i]}, origin, light))
            << "shape " << i << " left out of the candidates";
      }
    }
    if (!answer.blocked) return;
    ++tally.blocked;
    if (kind) ++*kind;
    EXPECT_TRUE(walk_blocks(shapes, origin, light))
        << "settled as blocked, but no shape blocks the feeler from " << origin.x << ' ' << origin.y
        << ' ' << origin.z << " to " << light.x << ' ' << light.y << ' ' << light.z;
  };
  IntersectionCounters counters;
  for (int f = 0; f < 1500 && !::testing::Test::HasFailure(); ++f) {
    const double kind = unit(rng);
    if (kind < 0.4 && !balls.empty()) {
      // Grazing a ball's cone: along a direction at its rim's angle, give or take a little,
      // from just beyond the ball or further.
      const InscribedBall& ball =
          balls[std::uniform_int_distribution<std::size_t>(0, balls.size() - 1)(rng)];
      const Vec3 axis = ball.centre - light;
      const double distance = length(axis);
      if (!(distance > ball.radius)) continue;
      const double angle = std::asin(ball.radius / distance) * (0.97 + 0.06 * unit(rng));
      Vec3 across = cross(axis, random_unit(rng));
      across = across / length(across);
      const Vec3 w = axis / distance * std::cos(angle) + across * std::sin(angle);
      const double beyond = distance + ball.radius;
      const double s =
          unit(rng) < 0.5 ? beyond * (1 + 1e-7 * unit(rng)) : beyond + 3 * size * unit(rng);
      check(light + w * s, &tally.grazing_blocked);
    } else if (kind < 0.7) {
      // From a shape's own surface, spawned towards the light as the tracer spawns feelers.
      const Shape& s =
          shapes[std::uniform_int_distribution<std::size_t>(0, shapes.size() - 1)(rng)];
      const Vec3 target = s.instance.to_world.apply_point(s.inside * unit(rng));
      const Vec3 from = target + random_unit(rng) * size * 3;
      WorldHit hit;
      if (!intersect_instance(s.instance, Ray{from, target - from, 0}, kInfinity, hit, counters))
        continue;
      check(offset_ray_origin(hit.point, hit.point_error, hit.normal, light - hit.point),
            &tally.own_surface_blocked);
    } else {
      const Vec3 r{2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1};
      check(centre + mul(r, extent) * 2, nullptr);
    }
  }
}

TEST(LightBufferBlocked, NeverContradictsTheShapesOwnTest) {
  std::mt19937_64 rng(20261128);
  Tally tally;
  for (int scene = 0; scene < 400 && !::testing::Test::HasFailure(); ++scene)
    check_random_scene(rng, tally);
  // Enough of each kind settled for the check to mean something.
  EXPECT_GT(tally.blocked, 20000) << tally.feelers << " feelers";
  EXPECT_GT(tally.grazing_blocked, 5000);
  EXPECT_GT(tally.own_surface_blocked, 1000);
}

// A transparent object's balls are not used: a feeler through it is only attenuated.
TEST(LightBufferBlocked, OnlyOpaqueObjectsBlock) {
  Scene scene;
  SceneObject torus;
  torus.geometry = Torus{0.4, 1};
  scene.objects.push_back(torus);
  scene.objects.push_back(torus);
  scene.objects[1].material.transparency = 0.5;
  std::vector<Instance> placed(2, *make_instance(Torus{0.4, 1}, Affine::identity(), nullptr));
  placed[1].object = 1;
  const std::uint32_t both[] = {0, 1}, transparent[] = {1};
  const Vec3 light{0, 0, 10};
  EXPECT_FALSE(opaque_balls(scene, placed, both, light).empty());
  EXPECT_TRUE(opaque_balls(scene, placed, transparent, light).empty());
}

// Lights in a torus's hole or inside its box give it no balls; a light inside a sphere none.
TEST(LightBufferBlocked, NoBallsForLightsInsideTheBounds) {
  const Instance torus = *make_instance(Torus{0.4, 1}, Affine::identity(), nullptr);
  EXPECT_TRUE(inscribed_balls(torus, {0, 0, 0}).empty());
  EXPECT_TRUE(inscribed_balls(torus, {1.3, 0, 0.39}).empty());
  EXPECT_EQ(inscribed_balls(torus, {0, 0, 0.5}).size(), 32u);
  const Instance sphere = *make_instance(Sphere{}, Affine::scaling({2, 2, 2}), nullptr);
  EXPECT_TRUE(inscribed_balls(sphere, {1.9, 0, 0}).empty());
  ASSERT_EQ(inscribed_balls(sphere, {0, 0, 5}).size(), 1u);
  EXPECT_NEAR(inscribed_balls(sphere, {0, 0, 5})[0].radius, 1.94, 1e-6);  // 0.97 of it
}

// A spindle torus's balls (about the circle rho = r, of radius 0.97 R) reach near its outer
// equator, its dimples and the lemon that the tube's self-overlap leaves outside: feelers from
// far beyond, aimed at a fine grid of directions across the torus from lights above, beside
// and oblique, are settled as blocked only when the torus's own test blocks them.
TEST(LightBufferBlocked, SpindleBallsStayInsideTheSolid) {
  int settled = 0;
  for (const double ratio : {1.2, 1.9, 2.5, 4.0}) {
    const double big_r = 0.5, r = big_r * ratio, e = big_r + r;
    const Shape shape{*make_instance(Torus{r, big_r}, Affine::identity(), nullptr), {}, {}};
    for (const Vec3& light : {Vec3{0, 0, 2.5 * e}, Vec3{0, 3 * e, 0}, Vec3{1.5 * e, 0.7 * e, e}}) {
      const std::vector<InscribedBall> balls = inscribed_balls(shape.instance, light);
      ASSERT_FALSE(balls.empty());
      const Bounds3 bounds[] = {shape.instance.world_bounds};
      const std::uint32_t ids[] = {0};
      const LightBuffer buffer(light, bounds, ids, balls);
      // Directions towards the grid's points on the plane through the axis facing the light.
      const Vec3 toward = -light / length(light);
      Vec3 u = cross(toward, std::fabs(toward.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
      u = u / length(u);
      const Vec3 v = cross(toward, u);
      constexpr int kGrid = 300;
      for (int i = 0; i <= kGrid; ++i)
        for (int j = 0; j <= kGrid; ++j) {
          const Vec3 target = u * (e * (2.0 * i / kGrid - 1)) + v * (e * (2.0 * j / kGrid - 1));
          const Vec3 origin = light + (target - light) * 3;
          if (!buffer.candidates(origin).blocked) continue;
          ++settled;
          ASSERT_TRUE(walk_blocks({shape}, origin, light))
              << "r/R " << ratio << ": settled as blocked, but the torus lets the feeler from "
              << origin.x << ' ' << origin.y << ' ' << origin.z << " pass";
        }
    }
  }
  EXPECT_GT(settled, 400000);
}

TEST(LightBufferBlocked, SingularValues) {
  const SingularValues sv =
      singular_values(*Affine::rotation(30, {1, 2, 3}) * Affine::scaling({0.5, 2, 3}));
  EXPECT_NEAR(sv.least, 0.5, 1e-6);
  EXPECT_LE(sv.least, 0.5);
  EXPECT_NEAR(sv.greatest, 3, 1e-6);
  EXPECT_GE(sv.greatest, 3);
}

}  // namespace
}  // namespace tessera
