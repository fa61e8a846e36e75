// Binned SAH BVH construction (pbrt-v3 §4.3.2, 16 bins, evaluated on all three axes), and the
// flat single-leaf "acceleration off". A node with at most BvhLeafTests::max_size primitives
// becomes a leaf when no split is cheaper (or, holding more than split_above, is split all the
// same and marked leaf_preferred); larger nodes are always split, except when all centroids
// coincide (no split separates anything). Primitives whose bounds are empty or not finite cannot be
// hit and are left out of the SAH tree; BvhMode::None keeps every primitive, in input order.
//
// One pass over a node's primitives bins them on all three axes at once, keeping per bin the
// bounds and the centroid bounds, so that each child's bounds are the union of its side's bins
// rather than another pass. Min and max are exact, so the union has the bits a pass over the
// child would give; the one exception is zero, where -0 and +0 compare equal and the sign of
// the result depends on the order of the operands, so a child whose bounds hold a zero gets
// the pass after all. The tree is thereby the same, bit for bit, as that of the builder that
// made one pass for the bounds and one per axis for the bins (tests/accel/bvh_build_test.cpp
// keeps that builder as its reference).
#include "common/accel/bvh.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <exception>
#include <limits>
#include <thread>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

namespace {

constexpr int kBins = 16;
// Below this depth the SAH decides; deeper, object-median splits halve the primitive count,
// which bounds the depth by kSahDepth + 32 < kBvhMaxDepth for any input.
constexpr int kSahDepth = 64;

// A box as six values that all shrink as it grows: lo, and hi negated (negation is exact), so
// that three SSE2 minpd extend it.
struct alignas(16) MinBox {
  std::array<double, 6> v{kInfinity, kInfinity, kInfinity, kInfinity, kInfinity, kInfinity};

  static MinBox of(const Bounds3& b) {
    return {{b.lo.x, b.lo.y, b.lo.z, -b.hi.x, -b.hi.y, -b.hi.z}};
  }
  static MinBox of(const Vec3& p) { return {{p.x, p.y, p.z, -p.x, -p.y, -p.z}}; }

  // `b < v ? b : v` keeps the current value on ties, as Bounds3::extend's std::min and
  // std::max do, so that a pass gives the bits Bounds3::extend would; minpd(b, v) computes
  // exactly that.
  void extend(const MinBox& b) {
#if defined(__SSE2__)
    _mm_store_pd(&v[0], _mm_min_pd(_mm_load_pd(&b.v[0]), _mm_load_pd(&v[0])));
    _mm_store_pd(&v[2], _mm_min_pd(_mm_load_pd(&b.v[2]), _mm_load_pd(&v[2])));
    _mm_store_pd(&v[4], _mm_min_pd(_mm_load_pd(&b.v[4]), _mm_load_pd(&v[4])));
#else
    for (std::size_t i = 0; i < 6; ++i) v[i] = b.v[i] < v[i] ? b.v[i] : v[i];
#endif
  }
  Bounds3 bounds() const { return {{v[0], v[1], v[2]}, {-v[3], -v[4], -v[5]}}; }
  bool has_zero() const {
    return std::any_of(v.begin(), v.end(), [](double x) { return x == 0; });
  }
};

struct BuildPrimitive {
  MinBox box;
  Vec3 centroid;
  std::uint32_t index = 0;
};

// A node's bounds and the bounds of its primitives' centroids.
struct NodeBoxes {
  MinBox bounds, centroids;
};

struct Bin {
  MinBox bounds;
  std::uint32_t count = 0;
};

bool usable(const Bounds3& b) { return !b.empty() && is_finite(b.lo) && is_finite(b.hi); }

// The bin of a centroid coordinate: the first bin for x <= 0 and NaN, the last for x >= the
// last bin and infinity (from a subnormal extent).
std::uint32_t bin_of(double centroid, double lo, double scale) {
  const double x = (centroid - lo) * scale;
#if defined(__SSE2__)
  // maxsd and minsd give the same without the branches the compiler makes of the comparisons.
  const __m128d above_zero = _mm_max_sd(_mm_set_sd(x), _mm_setzero_pd());
  return static_cast<std::uint32_t>(_mm_cvttsd_si32(_mm_min_sd(above_zero, _mm_set_sd(kBins - 1))));
#else
  const double above_zero = x > 0 ? x : 0;
  return static_cast<std::uint32_t>(above_zero < kBins - 1 ? above_zero : kBins - 1);
#endif
}

// Builds the subtree of one range of the shared primitives into its own nodes and
// primitive_order, which start at 0. While a thread is spare, it hands the second child of a
// large node to a Builder of its own on that thread and appends that subtree after the first
// child's, with its indices moved: the depth-first layout, and so the tree, is that of one
// thread, whatever the thread count. A thread is spare again as soon as its subtree is built,
// so that it may take a subtree of a larger side that is still being built.
class Builder {
 public:
  Builder(std::vector<BuildPrimitive>& primitives, Bvh& bvh, std::atomic<int>& spare_threads,
          BvhLeafTests leaf_tests)
      : primitives_(primitives),
        bvh_(bvh),
        spare_threads_(spare_threads),
        leaf_tests_(leaf_tests) {}

