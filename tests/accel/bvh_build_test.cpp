// The binned SAH builder gives, bit for bit, the tree of the builder it replaced (commit
// 66e52a1: a pass for the bounds, then one binning pass per axis, each extending Bounds3 boxes),
// which this file keeps as the reference: the same nodes, bounds bits, primitive_order and
// pairs, built with one thread or several, on random boxes, boxes full of signed zeros and
// ties, degenerate and skewed inputs and a triangle mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/accel/bvh.h"
#include "tests/accel/random_boxes.h"

namespace tessera {
namespace {

// The reference: commit 66e52a1's SAH build, condensed but with the same operations in the
// same order (the order of std::partition's and std::nth_element's moves included), with the
// leaves priced as BvhLeafTests says (ceil(n / group) tests, a step step_cost, at most max_size
// a leaf, nodes above split_above split anyway and marked leaf_preferred).
namespace reference {

constexpr int kBins = 16;

struct Primitive {
  Bounds3 bounds;
  Vec3 centroid;
  std::uint32_t index = 0;
};

struct Builder {
  std::vector<Primitive> p;
  Bvh& bvh;
  BvhLeafTests leaf_tests;

  double tests(std::size_t n) const { return std::ceil(static_cast<double>(n) / leaf_tests.group); }

  static std::uint32_t bin_of(const Primitive& q, int axis, double lo, double scale) {
    const double x = (q.centroid[axis] - lo) * scale;
    return !(x > 0) ? 0u : !(x < kBins - 1) ? kBins - 1 : static_cast<std::uint32_t>(x);
  }
  std::vector<Primitive>::iterator at(std::size_t i) {
    return p.begin() + static_cast<std::ptrdiff_t>(i);
  }

  std::uint32_t node(std::size_t begin, std::size_t end, int depth) {
    Bounds3 bounds, centroids;
    for (std::size_t i = begin; i < end; ++i) {
      bounds.extend(p[i].bounds);
      centroids.extend(p[i].centroid);
    }
    const Vec3 extent = centroids.diagonal();
    const auto leaf = [&] {
      bvh.nodes.push_back({bounds, static_cast<std::uint32_t>(bvh.primitive_order.size()),
                           static_cast<std::uint32_t>(end - begin), 0});
      for (std::size_t i = begin; i < end; ++i) bvh.primitive_order.push_back(p[i].index);
      return static_cast<std::uint32_t>(bvh.nodes.size() - 1);
    };
    if (end - begin == 1 || !(max_component(extent) > 0)) return leaf();
    int axis = max_axis(extent);
    std::size_t split = begin;
    const double area = bounds.surface_area();
    bool leaf_preferred = false;
    if (depth < 64 && area > 0) {
      double best_cost = kInfinity;
      int best_axis = -1, best_bin = 0;
      for (int a = 0; a < 3; ++a) {
        if (!(extent[a] > 0)) continue;
        const double scale = kBins / extent[a];
        std::array<Bounds3, kBins> bin_bounds;
        std::array<std::size_t, kBins> bin_counts{}, right_count{};
        for (std::size_t i = begin; i < end; ++i) {
          const std::uint32_t b = bin_of(p[i], a, centroids.lo[a], scale);
          ++bin_counts[b];
          bin_bounds[b].extend(p[i].bounds);
        }
        std::array<double, kBins> right_area{};
        Bounds3 right, left;
        std::size_t n_right = 0, n_left = 0;
        for (int b = kBins - 1; b > 0; --b) {
          right.extend(bin_bounds[b]);
          right_count[b] = n_right += bin_counts[b];
          right_area[b] = right.surface_area();
        }
        for (int b = 0; b < kBins - 1; ++b) {
          left.extend(bin_bounds[b]);
          n_left += bin_counts[b];
          if (n_left == 0 || right_count[b + 1] == 0) continue;
          const double cost =
              leaf_tests.step_cost + (tests(n_left) * left.surface_area() +
                                      tests(right_count[b + 1]) * right_area[b + 1]) /
                                         area;
          if (cost < best_cost) best_cost = cost, best_axis = a, best_bin = b;
        }
      }
      if (best_axis >= 0) {
        axis = best_axis;
        leaf_preferred = end - begin <= leaf_tests.max_size && tests(end - begin) <= best_cost;
        if (leaf_preferred && end - begin <= leaf_tests.split_above) return leaf();
        const double lo = centroids.lo[axis], scale = kBins / extent[axis];
        split =
            static_cast<std::size_t>(std::partition(at(begin), at(end),
                                                    [&](const Primitive& q) {
                                                      return bin_of(q, axis, lo, scale) <=
                                                             static_cast<std::uint32_t>(best_bin);
                                                    }) -
                                     p.begin());
      }
    }
    if (split == begin || split == end) {
      split = (begin + end) / 2;
      std::nth_element(at(begin), at(split), at(end),
                       [axis](const Primitive& a, const Primitive& b) {
                         return a.centroid[axis] < b.centroid[axis];
                       });
    }
    const auto self = static_cast<std::uint32_t>(bvh.nodes.size());
    bvh.nodes.push_back({bounds, 0, 0, static_cast<std::uint8_t>(axis), leaf_preferred});
    node(begin, split, depth + 1);
    bvh.nodes[self].first_or_second_child = node(split, end, depth + 1);
    return self;
  }
};

Bvh build_sah(const std::vector<Bounds3>& boxes, BvhLeafTests leaf_tests) {
  Bvh bvh;
  Builder builder{{}, bvh, leaf_tests};
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Bounds3& b = boxes[i];
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) continue;
    builder.p.push_back({b, b.centroid(), static_cast<std::uint32_t>(i)});
  }
  if (!builder.p.empty()) builder.node(0, builder.p.size(), 0);
  make_bvh_pairs(bvh);
  return bvh;
}

}  // namespace reference

