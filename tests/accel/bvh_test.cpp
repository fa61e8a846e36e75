#include "common/accel/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "common/accel/bvh_traverse.h"
#include "tests/accel/random_boxes.h"

namespace tessera {
namespace {

// The entry distance of a ray into a box (>= 0), or infinity when it misses within t_max.
double box_hit(const Bounds3& b, const Ray& ray, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (ray.direction[a] == 0) {
      if (ray.origin[a] < b.lo[a] || ray.origin[a] > b.hi[a]) return kInfinity;
      continue;
    }
    double tn = (b.lo[a] - ray.origin[a]) / ray.direction[a];
    double tf = (b.hi[a] - ray.origin[a]) / ray.direction[a];
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  return t0 <= t1 && t0 < t_max ? t0 : kInfinity;
}

Ray random_ray(std::mt19937_64& rng, double world) {
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 o{world * (2 * u(rng) - 0.5), world * (2 * u(rng) - 0.5), world * (2 * u(rng) - 0.5)};
  const Vec3 target{world * u(rng), world * u(rng), world * u(rng)};
  return {o, (target - o) * (0.1 + u(rng))};
}

struct Closest {
  double t = kInfinity;
  std::uint32_t index = 0;
  std::uint64_t nodes = 0;
  std::uint64_t tests = 0;
};

Closest closest_by_bvh(const Bvh& bvh, const std::vector<Bounds3>& boxes, const Ray& ray) {
  Closest c;
  traverse_bvh(bvh, ray, kInfinity, c.nodes, [&](std::uint32_t i, double t_max) {
    ++c.tests;
    const double t = box_hit(boxes[i], ray, t_max);
    if (t < t_max) c.t = t, c.index = i;
    return std::min(t, t_max);
  });
  return c;
}

Closest closest_by_brute_force(const std::vector<Bounds3>& boxes, const Ray& ray) {
  Closest c;
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    const double t = box_hit(boxes[i], ray, c.t);
    if (t < c.t) c.t = t, c.index = i;
  }
  return c;
}

// Structural invariants: every primitive with usable bounds appears exactly once, children lie
// inside their parents, leaves are small, the depth stays below the traversal stack. Returns
// the depth.
int check_structure(const Bvh& bvh, std::size_t primitives, std::size_t max_leaf) {
  if (primitives == 0) {
    EXPECT_TRUE(bvh.nodes.empty());
    return 0;
  }
  EXPECT_FALSE(bvh.nodes.empty());
  if (bvh.nodes.empty()) return 0;
  std::vector<int> seen(primitives, 0);
  struct Item {
    std::uint32_t node;
    int depth;
  };
  std::vector<Item> stack{{0, 1}};
  int max_depth = 0;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    max_depth = std::max(max_depth, item.depth);
    EXPECT_LT(item.node, bvh.nodes.size());
    if (item.node >= bvh.nodes.size()) return max_depth;
    const BvhNode& n = bvh.nodes[item.node];
    if (n.count > 0) {
      EXPECT_LE(n.count, max_leaf);
      for (std::uint32_t i = n.first_or_second_child; i < n.first_or_second_child + n.count; ++i)
        ++seen.at(bvh.primitive_order.at(i));
      continue;
    }
    const std::uint32_t children[2] = {item.node + 1, n.first_or_second_child};
    for (const std::uint32_t c : children) {
      EXPECT_LT(c, bvh.nodes.size());
      if (c >= bvh.nodes.size()) return max_depth;
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(bvh.nodes[c].bounds.lo[a], n.bounds.lo[a]);
        EXPECT_LE(bvh.nodes[c].bounds.hi[a], n.bounds.hi[a]);
      }
      stack.push_back({c, item.depth + 1});
    }
  }
  EXPECT_LT(max_depth, kBvhMaxDepth);
  for (std::size_t i = 0; i < primitives; ++i) EXPECT_EQ(seen[i], 1) << i;
  return max_depth;
}