  void build(std::size_t begin, std::size_t end, int depth, const NodeBoxes& boxes) {
    bvh_.nodes.reserve(2 * (end - begin));
    bvh_.primitive_order.reserve(end - begin);
    build_node(begin, end, depth, boxes);
  }

  void build() {
    if (!primitives_.empty()) build(0, primitives_.size(), 0, gather(0, primitives_.size()));
  }

 private:
  // Below this many primitives a subtree is not worth a thread (about a millisecond of work).
  static constexpr std::size_t kMinParallelPrimitives = 4096;

  // The boxes of [begin, end) by a pass, in order (Bounds3::extend's bits, zeros included).
  NodeBoxes gather(std::size_t begin, std::size_t end) const {
    NodeBoxes boxes;
    for (std::size_t i = begin; i < end; ++i) {
      boxes.bounds.extend(primitives_[i].box);
      boxes.centroids.extend(MinBox::of(primitives_[i].centroid));
    }
    return boxes;
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

  // Fills bins_ and occupied_ for every axis in one pass over [begin, end); the bins must be
  // empty (clear_bins).
  void bin(std::size_t begin, std::size_t end, const Vec3& lo, const Vec3& scale) {
    const auto add = [this](int axis, std::uint32_t b, const BuildPrimitive& p) {
      Bin& bin = bins_[static_cast<std::size_t>(axis)][b];
      ++bin.count;
      bin.bounds.extend(p.box);
      occupied_[static_cast<std::size_t>(axis)] |= 1u << b;
    };
    for (const BuildPrimitive* p = primitives_.data() + begin; p != primitives_.data() + end; ++p) {
      add(0, bin_of(p->centroid.x, lo.x, scale.x), *p);
      add(1, bin_of(p->centroid.y, lo.y, scale.y), *p);
      add(2, bin_of(p->centroid.z, lo.z, scale.z), *p);
    }
  }

  // Empties the occupied bins (cheaper than all 48 for the many small nodes).
  void clear_bins() {
    for (std::size_t a = 0; a < 3; ++a) {
      for (unsigned rest = occupied_[a]; rest != 0; rest &= rest - 1)
        bins_[a][static_cast<std::size_t>(std::countr_zero(rest))] = Bin{};
      occupied_[a] = 0;
    }
  }

  // The cheapest split of the binned node by the SAH; axis -1 when no bin boundary separates
  // primitives.
  struct SahChoice {
    double cost = std::numeric_limits<double>::infinity();
    int axis = -1, bin = 0;
  };
  // The primitive tests a leaf of `count` costs: ceil(count / group).
  double tests(std::uint32_t count) const {
    return static_cast<double>((count + leaf_tests_.group - 1) / leaf_tests_.group);
  }

  SahChoice cheapest_split(double area, const Vec3& extent) const {
    SahChoice best;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0)) continue;
      const auto& bins = bins_[static_cast<std::size_t>(a)];
      const unsigned occupied = occupied_[static_cast<std::size_t>(a)];
      // Only splits after an occupied bin are costed: after an empty one the sides, so the
      // cost, are those of the split before it, and an equal cost never replaces the best.
      // The right side of the split after bin b starts at the next occupied bin. Sweep from
      // the right for the area and count of every right side (all but the lowest bin's).
      std::array<double, kBins> right_area;
      std::array<std::uint32_t, kBins> right_count;
      MinBox right;
      std::uint32_t n_right = 0;
      for (unsigned rest = occupied; (rest & (rest - 1)) != 0;) {
        const auto b = static_cast<std::size_t>(std::bit_width(rest) - 1);
        rest ^= 1u << b;
        right.extend(bins[b].bounds);
        n_right += bins[b].count;
        right_area[b] = right.bounds().surface_area();
        right_count[b] = n_right;
      }
      MinBox left;
      std::uint32_t n_left = 0;
      for (unsigned rest = occupied; (rest & (rest - 1)) != 0;) {  // all but the highest bin
        const auto b = static_cast<std::size_t>(std::countr_zero(rest));
        rest ^= 1u << b;
        const auto next = static_cast<std::size_t>(std::countr_zero(rest));
        left.extend(bins[b].bounds);
        n_left += bins[b].count;
        const double cost = leaf_tests_.step_cost + (tests(n_left) * left.bounds().surface_area() +
                                                     tests(right_count[next]) * right_area[next]) /
                                                        area;
        if (cost < best.cost) best.cost = cost, best.axis = a, best.bin = static_cast<int>(b);
      }
    }
    return best;
  }

  // Partitions [begin, end) at the chosen bin; returns the split position and the boxes of both
  // sides: the bounds as the union of each side's bins, the centroid bounds gathered by the
  // partition (which applies its predicate once per primitive), or both by a pass when a zero
  // makes the union's sign depend on the order (see the top of the file).
  std::size_t partition(std::size_t begin, std::size_t end, const SahChoice& choice,
                        const Bounds3& centroids, const Vec3& scale, NodeBoxes& first,
                        NodeBoxes& second) {
    const int axis = choice.axis;
    const auto last_first_bin = static_cast<std::uint32_t>(choice.bin);
    const double lo = centroids.lo[axis];
    const auto middle = std::partition(
        primitives_.begin() + static_cast<std::ptrdiff_t>(begin),
        primitives_.begin() + static_cast<std::ptrdiff_t>(end), [&](const BuildPrimitive& p) {
          const bool in_first = bin_of(p.centroid[axis], lo, scale[axis]) <= last_first_bin;
          (in_first ? first : second).centroids.extend(MinBox::of(p.centroid));
          return in_first;
        });
    // Binning and partition use one bin_of, so each side holds the primitives counted in its
    // bins, and neither is empty.
    const auto split = static_cast<std::size_t>(middle - primitives_.begin());
    const auto& bins = bins_[static_cast<std::size_t>(axis)];
    for (unsigned rest = occupied_[static_cast<std::size_t>(axis)]; rest != 0; rest &= rest - 1) {
      const auto b = static_cast<std::uint32_t>(std::countr_zero(rest));
      (b <= last_first_bin ? first : second).bounds.extend(bins[b].bounds);
    }
    if (first.bounds.has_zero() || first.centroids.has_zero()) first = gather(begin, split);
    if (second.bounds.has_zero() || second.centroids.has_zero()) second = gather(split, end);
    return split;
  }

  std::uint32_t build_node(std::size_t begin, std::size_t end, int depth, const NodeBoxes& boxes) {
    const Bounds3 bounds = boxes.bounds.bounds();
    const Bounds3 centroids = boxes.centroids.bounds();
    const Vec3 extent = centroids.diagonal();
    const std::size_t count = end - begin;
    // All centroids equal: no split separates anything (pbrt makes a leaf too).
    if (count == 1 || !(max_component(extent) > 0)) return make_leaf(begin, end, bounds);

    int axis = max_axis(extent);
    std::size_t split = 0;
    NodeBoxes first, second;
    const double area = bounds.surface_area();
    SahChoice choice;
    bool node_leaf_preferred = false;
    // From depth kSahDepth on, and for flat or line-like primitives whose boxes have no area,
    // the node is split by count.
    if (depth < kSahDepth && area > 0) {
      const Vec3 scale{extent.x > 0 ? kBins / extent.x : 0, extent.y > 0 ? kBins / extent.y : 0,
                       extent.z > 0 ? kBins / extent.z : 0};
      bin(begin, end, centroids.lo, scale);
      choice = cheapest_split(area, extent);
      const bool leaf_preferred = choice.axis >= 0 && count <= leaf_tests_.max_size &&
                                  tests(static_cast<std::uint32_t>(count)) <= choice.cost;
      const bool leaf = leaf_preferred && count <= leaf_tests_.split_above;
      node_leaf_preferred = leaf_preferred;
      if (choice.axis >= 0 && !leaf) {
        axis = choice.axis;
        split = partition(begin, end, choice, centroids, scale, first, second);
      }
      clear_bins();
      if (leaf) return make_leaf(begin, end, bounds);
    }
    if (choice.axis < 0) {
      split = median_split(begin, end, axis);
      first = gather(begin, split);
      second = gather(split, end);
    }

    const auto self = static_cast<std::uint32_t>(bvh_.nodes.size());
    BvhNode node;
    node.bounds = bounds;
    node.split_axis = static_cast<std::uint8_t>(axis);
    node.leaf_preferred = node_leaf_preferred;
    bvh_.nodes.push_back(node);
    if (end - split >= kMinParallelPrimitives && take_spare_thread()) {
      // The two children's ranges are disjoint, so both builders may reorder theirs at once.
      // A failure (std::bad_alloc on a hostile mesh) on either thread reaches the caller.
      Bvh second_tree;
      std::exception_ptr second_failure;
      {
        std::jthread second_builder([&] {
          try {
            Builder(primitives_, second_tree, spare_threads_, leaf_tests_)
                .build(split, end, depth + 1, second);
          } catch (...) {
            second_failure = std::current_exception();
          }
          spare_threads_.fetch_add(1);
        });
        build_node(begin, split, depth + 1, first);  // the first child is the next node
      }
      if (second_failure) std::rethrow_exception(second_failure);
      bvh_.nodes[self].first_or_second_child = append(second_tree);
    } else {
      build_node(begin, split, depth + 1, first);  // the first child is the next node
      bvh_.nodes[self].first_or_second_child = build_node(split, end, depth + 1, second);
    }
    return self;
  }

  bool take_spare_thread() {
    int spare = spare_threads_.load();
    while (spare > 0 && !spare_threads_.compare_exchange_weak(spare, spare - 1)) {
    }
    return spare > 0;
  }

  // Appends a subtree built by another Builder; returns the index of its root.
  std::uint32_t append(const Bvh& subtree) {
    const auto node_base = static_cast<std::uint32_t>(bvh_.nodes.size());
    const auto order_base = static_cast<std::uint32_t>(bvh_.primitive_order.size());
    for (BvhNode node : subtree.nodes) {
      node.first_or_second_child += node.count > 0 ? order_base : node_base;
      bvh_.nodes.push_back(node);
    }
    bvh_.primitive_order.insert(bvh_.primitive_order.end(), subtree.primitive_order.begin(),
                                subtree.primitive_order.end());
    return node_base;
  }

  std::vector<BuildPrimitive>& primitives_;  // shared; each Builder reorders only its range
  Bvh& bvh_;
  std::atomic<int>& spare_threads_;  // shared by all Builders of one tree
  const BvhLeafTests leaf_tests_;
  std::array<std::array<Bin, kBins>, 3> bins_;  // one node's at a time
  std::array<unsigned, 3> occupied_{};          // bit b: bins_[axis][b] is not empty
};

}  // namespace

