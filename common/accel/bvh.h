// A bounding volume hierarchy over anything with bounds, built with the surface area heuristic
// (binned, as in pbrt-v3 §4.3) or, for comparison, not at all (BvhMode::None: one leaf holding
// every primitive, the seeds' "acceleration off").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "common/math/ray.h"

namespace tessera {

enum class BvhMode { Sah, None };

struct BvhNode {
  Bounds3 bounds;
  // Leaf: first primitive index into Bvh::primitive_order and count > 0.
  // Interior: count == 0, the first child is the next node, `second_child` the other.
  std::uint32_t first_or_second_child = 0;
  std::uint32_t count = 0;
  std::uint8_t split_axis = 0;
};

struct Bvh {
  std::vector<BvhNode> nodes;                  // depth-first; nodes[0] is the root when non-empty
  std::vector<std::uint32_t> primitive_order;  // leaf ranges index into this
};

Bvh build_bvh(std::span<const Bounds3> primitive_bounds, BvhMode mode);

// Visits the leaves whose boxes the ray [0, t_max] enters, nearest-first by split axis.
// `visit(primitive_index, t_max)` returns the possibly shrunk t_max (closest hit) or a negative
// value to stop the traversal (any-hit queries). Counts visited nodes in `nodes_visited`.
template <typename Visit>
void traverse_bvh(const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
                  Visit&& visit);

}  // namespace tessera

#include "common/accel/bvh_traverse.h"
