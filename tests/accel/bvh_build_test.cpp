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

namespace tessera {
namespace {

// The reference: commit 66e52a1's common/accel/bvh.cpp, cut to the SAH build.
namespace reference {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 4;
constexpr double kTraversalCost = 0.5;
constexpr int kSahDepth = 64;

struct BuildPrimitive {
  Bounds3 bounds;
  Vec3 centroid;
  std::uint32_t index = 0;
};

class Builder {
 public:
  Builder(std::vector<BuildPrimitive> primitives, Bvh& bvh)
      : primitives_(std::move(primitives)), bvh_(bvh) {}

  void build() {
    if (!primitives_.empty()) build_node(0, primitives_.size(), 0);
  }

 private:
  std::uint32_t bin_of(const BuildPrimitive& p, int axis, double lo, double scale) const {
    const double x = (p.centroid[axis] - lo) * scale;
    if (!(x > 0)) return 0;
    if (!(x < kBins - 1)) return kBins - 1;
    return static_cast<std::uint32_t>(x);
  }

  std::uint32_t make_leaf(std::size_t begin, std::size_t end, const Bounds3& bounds) {
    BvhNode node;
    node.bounds = bounds;
    node.first_or_second_child = static_cast<std::uint32_t>(bvh_.primitive_order.size());
    node.count = static_cast<std::uint32_t>(end - begin);
    for (std::size_t i = begin; i < end; ++i) bvh_.primitive_order.push_back(primitives_[i].index);
    bvh_.nodes.push_back(node);
    return static_cast<std::uint32_t>(bvh_.nodes.size() - 1);
  }

  std::size_t median_split(std::size_t begin, std::size_t end, int axis) {
    const std::size_t mid = (begin + end) / 2;
    std::nth_element(primitives_.begin() + static_cast<std::ptrdiff_t>(begin),
                     primitives_.begin() + static_cast<std::ptrdiff_t>(mid),
                     primitives_.begin() + static_cast<std::ptrdiff_t>(end),
                     [axis](const BuildPrimitive& a, const BuildPrimitive& b) {
                       return a.centroid[axis] < b.centroid[axis];
                     });
    return mid;
  }

  std::size_t sah_split(std::size_t begin, std::size_t end, const Bounds3& bounds,
                        const Bounds3& centroids, int& axis) {
    const std::size_t count = end - begin;
    const double area = bounds.surface_area();
    const Vec3 extent = centroids.diagonal();
    if (!(area > 0)) {
      axis = max_axis(extent);
      return median_split(begin, end, axis);
    }
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0)) continue;
      const double scale = kBins / extent[a];
      std::array<Bounds3, kBins> bin_bounds;
      std::array<std::size_t, kBins> bin_counts{};
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t b = bin_of(primitives_[i], a, centroids.lo[a], scale);
        ++bin_counts[b];
        bin_bounds[b].extend(primitives_[i].bounds);
      }
      std::array<double, kBins> right_area{};
      std::array<std::size_t, kBins> right_count{};
      Bounds3 right;
      std::size_t n_right = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.extend(bin_bounds[b]);
        n_right += bin_counts[b];
        right_area[b] = right.surface_area();
        right_count[b] = n_right;
      }
      Bounds3 left;
      std::size_t n_left = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        left.extend(bin_bounds[b]);
        n_left += bin_counts[b];
        if (n_left == 0 || right_count[b + 1] == 0) continue;
        const double cost =
            kTraversalCost + (static_cast<double>(n_left) * left.surface_area() +
                              static_cast<double>(right_count[b + 1]) * right_area[b + 1]) /
                                 area;
        if (cost < best_cost) best_cost = cost, best_axis = a, best_bin = b;
      }
    }
    if (best_axis < 0) {
      axis = max_axis(extent);
      return median_split(begin, end, axis);
    }
    axis = best_axis;
    if (count <= kMaxLeafSize && static_cast<double>(count) <= best_cost) return begin;
    const double lo = centroids.lo[axis];
    const double scale = kBins / extent[axis];
    const auto middle = std::partition(
        primitives_.begin() + static_cast<std::ptrdiff_t>(begin),
        primitives_.begin() + static_cast<std::ptrdiff_t>(end), [&](const BuildPrimitive& p) {
          return bin_of(p, axis, lo, scale) <= static_cast<std::uint32_t>(best_bin);
        });
    const auto split = static_cast<std::size_t>(middle - primitives_.begin());
    if (split == begin || split == end) return median_split(begin, end, axis);
    return split;
  }

  std::uint32_t build_node(std::size_t begin, std::size_t end, int depth) {
    Bounds3 bounds, centroids;
    for (std::size_t i = begin; i < end; ++i) {
      bounds.extend(primitives_[i].bounds);
      centroids.extend(primitives_[i].centroid);
    }
    const std::size_t count = end - begin;
    if (count == 1 || !(max_component(centroids.diagonal()) > 0))
      return make_leaf(begin, end, bounds);
    int axis = 0;
    std::size_t split = 0;
    if (depth < kSahDepth) {
      split = sah_split(begin, end, bounds, centroids, axis);
      if (split == begin) return make_leaf(begin, end, bounds);
    } else {
      axis = max_axis(centroids.diagonal());
      split = median_split(begin, end, axis);
    }
    const auto self = static_cast<std::uint32_t>(bvh_.nodes.size());
    BvhNode node;
    node.bounds = bounds;
    node.split_axis = static_cast<std::uint8_t>(axis);
    bvh_.nodes.push_back(node);
    build_node(begin, split, depth + 1);
    const std::uint32_t second = build_node(split, end, depth + 1);
    bvh_.nodes[self].first_or_second_child = second;
    return self;
  }

  std::vector<BuildPrimitive> primitives_;
  Bvh& bvh_;
};

Bvh build_sah(const std::vector<Bounds3>& boxes) {
  Bvh bvh;
  std::vector<BuildPrimitive> primitives;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Bounds3& b = boxes[i];
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi)) continue;
    primitives.push_back({b, b.centroid(), static_cast<std::uint32_t>(i)});
  }
  Builder(std::move(primitives), bvh).build();
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

// The same tree as the reference's, built with one thread and with several.
void expect_same_tree(const std::vector<Bounds3>& boxes) {
  const Bvh expected = reference::build_sah(boxes);
  for (const int threads : {1, 2, 3, 8}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    expect_same_tree(expected, build_bvh(boxes, BvhMode::Sah, threads));
  }
}

std::vector<Bounds3> random_boxes(std::mt19937_64& rng, int n, double world, double size) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Bounds3> boxes;
  for (int i = 0; i < n; ++i) {
    const Vec3 c{world * u(rng), world * u(rng), world * u(rng)};
    const Vec3 h{size * u(rng), size * u(rng), size * u(rng)};
    boxes.push_back({c - h, c + h});
  }
  return boxes;
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
}

}  // namespace
}  // namespace tessera