Bvh build_bvh_nodes(std::span<const Bounds3> primitive_bounds, BvhMode mode, int threads,
                    BvhLeafTests leaf_tests) {
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
    primitives.push_back({MinBox::of(b), b.centroid(), static_cast<std::uint32_t>(i)});
  }
  std::atomic<int> spare_threads = threads - 1;  // the caller's thread builds too
  Builder(primitives, bvh, spare_threads, leaf_tests).build();
  return bvh;
}

Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode, int threads) {
  Bvh bvh = build_bvh_nodes(primitive_bounds, mode, threads);
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

void make_bvh_wide(Bvh& bvh) {
  bvh.wide.clear();
  if (bvh.nodes.empty() || bvh.nodes[0].count > 0) return;
  const auto second_child = [&](std::size_t n) { return bvh.nodes[n].first_or_second_child; };
  // Wide nodes are made in the order they are reached (the root first); `pending` holds a
  // wide node still to fill and the binary node it stands for.
  std::vector<std::pair<std::uint32_t, std::size_t>> pending = {{0, 0}};
  bvh.wide.emplace_back();
  while (!pending.empty()) {
    const auto [wide_index, binary] = pending.back();
    pending.pop_back();
    std::size_t children[kWideChildren] = {binary + 1, second_child(binary)};
    int n = 2;
    while (n < kWideChildren) {
      int widest = -1;
      double widest_area = -1;
      for (int c = 0; c < n; ++c) {
        const BvhNode& child = bvh.nodes[children[c]];
        if (child.count == 0 && child.bounds.surface_area() > widest_area)
          widest = c, widest_area = child.bounds.surface_area();
      }
      if (widest < 0) break;
      const std::size_t opened = children[widest];
      children[widest] = opened + 1;
      children[n++] = second_child(opened);
    }
    BvhWideNode node;
    for (int c = 0; c < n; ++c) {
      const BvhNode& child = bvh.nodes[children[c]];
      set_float_child_box(node.boxes, c, child.bounds);
      node.count[c] = child.count;
      if (child.count > 0) {
        node.child[c] = child.first_or_second_child;
      } else if (child.leaf_preferred) {
        // The subtree's leaves lie in order: the range runs from its first to its last.
        std::size_t first = children[c], last = children[c];
        while (bvh.nodes[first].count == 0) ++first;
        while (bvh.nodes[last].count == 0) last = second_child(last);
        node.child[c] = bvh.nodes[first].first_or_second_child;
        node.count[c] =
            bvh.nodes[last].first_or_second_child + bvh.nodes[last].count - node.child[c];
      } else {
        node.child[c] = static_cast<std::uint32_t>(bvh.wide.size());
        pending.emplace_back(node.child[c], children[c]);
        bvh.wide.emplace_back();
      }
    }
    bvh.wide[wide_index] = node;
  }
}

WideBvhCost wide_bvh_cost(const Bvh& bvh, BvhLeafTests leaf_tests) {
  WideBvhCost cost;
  if (bvh.wide.empty()) return cost;
  const double root_area = bvh.nodes[0].bounds.surface_area();
  if (!(root_area > 0)) return cost;
  const auto area = [](const FloatChildBoxes& boxes, int c) {
    const auto side = [&](int a) {
      return static_cast<double>(boxes.bound[a][1][c]) - static_cast<double>(boxes.bound[a][0][c]);
    };
    return 2 * (side(0) * side(1) + side(1) * side(2) + side(2) * side(0));
  };
  // (wide node, its area over the root's)
  std::vector<std::pair<std::uint32_t, double>> pending = {{0, 1.0}};
  while (!pending.empty()) {
    const auto [index, weight] = pending.back();
    pending.pop_back();
    cost.node_steps += weight;
    const BvhWideNode& node = bvh.wide[index];
    for (int c = 0; c < kWideChildren; ++c) {
      if (!(node.boxes.bound[0][0][c] <= node.boxes.bound[0][1][c])) continue;  // empty slot
      const double child_weight = area(node.boxes, c) / root_area;
      if (node.count[c] > 0)
        cost.leaf_tests +=
            child_weight * ((node.count[c] + leaf_tests.group - 1) / leaf_tests.group);
      else
        pending.emplace_back(node.child[c], child_weight);
    }
  }
  return cost;
}

}  // namespace tessera
