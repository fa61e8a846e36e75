// A bounding volume hierarchy over anything with bounds, built with the surface area heuristic
// (binned, as in pbrt-v3 §4.3) or, for comparison, not at all (BvhMode::None: one leaf holding
// every primitive, the seeds' "acceleration off").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/accel/child_boxes.h"
#include "common/math/ray.h"
#include "common/settings/bvh_mode.h"

namespace tessera {

struct BvhNode {
  Bounds3 bounds;
  // Leaf: first primitive index into Bvh::primitive_order and count > 0.
  // Interior: count == 0, the first child is the next node, `second_child` the other.
  std::uint32_t first_or_second_child = 0;
  std::uint32_t count = 0;
  std::uint8_t split_axis = 0;
};

// The form traversal reads: one entry per interior node holding both children, their boxes
// side by side (child_boxes.h), so that one step tests two boxes and loads one cache line pair.
struct BvhPair {
  ChildBoxes boxes;
  std::uint32_t child[2] = {0, 0};  // pairs index of an interior child; first primitive of a leaf
  std::uint32_t count[2] = {0, 0};  // primitives of a leaf child; 0 for an interior child
};

struct Bvh {
  std::vector<BvhNode> nodes;                  // depth-first; nodes[0] is the root when non-empty
  std::vector<std::uint32_t> primitive_order;  // leaf ranges index into this
  std::vector<BvhPair> pairs;  // from nodes (make_bvh_pairs); pairs[0] is the root's, if interior
};

// `threads` (the caller's included) may build large subtrees at once; the tree is the same
// for any count.
Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode, int threads = 1);
// Fills bvh.pairs from bvh.nodes (build_bvh does; for hand-made trees).
void make_bvh_pairs(Bvh& bvh);
// Traversal: common/accel/bvh_traverse.h.

}  // namespace tessera