bool same_bits(const Bounds3& a, const Bounds3& b) {
  for (int k = 0; k < 3; ++k)
    if (std::bit_cast<std::uint64_t>(a.lo[k]) != std::bit_cast<std::uint64_t>(b.lo[k]) ||
        std::bit_cast<std::uint64_t>(a.hi[k]) != std::bit_cast<std::uint64_t>(b.hi[k]))
      return false;
  return true;
}

// Counts the nodes whose bounds hold a -0 (so that the signed-zero cases are known to occur).
int nodes_with_negative_zero(const Bvh& bvh) {
  int n = 0;
  for (const BvhNode& node : bvh.nodes)
    for (int k = 0; k < 3; ++k)
      if ((node.bounds.lo[k] == 0 && std::signbit(node.bounds.lo[k])) ||
          (node.bounds.hi[k] == 0 && std::signbit(node.bounds.hi[k]))) {
        ++n;
        break;
      }
  return n;
}

void expect_same_tree(const Bvh& expected, const Bvh& actual) {
  ASSERT_EQ(actual.nodes.size(), expected.nodes.size());
  for (std::size_t n = 0; n < expected.nodes.size(); ++n) {
    SCOPED_TRACE(n);
    const BvhNode &a = actual.nodes[n], &e = expected.nodes[n];
    ASSERT_TRUE(same_bits(a.bounds, e.bounds));
    ASSERT_EQ(a.first_or_second_child, e.first_or_second_child);
    ASSERT_EQ(a.count, e.count);
    ASSERT_EQ(a.split_axis, e.split_axis);
    ASSERT_EQ(a.leaf_preferred, e.leaf_preferred);
  }
  EXPECT_EQ(actual.primitive_order, expected.primitive_order);
  ASSERT_EQ(actual.pairs.size(), expected.pairs.size());
  for (std::size_t p = 0; p < expected.pairs.size(); ++p) {
    const BvhPair &a = actual.pairs[p], &e = expected.pairs[p];
    ASSERT_EQ(std::memcmp(&a.boxes, &e.boxes, sizeof a.boxes), 0) << p;
    ASSERT_EQ(a.child[0], e.child[0]);
    ASSERT_EQ(a.child[1], e.child[1]);
    ASSERT_EQ(a.count[0], e.count[0]);
    ASSERT_EQ(a.count[1], e.count[1]);
  }
}

// The leaf pricing of mesh BVHs (mesh_accel.h).
constexpr BvhLeafTests kMeshLeafTests{.group = 4, .max_size = 16, .step_cost = 2, .split_above = 4};

// The same tree as the reference's, built with one thread and with several, with the default
// leaf pricing and with the meshes'.
void expect_same_tree(const std::vector<Bounds3>& boxes) {
  for (const BvhLeafTests leaf_tests : {BvhLeafTests{}, kMeshLeafTests}) {
    const Bvh expected = reference::build_sah(boxes, leaf_tests);
    for (const int threads : {1, 2, 3, 8}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, leaf tests of " << leaf_tests.group);
      Bvh actual = build_bvh_nodes(boxes, BvhMode::Sah, threads, leaf_tests);
      make_bvh_pairs(actual);
      expect_same_tree(expected, actual);
    }
  }
}

// The largest leaf of a tree.
std::uint32_t largest_leaf(const Bvh& bvh) {
  std::uint32_t largest = 0;
  for (const BvhNode& node : bvh.nodes) largest = std::max(largest, node.count);
  return largest;
}

TEST(BvhBuild, SameTreeAsTheReferenceOnRandomBoxes) {
  std::mt19937_64 rng(2026);
  // 20,000: large enough for subtrees on other threads.
  for (const int n : {1, 2, 3, 4, 5, 9, 17, 64, 100, 1000, 20000}) {
    for (const double size : {0.001, 0.1, 3.0}) {
      SCOPED_TRACE(testing::Message() << n << " boxes of size " << size);
      expect_same_tree(random_boxes(rng, n, 10, size));
    }
  }
}