TEST(Bvh, SahAndNoneMatchBruteForceOnRandomBoxes) {
  for (std::uint64_t seed : {1u, 2u}) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    std::mt19937_64 rng(seed);
    const std::vector<Bounds3> boxes = random_boxes(rng, 1000, 100, 2.5);
    const Bvh sah = build_bvh(boxes, BvhMode::Sah);
    const Bvh none = build_bvh(boxes, BvhMode::None);
    check_structure(sah, boxes.size(), 4);
    ASSERT_EQ(none.nodes.size(), 1u);
    EXPECT_EQ(none.nodes[0].count, boxes.size());
    for (std::uint32_t i = 0; i < boxes.size(); ++i) EXPECT_EQ(none.primitive_order[i], i);
    int hits = 0;
    for (int r = 0; r < 1000; ++r) {
      const Ray ray = random_ray(rng, 100);
      const Closest expected = closest_by_brute_force(boxes, ray);
      const Closest a = closest_by_bvh(sah, boxes, ray);
      const Closest b = closest_by_bvh(none, boxes, ray);
      ASSERT_EQ(a.t, expected.t) << r;
      ASSERT_EQ(b.t, expected.t) << r;
      if (expected.t < kInfinity) {
        ++hits;
        EXPECT_EQ(boxes[a.index].lo, boxes[expected.index].lo);
      }
    }
    EXPECT_GT(hits, 250);
  }
}

TEST(Bvh, SahDoesFarLessWorkThanNone) {
  std::mt19937_64 rng(42);
  const std::vector<Bounds3> boxes = random_boxes(rng, 10000, 100, 0.5);
  const Bvh sah = build_bvh(boxes, BvhMode::Sah);
  const Bvh none = build_bvh(boxes, BvhMode::None);
  std::uint64_t sah_nodes = 0, sah_tests = 0, none_nodes = 0, none_tests = 0;
  constexpr int kRays = 200;
  for (int r = 0; r < kRays; ++r) {
    const Ray ray = random_ray(rng, 100);
    const Closest a = closest_by_bvh(sah, boxes, ray);
    const Closest b = closest_by_bvh(none, boxes, ray);
    ASSERT_EQ(a.t, b.t);
    sah_nodes += a.nodes, sah_tests += a.tests;
    none_nodes += b.nodes, none_tests += b.tests;
  }
  // "Off" visits one node per ray and tests every primitive behind it.
  EXPECT_EQ(none_nodes, kRays);
  EXPECT_EQ(none_tests, kRays * boxes.size());
  // The tree's total work (node boxes plus primitive tests) is a small fraction of that.
  EXPECT_LT((sah_nodes + sah_tests) * 50, none_nodes + none_tests)
      << "sah nodes " << sah_nodes << " tests " << sah_tests;
}

TEST(Bvh, EmptyAndSinglePrimitive) {
  for (BvhMode mode : {BvhMode::Sah, BvhMode::None}) {
    const Bvh empty = build_bvh({}, mode);
    EXPECT_TRUE(empty.nodes.empty());
    std::uint64_t nodes = 0;
    int visits = 0;
    traverse_bvh(empty, {{0, 0, 0}, {1, 0, 0}}, kInfinity, nodes, [&](std::uint32_t, double t) {
      ++visits;
      return t;
    });
    EXPECT_EQ(nodes, 0u);
    EXPECT_EQ(visits, 0);

    const std::vector<Bounds3> one{{{1, -1, -1}, {2, 1, 1}}};
    const Bvh single = build_bvh(one, mode);
    ASSERT_EQ(single.nodes.size(), 1u);
    EXPECT_EQ(single.nodes[0].count, 1u);
    EXPECT_EQ(closest_by_bvh(single, one, {{0, 0, 0}, {1, 0, 0}}).t, 1);
    EXPECT_EQ(closest_by_bvh(single, one, {{0, 0, 0}, {-1, 0, 0}}).t, kInfinity);
  }
}

