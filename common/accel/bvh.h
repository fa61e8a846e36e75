// A bounding volume hierarchy over anything with bounds, built with the surface area heuristic
// (binned, as in pbrt-v3 §4.3) or, for comparison, not at all (BvhMode::None: one leaf holding
// every primitive, the seeds' "acceleration off"). The tree is built binary in double; the scene
// BVH is traversed in that form, in double (BvhPair, bvh_traverse.h), a mesh's as an 8-wide tree
// in float (BvhWideNode, wide_bvh_traverse.h; conservative, see float_child_boxes.h). Float
// boxes contain a ray that leaves a surface more often than double ones (its origin is a few
// rounding errors outside the surface's box in double, inside it in float): that costs nothing
// inside a mesh, whose boxes the ray starts in anyway, but made every secondary ray re-test
// the object it leaves in the scene BVH (docs/PERFORMANCE.md).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/accel/child_boxes.h"
#include "common/accel/float_child_boxes.h"
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
  // Interior: the SAH would have made this node a leaf, but it holds more than
  // BvhLeafTests::split_above primitives (make_bvh_wide).
  bool leaf_preferred = false;
};

// The form traversal reads: one entry per interior node holding both children, their boxes
// side by side (child_boxes.h), so that one step tests two boxes and loads one cache line pair.
struct BvhPair {
  ChildBoxes boxes;
  std::uint32_t child[2] = {0, 0};  // pairs index of an interior child; first primitive of a leaf
  std::uint32_t count[2] = {0, 0};  // primitives of a leaf child; 0 for an interior child
};

// The mesh BVH's form: the binary tree collapsed into nodes of up to eight children
// (make_bvh_wide), their boxes side by side in float, rounded outward (float_child_boxes.h), so
// that one step tests eight boxes with AVX (or two fours with SSE) and the node fills four cache
// lines exactly.
struct alignas(64) BvhWideNode {
  FloatChildBoxes boxes = empty_float_child_boxes();
  // Per child: its index into Bvh::wide if interior, else its leaf's first primitive ...
  std::uint32_t child[kWideChildren] = {};
  // ... and its leaf's primitive count, 0 for an interior child.
  std::uint32_t count[kWideChildren] = {};
};
static_assert(sizeof(BvhWideNode) == 256);

// The build keeps trees shallower than this (bvh.cpp), so the traversals' fixed stacks cannot
// overflow.
inline constexpr int kBvhMaxDepth = 128;

struct Bvh {
  std::vector<BvhNode> nodes;                  // depth-first; nodes[0] is the root when non-empty
  std::vector<std::uint32_t> primitive_order;  // leaf ranges index into this
  // The form a traversal reads, made from nodes; [0] is the root's, if interior. Either one:
  std::vector<BvhPair> pairs;     // make_bvh_pairs (build_bvh), for bvh_traverse.h
  std::vector<BvhWideNode> wide;  // make_bvh_wide, for wide_bvh_traverse.h
};

// How the SAH prices a leaf: its primitives are tested `group` at a time, so a leaf of n costs
// ceil(n / group) tests (a traversal step costs `step_cost` tests), and a leaf holds at most
// `max_size`. The scene's objects are tested one at a time; a mesh's triangles four at a time
// with AVX2 (intersect_triangle_pair.h), whose larger leaves save node visits (MeshAccel).
struct BvhLeafTests {
  std::uint32_t group = 1;
  std::uint32_t max_size = 4;
  double step_cost = 0.5;
  // A node of more primitives is split even where the SAH prefers a leaf (it is marked
  // leaf_preferred), so that make_bvh_wide may still open it to fill a wide node's free slots.
  std::uint32_t split_above = 0xffffffffu;
};

// The binary tree (nodes and primitive_order), without a traversal form. `threads` (the
// caller's included) may build large subtrees at once; the tree is the same for any count.
Bvh build_bvh_nodes(std::span<const Bounds3> primitive_bounds, BvhMode mode, int threads = 1,
                    BvhLeafTests leaf_tests = {});
// build_bvh_nodes and make_bvh_pairs.
Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode, int threads = 1);
// Fills bvh.pairs from bvh.nodes (build_bvh does; for hand-made trees).
void make_bvh_pairs(Bvh& bvh);
// Fills bvh.wide from bvh.nodes: each interior node takes the children of its largest-area
// interior children until it has kWideChildren (Embree's and pbrt-v4's collapse of a binary SAH
// tree). An interior child left over that is leaf_preferred becomes one leaf of its subtree's
// primitive range (with any gaps the caller left between its leaves), as Embree's n-ary build
// fills a node's slots first and asks the SAH for a leaf only of the children that remain.
void make_bvh_wide(Bvh& bvh);

// The SAH's two terms for bvh.wide, to compare builds without tracing: the expected wide-node
// steps and leaf tests (ceil(n / group) each) of a ray through random points of the root's box
// (each node or leaf weighted by its float box's area over the root's).
struct WideBvhCost {
  double node_steps = 0;
  double leaf_tests = 0;
};
WideBvhCost wide_bvh_cost(const Bvh& bvh, BvhLeafTests leaf_tests);
// Traversals: common/accel/bvh_traverse.h, common/accel/wide_bvh_traverse.h.

}  // namespace tessera
