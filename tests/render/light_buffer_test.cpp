// The light buffer never leaves out of a feeler's candidates an object whose bounds could block
// it: random boxes around random lights, random feelers (from boxes' faces, corners and edges,
// from inside boxes, from near the light and along cell borders), each answer checked against a
// segment-box test.
#include "common/render/light_buffer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

// Whether the closed segment from `a` to `b` meets the box grown by `grow` on every side: the
// slab test in double, grown so that rounding can only make it say yes.
bool segment_meets(const Vec3& a, const Vec3& b, const Bounds3& box, double grow) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.lo[k] - grow, hi = box.hi[k] + grow, d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double n = (lo - a[k]) / d, f = (hi - a[k]) / d;
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n - 1e-9);
    t1 = std::min(t1, f + 1e-9);
    if (t0 > t1) return false;
  }
  return true;
}

struct Tally {
  int none = 0, some = 0, walk = 0;
};

// Checks `feelers` feelers from points near the boxes of a random scene of `count` boxes.
Tally check_random_scene(std::mt19937_64& rng, int count, int feelers) {
  std::uniform_real_distribution<double> unit(0, 1), spread(-10, 10);
  std::vector<Bounds3> boxes;
  std::vector<std::uint32_t> ids;
  for (int i = 0; i < count; ++i) {
    const Vec3 c{spread(rng), spread(rng), spread(rng)};
    // Mostly small boxes, some thin and wide (floors and walls).
    Vec3 h{0.1 + unit(rng), 0.1 + unit(rng), 0.1 + unit(rng)};
    if (unit(rng) < 0.15) h[static_cast<int>(unit(rng) * 3)] *= 12;
    boxes.push_back({c - h, c + h});
    ids.push_back(static_cast<std::uint32_t>(100 + 3 * i));  // ids need not be indices
  }
  // The light sometimes inside a box or on a box's face.
  Vec3 light{spread(rng), spread(rng), spread(rng)};
  if (unit(rng) < 0.1) light = boxes[0].hi;
  const LightBuffer buffer(light, boxes, ids);
  Tally tally;
  for (int f = 0; f < feelers; ++f) {
    const Bounds3& b = boxes[static_cast<std::size_t>(unit(rng) * count)];
    Vec3 origin;
    const double kind = unit(rng);
    for (int k = 0; k < 3; ++k) origin[k] = b.lo[k] + unit(rng) * (b.hi[k] - b.lo[k]);
    if (kind < 0.5) {
      // On a face, an edge or a corner of its own box.
      const int axis = static_cast<int>(unit(rng) * 3);
      origin[axis] = unit(rng) < 0.5 ? b.lo[axis] : b.hi[axis];
      if (kind < 0.1) origin[(axis + 1) % 3] = b.hi[(axis + 1) % 3];
    } else if (kind < 0.6) {
      origin = light + (origin - light) * 1e-7;  // close to the light
    } else if (kind < 0.7) {
      // Along a cell border: a direction whose tangent is a multiple of a cell.
      constexpr double kHalfCells = LightBuffer::kCells / 2.0;
      const Vec3 d = origin - light;
      const double major = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
      for (int k = 0; k < 3; ++k)
        if (std::fabs(d[k]) != major)
          origin[k] = light[k] + std::round(d[k] / major * kHalfCells) / kHalfCells * major;
    } else if (kind < 0.75) {
      origin = Vec3{spread(rng), spread(rng), spread(rng)} * 2;  // anywhere, often far
    }
    const LightBuffer::Candidates answer = buffer.candidates(origin);
    if (answer.walk) {
      ++tally.walk;
      continue;
    }
    (answer.count == 0 ? tally.none : tally.some) += 1;
    for (int i = 0; i < count; ++i) {
      if (std::find(answer.ids, answer.ids + answer.count, ids[i]) != answer.ids + answer.count)
        continue;
      EXPECT_FALSE(segment_meets(origin, light, boxes[i], 1e-12))
          << "box " << i << " may block a feeler but is no candidate, from " << origin.x << ' '
          << origin.y << ' ' << origin.z << " to " << light.x << ' ' << light.y << ' ' << light.z;
      if (::testing::Test::HasFailure()) return tally;
    }
  }
  return tally;
}

TEST(LightBuffer, NeverLeavesOutABlocker) {
  std::mt19937_64 rng(18);
  Tally total;
  for (int scene = 0; scene < 300 && !::testing::Test::HasFailure(); ++scene) {
    const Tally t = check_random_scene(rng, 1 + scene % 40, 400);
    total.none += t.none;
    total.some += t.some;
    total.walk += t.walk;
  }
  // And it does settle feelers, both ways: the check above is not vacuous.
  EXPECT_GT(total.none, 5000);
  EXPECT_GT(total.some, 10000);
  EXPECT_GT(total.walk, 1000);
}

TEST(LightBuffer, NamesTheNearestCandidatesFirst) {
  const Vec3 light{0, 0, 0};
  const std::vector<Bounds3> boxes{{{-1, -1, 8}, {1, 1, 9}},       // far
                                   {{-1, -1, 4}, {1, 1, 5}},       // near
                                   {{-1, -1, 6}, {1, 1, 7}},       // between
                                   {{20, 20, 20}, {21, 21, 21}}};  // elsewhere
  const std::vector<std::uint32_t> ids{7, 5, 6, 9};
  const LightBuffer buffer(light, boxes, ids);
  LightBuffer::Candidates c = buffer.candidates({0, 0, 3});
  EXPECT_FALSE(c.walk);
  EXPECT_EQ(c.count, 0);
  c = buffer.candidates({0, 0, 5.5});
  ASSERT_FALSE(c.walk);
  ASSERT_EQ(c.count, 1);
  EXPECT_EQ(c.ids[0], 5u);
  c = buffer.candidates({0, 0, 7.5});
  ASSERT_FALSE(c.walk);
  ASSERT_EQ(c.count, 2);
  EXPECT_EQ(c.ids[0], 5u);
  EXPECT_EQ(c.ids[1], 6u);
  EXPECT_TRUE(buffer.candidates({0, 0, 10}).walk);  // three may block
}

TEST(LightBuffer, FeelersFromTheLightOrWithoutBoundsWalk) {
  const Vec3 light{1, 2, 3};
  const std::vector<Bounds3> boxes{{{5, 5, 5}, {6, 6, 6}}};
  const std::vector<std::uint32_t> ids{0};
  const LightBuffer buffer(light, boxes, ids);
  EXPECT_TRUE(buffer.candidates(light).walk);
  EXPECT_TRUE(buffer.candidates({std::numeric_limits<double>::quiet_NaN(), 0, 0}).walk);
  EXPECT_EQ(buffer.candidates({1, 2, 2}).count, 0);
  EXPECT_EQ(buffer.candidates({7, 7, 7}).count, 1);
  // An unbounded object may be anywhere.
  const std::vector<Bounds3> unbounded{{{-kInfinity, -kInfinity, -kInfinity}, {kInfinity, 0, 0}}};
  const LightBuffer everywhere(light, unbounded, ids);
  EXPECT_EQ(everywhere.candidates({1, 2, 2}).count, 1);
  // Ids past a cell's 16 bits: no buffer.
  const std::vector<std::uint32_t> large{LightBuffer::kMaxId + 1};
  EXPECT_TRUE(LightBuffer(light, boxes, large).empty());
}

}  // namespace
}  // namespace tessera