TEST(Bvh, DegenerateInputs) {
  std::mt19937_64 rng(9);
  // All centroids equal (nested boxes), all boxes equal, flat boxes on a line, points.
  std::vector<std::vector<Bounds3>> cases(4);
  for (int i = 0; i < 100; ++i) {
    const double s = 0.01 * (i + 1);
    cases[0].push_back({{-s, -s, -s}, {s, s, s}});
    cases[1].push_back({{0, 0, 0}, {1, 1, 1}});
    cases[2].push_back({{0.1 * i, 0, 0}, {0.1 * i + 0.05, 0, 0}});
    cases[3].push_back({{0.5, 0.1 * i, 0.5}, {0.5, 0.1 * i, 0.5}});
  }
  for (std::size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(c);
    const std::vector<Bounds3>& boxes = cases[c];
    const Bvh sah = build_bvh(boxes, BvhMode::Sah);
    check_structure(sah, boxes.size(), c < 2 ? boxes.size() : 4);
    for (int r = 0; r < 300; ++r) {
      const Ray ray = random_ray(rng, 1);
      EXPECT_EQ(closest_by_bvh(sah, boxes, ray).t, closest_by_brute_force(boxes, ray).t);
    }
    // Rays exactly along the line of the flat boxes (zero direction components).
    const Ray along{{-1, 0, 0}, {1, 0, 0}};
    EXPECT_EQ(closest_by_bvh(sah, boxes, along).t, closest_by_brute_force(boxes, along).t);
  }
}

TEST(Bvh, DepthStaysBoundedForSkewedInputs) {
  // Geometrically spaced boxes: the SAH peels off a few primitives per level, which would make
  // the tree about as deep as the input is long without the build's switch to median splits.
  std::vector<Bounds3> boxes;
  for (int i = 0; i < 1000; ++i) {
    const double x = std::ldexp(1.0, -i);
    boxes.push_back({{x, 0, 0}, {x * 1.0001, 1, 1}});
  }
  const Bvh sah = build_bvh(boxes, BvhMode::Sah);
  const int depth = check_structure(sah, boxes.size(), 4);
  EXPECT_GT(depth, 64);  // the median splits below depth 64 were needed
  EXPECT_LE(depth, 64 + 16);
  std::mt19937_64 rng(3);
  for (int r = 0; r < 200; ++r) {
    const Ray ray = random_ray(rng, 1);
    EXPECT_EQ(closest_by_bvh(sah, boxes, ray).t, closest_by_brute_force(boxes, ray).t);
  }
}

TEST(Bvh, EmptyBoundsAreSkippedByTheTree) {
  std::vector<Bounds3> boxes{{{0, 0, 0}, {1, 1, 1}}, Bounds3{}, {{2, 0, 0}, {3, 1, 1}}};
  const Bvh sah = build_bvh(boxes, BvhMode::Sah);
  std::vector<std::uint32_t> order = sah.primitive_order;
  std::sort(order.begin(), order.end());
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0, 2}));
  const Bvh none = build_bvh(boxes, BvhMode::None);
  EXPECT_EQ(none.primitive_order.size(), 3u);
}

TEST(Bvh, NearChildFirstAndEarlyStop) {
  // Boxes along x: a ray in +x meets them in index order, a ray in -x in reverse order.
  std::vector<Bounds3> boxes;
  for (int i = 0; i < 64; ++i) boxes.push_back({{2.0 * i, 0, 0}, {2.0 * i + 1, 1, 1}});
  const Bvh sah = build_bvh(boxes, BvhMode::Sah);
  for (const double sign : {1.0, -1.0}) {
    const Ray ray{{sign > 0 ? -10.0 : 200.0, 0.5, 0.5}, {sign, 0, 0}};
    std::vector<std::uint32_t> visited;
    std::uint64_t nodes = 0;
    traverse_bvh(sah, ray, kInfinity, nodes, [&](std::uint32_t i, double t_max) {
      visited.push_back(i);
      return t_max;  // keep going: every box is visited
    });
    ASSERT_EQ(visited.size(), boxes.size());
    for (std::size_t k = 1; k < visited.size(); ++k) {
      if (sign > 0) {
        EXPECT_LT(visited[k - 1], visited[k]);
      } else {
        EXPECT_GT(visited[k - 1], visited[k]);
      }
    }
    // Any-hit: a negative return stops at once.
    int calls = 0;
    traverse_bvh(sah, ray, kInfinity, nodes, [&](std::uint32_t, double) {
      ++calls;
      return -1.0;
    });
    EXPECT_EQ(calls, 1);
  }
}

}  // namespace
}  // namespace tessera