TEST(BvhBuild, SameTreeWithSignedZerosAndTies) {
  // Coordinates from a few values, -0 and +0 among them: many bounds and centroids meet at
  // zero with either sign, and many primitives tie in bins and in the median.
  std::mt19937_64 rng(18);
  const double values[] = {-1, -0.5, -0.0, 0.0, 0.0, -0.0, 0.25, 1};
  std::uniform_int_distribution<int> pick(0, 7);
  int zero_nodes = 0;
  for (const int n : {8, 50, 300, 3000}) {
    std::vector<Bounds3> boxes;
    for (int i = 0; i < n; ++i) {
      Bounds3 b;
      b.extend(Vec3{values[pick(rng)], values[pick(rng)], values[pick(rng)]});
      b.extend(Vec3{values[pick(rng)], values[pick(rng)], values[pick(rng)]});
      boxes.push_back(b);
    }
    SCOPED_TRACE(n);
    expect_same_tree(boxes);
    zero_nodes += nodes_with_negative_zero(build_bvh(boxes, BvhMode::Sah));
  }
  EXPECT_GT(zero_nodes, 0);
}

TEST(BvhBuild, SameTreeOnDegenerateSkewedAndUnusableInputs) {
  std::vector<std::vector<Bounds3>> cases(6);
  for (int i = 0; i < 100; ++i) {
    const double s = 0.01 * (i + 1);
    cases[0].push_back({{-s, -s, -s}, {s, s, s}});                              // nested
    cases[1].push_back({{0, 0, 0}, {1, 1, 1}});                                 // equal
    cases[2].push_back({{0.1 * i, 0, 0}, {0.1 * i + 0.05, 0, 0}});              // on a line
    cases[3].push_back({{0.5, 0.1 * i, 0.5}, {0.5, 0.1 * i, 0.5}});             // points
    cases[4].push_back({{0.1 * i, 0.2 * i, -0.0}, {0.1 * i + 1, 0.2 * i, 0}});  // flat, -0
  }
  // Geometrically spaced: median splits below depth 64.
  for (int i = 0; i < 1000; ++i) {
    const double x = std::ldexp(1.0, -i);
    cases[5].push_back({{x, 0, 0}, {x * 1.0001, 1, 1}});
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  cases[0].push_back(Bounds3{});
  cases[5].push_back({{0, 0, 0}, {kInfinity, 1, 1}});
  cases[5].push_back({{kNaN, 0, 0}, {1, 1, 1}});
  for (std::size_t c = 0; c < cases.size(); ++c) {
    SCOPED_TRACE(c);
    expect_same_tree(cases[c]);
  }
}

TEST(BvhBuild, SameTreeOnATriangleMesh) {
  // The triangles of a surface of revolution about y, as the teapot is made, with the seam
  // and the poles on coordinate planes (exact zeros of both signs).
  std::vector<Bounds3> boxes;
  constexpr int kRings = 60, kSegments = 90;
  const double pi = std::acos(-1.0);
  auto point = [&](int ring, int segment) {
    const double theta = pi * ring / kRings, phi = 2 * pi * segment / kSegments;
    const double r = std::sin(theta) * (1.3 + 0.2 * std::cos(5 * theta));
    const double x = segment % (kSegments / 2) == 0 ? -0.0 * r : r * std::sin(phi);
    return Vec3{x, std::cos(theta), r * std::cos(phi)};
  };
  for (int ring = 0; ring < kRings; ++ring)
    for (int segment = 0; segment < kSegments; ++segment)
      for (int half = 0; half < 2; ++half) {
        Bounds3 b;
        b.extend(point(ring, segment));
        b.extend(point(ring + 1, segment + half));
        b.extend(point(ring + half, segment + 1));
        boxes.push_back(b);
      }
  expect_same_tree(boxes);
  EXPECT_GT(nodes_with_negative_zero(build_bvh(boxes, BvhMode::Sah)), 0);
  // Priced as tests of four, nodes are split down to four triangles all the same, some of them
  // marked as the larger leaves the SAH prefers.
  EXPECT_EQ(largest_leaf(build_bvh(boxes, BvhMode::Sah)), 4u);
  const Bvh mesh_tree = build_bvh_nodes(boxes, BvhMode::Sah, 1, kMeshLeafTests);
  EXPECT_LE(largest_leaf(mesh_tree), 4u);
  EXPECT_TRUE(std::any_of(mesh_tree.nodes.begin(), mesh_tree.nodes.end(),
                          [](const BvhNode& node) { return node.leaf_preferred; }));
}

}  // namespace
}  // namespace tessera
