// A bounding volume hierarchy over anything with bounds, built with the surface area heuristic
// (binned, as in pbrt-v3 §4.3) or, for comparison, not at all (BvhMode::None: one leaf holding
// every primitive, the seeds' "acceleration off"). The tree is built binary in double and
// traversed as a 4-wide tree in float (BvhWideNode; conservative, see child_boxes.h).
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

// The form traversal reads: the binary tree collapsed into nodes of up to four children
// (make_bvh_wide), their boxes side by side in float, rounded outward (child_boxes.h), so that
// one step tests four boxes with SSE and the node fills two cache lines exactly.
struct alignas(64) BvhWideNode {
  ChildBoxes boxes = empty_child_boxes();
  std::uint32_t child[4] = {0, 0, 0,
                            0};  // wide index of an interior child; first primitive of a leaf
  std::uint32_t count[4] = {0, 0, 0, 0};  // primitives of a leaf child; 0 for an interior one
};
static_assert(sizeof(BvhWideNode) == 128);

struct Bvh {
  std::vector<BvhNode> nodes;                  // depth-first; nodes[0] is the root when non-empty
  std::vector<std::uint32_t> primitive_order;  // leaf ranges index into this
  std::vector<BvhWideNode> wide;  // from nodes (make_bvh_wide); wide[0] is the root's, if interior
};

Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode);
// Fills bvh.wide from bvh.nodes (build_bvh does; for hand-made trees): each interior node
// takes the children of its largest-area interior children until it has four (Embree's and
// pbrt-v4's collapse of a binary SAH tree).
void make_bvh_wide(Bvh& bvh);
// Traversal: common/accel/bvh_traverse.h.

}  // namespace tessera
