// A torus enters the light buffer with sector boxes as its pieces (prepared_scene.h,
// light_buffer_pieces): a cell that leaves it out, or a feeler too short to reach its bound
// there, must be one that the torus's own occlusion test lets through. Random tori (ring, horn and
// spindle) under random rotations, scales (some not uniform) and translations; lights around them,
// in their holes and just off their surfaces; feelers from just beyond points of the surface,
// grazing it, and from anywhere near.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/render/light_buffer.h"
#include "common/render/prepared_scene.h"
#include "common/stats/intersection_counters.h"
#include "tests/render/random_placement.h"

namespace tessera {
namespace {

Instance random_torus(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double big_r = 0.3 + 2 * unit(rng);
  const double kind = unit(rng);
  const double r = kind < 0.6    ? big_r * (0.02 + 0.9 * unit(rng))
                   : kind < 0.75 ? big_r
                                 : big_r * (1 + 2.5 * unit(rng));
  // Some axis-aligned (as scenes' tori mostly are): their sectors' world boxes then touch the
  // surface, and a box too small by a hair leaves out feelers that the torus blocks.
  Affine transform;
  if (unit(rng) < 0.4) {
    const Vec3 scale{0.3 + 2.7 * unit(rng), 0.3 + 2.7 * unit(rng), 0.3 + 2.7 * unit(rng)};
    transform = Affine::translation(random_offset(rng)) *
                *Affine::rotation(90 * std::floor(4 * unit(rng)), {0, 0, 1}) *
                Affine::scaling(scale);
  } else {
    transform = random_placement(rng);
  }
  return *make_instance(Torus{r, big_r}, transform, nullptr);
}

struct Tally {
  int feelers = 0, blocked = 0, left_out = 0, left_out_by_sectors = 0;
};

void check_random_torus(std::mt19937_64& rng, Tally& tally) {
  std::uniform_real_distribution<double> unit(0, 1);
  const Instance torus = random_torus(rng);
  const Torus& shape = std::get<Torus>(torus.geometry);
  const double e = shape.torus_radius + shape.tube_radius;
  const Vec3 centre = torus.to_world.apply_point({0, 0, 0});
  const Vec3 extent = torus.world_bounds.diagonal();
  const double size = length(extent);
  // A point of the torus's plane at radius rho and a random angle (object space).
  const auto in_plane = [&](double rho) {
    const double angle = 2 * std::numbers::pi * unit(rng);
    return Vec3{rho * std::cos(angle), rho * std::sin(angle), 0};
  };
  // The light: around the torus, in its hole, or just off its outer equator or its top.
  Vec3 light = centre + random_unit(rng) * size * (0.3 + 3 * unit(rng));
  const double where = unit(rng);
  if (where < 0.15) {
    light = torus.to_world.apply_point(
        in_plane(std::max(shape.torus_radius - shape.tube_radius, 0.0) * unit(rng)) +
        random_unit(rng) * 0.01 * e);
  } else if (where < 0.3) {
    light = torus.to_world.apply_point(in_plane(e * (1 + 0.05 * unit(rng))));
  } else if (where < 0.4) {
    Vec3 top = in_plane(shape.torus_radius);
    top.z = shape.tube_radius * (1 + 0.05 * unit(rng));
    light = torus.to_world.apply_point(top);
  }
  std::vector<Bounds3> sectors;
  light_buffer_pieces(torus, sectors);
  ASSERT_EQ(sectors.size(), std::size_t{kTorusLightBufferSectors});
  const std::vector<std::uint32_t> first{0, static_cast<std::uint32_t>(sectors.size())};
  const std::vector<Bounds3> whole{torus.world_bounds};
  const std::vector<std::uint32_t> whole_id{0};
  const LightBuffer buffer(light, whole, whole_id, {}, {sectors, first});
  const LightBuffer whole_buffer(light, whole, whole_id);
  if (buffer.empty()) return;
  IntersectionCounters counters;
  const auto check = [&](const Vec3& origin) {
    ++tally.feelers;
    const LightBuffer::Candidates answer = buffer.candidates(origin);
    std::uint32_t object = 0;
    const bool blocked =
        occluded_instance(torus, Ray{origin, light - origin, 0}, 1.0, object, counters);
    tally.blocked += blocked;
    if (answer.walk || answer.count > 0) return;
    ++tally.left_out;
    EXPECT_FALSE(blocked) << "the torus left out of a cell, yet it blocks the feeler from "
                          << origin.x << ' ' << origin.y << ' ' << origin.z << " to " << light.x
                          << ' ' << light.y << ' ' << light.z;
    const LightBuffer::Candidates by_box = whole_buffer.candidates(origin);
    tally.left_out_by_sectors += !by_box.walk && by_box.count > 0;
  };
  for (int f = 0; f < 1500 && !::testing::Test::HasFailure(); ++f) {
    const double kind = unit(rng);
    if (kind < 0.7) {
      // Just beyond a point of the surface seen from the light, the line sometimes turned a
      // little so as to graze the surface.
      Vec3 target = in_plane(shape.torus_radius) + random_unit(rng) * shape.tube_radius;
      target = torus.to_world.apply_point(target);
      WorldHit hit;
      if (!intersect_instance(torus, Ray{light, target - light, 0}, kInfinity, hit, counters))
        continue;
      Vec3 towards = hit.point - light;
      if (unit(rng) < 0.3)
        towards = towards + random_unit(rng) * (length(towards) * 1e-3 * unit(rng));
      const double beyond = std::pow(10.0, -7 + 7 * unit(rng));
      check(light + towards * (1 + beyond));
    } else {
      const Vec3 r{2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1};
      check(centre + mul(r, extent) * 2);
    }
  }
}

TEST(LightBufferSectors, LeavesOutOnlyFeelersTheTorusLetsThrough) {
  std::mt19937_64 rng(20261128);
  Tally tally;
  for (int scene = 0; scene < 300 && !::testing::Test::HasFailure(); ++scene)
    check_random_torus(rng, tally);
  // Enough of each kind for the check to mean something: blocked feelers, feelers the cells
  // leave the torus out of, and among those ones that its whole box would have listed.
  EXPECT_GT(tally.blocked, 250000) << tally.feelers << " feelers";
  EXPECT_GT(tally.left_out, 50000);
  EXPECT_GT(tally.left_out_by_sectors, 1500);
}

// At the entry cap: 42 tori turned at random, each with the light inside its whole box, which
// then fills every cell of the six faces (42 * 6 * 128^2 entries, just under kMaxEntries): 41 thin
// ring tori with the light near the centre of the hole, whose sectors reach only a band of cells
// about the ring's plane, and a spindle with the light in a dimple (on the axis, above the lemon
// and below the tube's top), inside every one of its sector boxes. Those sectors as boxes of
// their own would pass the cap; as pieces an object still fills a cell at most once, so the
// buffer is kept. Every torus that blocks a settled feeler must be among its candidates.
TEST(LightBufferSectors, KeepsItsBufferAtTheEntryCap) {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> unit(0, 1);
  const Vec3 light{0.25, -0.5, 1};
  const int count = 42;
  ASSERT_LE(std::size_t{count} * 6 * LightBuffer::kCells * LightBuffer::kCells,
            LightBuffer::kMaxEntries);
  std::vector<Instance> tori;
  std::vector<Bounds3> whole, sectors;
  std::vector<std::uint32_t> ids, first, sector_ids;
  for (int t = 0; t < count; ++t) {
    double big_r, r;
    Vec3 at;  // the light's place in object space
    if (t < 1) {
      // The lemon reaches sqrt(r^2 - R^2) < 0.97 r up the axis (r < 4 R).
      big_r = 0.5 + 0.5 * unit(rng), r = big_r * (1.2 + 0.5 * unit(rng));
      at = {0, 0, r * (0.97 + 0.02 * unit(rng))};
    } else {
      big_r = 1 + 3 * unit(rng), r = big_r * (0.08 + 0.07 * unit(rng));
      at = random_unit(rng) * (0.3 * (big_r - r) * unit(rng));
    }
    const Affine turn = *Affine::rotation(360 * unit(rng), random_unit(rng));
    // Placed so that the object-space point `at` lands on the light.
    const Affine to_world = Affine::translation(light - turn.apply_point(at)) * turn;
    tori.push_back(*make_instance(Torus{r, big_r}, to_world, nullptr));
    whole.push_back(tori.back().world_bounds);
    ids.push_back(static_cast<std::uint32_t>(t));
    first.push_back(static_cast<std::uint32_t>(sectors.size()));
    light_buffer_pieces(tori.back(), sectors);
  }
  first.push_back(static_cast<std::uint32_t>(sectors.size()));
  for (std::uint32_t t = 0; t < count; ++t) sector_ids.resize(first[t + 1], t);
  const LightBuffer buffer(light, whole, ids, {}, {sectors, first});
  ASSERT_FALSE(buffer.empty());
  ASSERT_TRUE(LightBuffer(light, sectors, sector_ids).empty());
  ASSERT_FALSE(LightBuffer(light, whole, ids).empty());

  IntersectionCounters counters;
  int settled = 0, blocked_by_rings = 0;
  for (int f = 0; f < 20000 && !::testing::Test::HasFailure(); ++f) {
    // Just beyond the first surface seen from the light in a random direction, or anywhere
    // near.
    Vec3 origin = light + random_unit(rng) * (6 * unit(rng));
    if (unit(rng) < 0.7) {
      const Ray ray{light, random_unit(rng), 0};
      double nearest = kInfinity;
      for (const Instance& torus : tori) {
        WorldHit hit;
        if (intersect_instance(torus, ray, nearest, hit, counters)) nearest = hit.t;
      }
      if (!(nearest < kInfinity)) continue;
      origin = light + ray.direction * (nearest * (1 + std::pow(10.0, -7 + 7 * unit(rng))));
    }
    const LightBuffer::Candidates answer = buffer.candidates(origin);
    if (answer.walk) continue;
    ++settled;
    bool by_ring = false;
    for (std::uint32_t t = 0; t < count; ++t) {
      std::uint32_t object = 0;
      if (!occluded_instance(tori[t], Ray{origin, light - origin, 0}, 1.0, object, counters))
        continue;
      by_ring |= t >= 1;
      const bool listed =
          (answer.count > 0 && answer.ids[0] == t) || (answer.count > 1 && answer.ids[1] == t);
      EXPECT_TRUE(listed) << "torus " << t << " blocks the feeler from " << origin.x << ' '
                          << origin.y << ' ' << origin.z << " but is not a candidate";
    }
    blocked_by_rings += by_ring;
  }
  EXPECT_GT(settled, 6000);
  EXPECT_GT(blocked_by_rings, 250);
}

// Other shapes have no pieces: they enter as their world bounds.
TEST(LightBufferSectors, OnlyStillToriAreCut) {
  const Instance sphere = *make_instance(Sphere{}, Affine::translation({1, 2, 3}), nullptr);
  std::vector<Bounds3> pieces;
  light_buffer_pieces(sphere, pieces);
  EXPECT_TRUE(pieces.empty());
}

}  // namespace
}  // namespace tessera
