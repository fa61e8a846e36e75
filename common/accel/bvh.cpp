// Binned SAH BVH construction (pbrt-v3 §4.3.2, 16 bins, evaluated on all three axes), and the
// flat single-leaf "acceleration off". A node with at most 4 primitives becomes a leaf when no
// split is cheaper; larger nodes are always split, except when all centroids coincide (no
// split separates anything). Primitives whose bounds are empty or not finite cannot be hit and
// are left out of the SAH tree; BvhMode::None keeps every primitive, in input order.
#include "common/accel/bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 4;
// Cost of a traversal step relative to one primitive test.
constexpr double kTraversalCost = 0.5;
// Below this depth the SAH decides; deeper, object-median splits halve the primitive count,
// which bounds the depth by kSahDepth + 32 < kBvhMaxDepth for any input.
constexpr int kSahDepth = 64;

struct BuildPrimitive {
  Bounds3 bounds;
  Vec3 centroid;
  std::uint32_t index = 0;
};

bool usable(const Bounds3& b) { return !b.empty() && is_finite(b.lo) && is_finite(b.hi); }

class Builder {
 public:
  Builder(std::vector<BuildPrimitive> primitives, Bvh& bvh)
      : primitives_(std::move(primitives)), bvh_(bvh) {}

  void build() {
    if (primitives_.empty()) return;
    bvh_.nodes.reserve(2 * primitives_.size());
    bvh_.primitive_order.reserve(primitives_.size());
    build_node(0, primitives_.size(), 0);
  }

 private:
  std::uint32_t bin_of(const BuildPrimitive& p, int axis, double lo, double scale) const {
    const double x = (p.centroid[axis] - lo) * scale;
    if (!(x > 0)) return 0;
    if (!(x < kBins - 1)) return kBins - 1;  // also an infinite scale from a subnormal extent
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

  // Splits [begin, end) at the median centroid on `axis`; returns the split position.
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

  // Chooses a split of [begin, end) by the binned SAH over all three axes. Returns the split
  // position, or `begin` when a leaf is cheaper (and allowed).
  std::size_t sah_split(std::size_t begin, std::size_t end, const Bounds3& bounds,
                        const Bounds3& centroids, int& axis) {
    const std::size_t count = end - begin;
    const double area = bounds.surface_area();
    const Vec3 extent = centroids.diagonal();
    if (!(area > 0)) {
      // Flat or line-like primitives whose boxes have no area: split by count.
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
      // Sweep from the right to get the area and count of every right-hand side.
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
      for (int b = 0; b < kBins - 1; ++b) {  // split between bin b and bin b + 1
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
    if (best_axis < 0) {  // cannot happen with a non-degenerate centroid box; be safe
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
    // All centroids equal: no split separates anything (pbrt makes a leaf too).
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
    build_node(begin, split, depth + 1);  // the first child is the next node
    const std::uint32_t second = build_node(split, end, depth + 1);
    bvh_.nodes[self].first_or_second_child = second;
    return self;
  }

  std::vector<BuildPrimitive> primitives_;
  Bvh& bvh_;
};

}  // namespace

Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode) {
  Bvh bvh;
  if (primitive_bounds.empty()) return bvh;
  if (mode == BvhMode::None) {
    BvhNode leaf;
    for (const Bounds3& b : primitive_bounds) leaf.bounds.extend(b);
    leaf.count = static_cast<std::uint32_t>(primitive_bounds.size());
    bvh.nodes.push_back(leaf);
    bvh.primitive_order.resize(primitive_bounds.size());
    for (std::size_t i = 0; i < primitive_bounds.size(); ++i)
      bvh.primitive_order[i] = static_cast<std::uint32_t>(i);
    return bvh;
  }
  // Primitives with empty or non-finite bounds can never be hit and are left out of the tree.
  std::vector<BuildPrimitive> primitives;
  primitives.reserve(primitive_bounds.size());
  for (std::size_t i = 0; i < primitive_bounds.size(); ++i) {
    const Bounds3& b = primitive_bounds[i];
    if (!usable(b)) continue;
    primitives.push_back({b, b.centroid(), static_cast<std::uint32_t>(i)});
  }
  Builder(std::move(primitives), bvh).build();
  make_bvh_pairs(bvh);
  return bvh;
}

void make_bvh_pairs(Bvh& bvh) {
  bvh.pairs.clear();
  std::vector<std::uint32_t> pair_of(bvh.nodes.size());
  std::uint32_t interior = 0;
  for (std::size_t n = 0; n < bvh.nodes.size(); ++n)
    if (bvh.nodes[n].count == 0) pair_of[n] = interior++;
  bvh.pairs.reserve(interior);
  for (std::size_t n = 0; n < bvh.nodes.size(); ++n) {
    if (bvh.nodes[n].count > 0) continue;
    const std::size_t children[2] = {n + 1, bvh.nodes[n].first_or_second_child};
    BvhPair pair;
    pair.boxes = make_child_boxes(bvh.nodes[children[0]].bounds, bvh.nodes[children[1]].bounds);
    for (int c = 0; c < 2; ++c) {
      const BvhNode& child = bvh.nodes[children[c]];
      pair.child[c] = child.count > 0 ? child.first_or_second_child : pair_of[children[c]];
      pair.count[c] = child.count;
    }
    bvh.pairs.push_back(pair);
  }
}

}  // namespace tessera
