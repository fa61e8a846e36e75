// The traversal of common/accel/bvh.h: depth-first with an explicit stack. An interior node
// tests both children's boxes and descends into the one the ray enters first, keeping the
// other with its entry distance; a kept child is skipped when a closer hit found meanwhile
// lies before its entry (the same answer a second box test would give).
#pragma once

#include <cstdint>

#include "common/accel/bvh.h"

namespace tessera {

// Visits the leaves whose boxes the ray [0, t_max] enters, the nearer child's first:
// `visit_leaf(first, count, t_max)` gets the leaf's range [first, first + count) of
// Bvh::primitive_order and returns the possibly shrunk t_max (closest hit) or a negative value to
// stop the traversal (any-hit queries). Counts the nodes whose boxes it tests in `nodes_visited`.
template <typename VisitLeaf>
void traverse_bvh_leaves(const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
                         VisitLeaf&& visit_leaf) {
  if (bvh.nodes.empty()) return;
  const BoxRay box_ray(ray);
  const BvhNode& root = bvh.nodes[0];
  if (root.count > 0) {
    ++nodes_visited;
    if (intersect_bounds(root.bounds, box_ray.origin, box_ray.inv_dir, t_max))
      visit_leaf(root.first_or_second_child, root.count, t_max);
    return;
  }
  // An interior root's own box is not tested (a scalar test, some 4 % of a small scene's
  // instructions): its children's boxes lie inside it, and each slab distance is monotonic in
  // the plane, so a ray that misses it misses both of them in the first pair test below.
  // A child to visit: an interior one (count 0, index into bvh.pairs) or a leaf's range.
  struct Pending {
    std::uint32_t index;
    std::uint32_t count;
    double entry;
  };
  Pending stack[kBvhMaxDepth];
  int size = 0;
  Pending current{0, 0, 0};
  const BvhPair* pairs = bvh.pairs.data();
  for (;;) {
    if (current.count > 0) {
      const double limit = visit_leaf(current.index, current.count, t_max);
      if (limit < 0) return;
      t_max = limit;
    } else {
      const BvhPair& pair = pairs[current.index];
      double entry[2];
      nodes_visited += 2;
      const unsigned hits = intersect_child_boxes(pair.boxes, box_ray, t_max, entry);
      if (hits != 0) {
        // Both hit: the nearer first (the first child on a tie), the other kept for later.
        const int near = hits == 2 || (hits == 3 && entry[1] < entry[0]) ? 1 : 0;
        if (hits == 3)
          stack[size++] = {pair.child[1 - near], pair.count[1 - near], entry[1 - near]};
        current = {pair.child[near], pair.count[near], entry[near]};
        continue;
      }
    }
    for (;;) {
      if (size == 0) return;
      current = stack[--size];
      if (current.entry <= t_max) break;
    }
  }
}

// The same walk a primitive at a time: `visit(primitive_index, t_max)` returns t_max as
// `visit_leaf` does.
template <typename Visit>
void traverse_bvh(const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
                  Visit&& visit) {
  traverse_bvh_leaves(bvh, ray, t_max, nodes_visited,
                      [&](std::uint32_t first, std::uint32_t count, double limit) {
                        const std::uint32_t end = first + count;
                        for (std::uint32_t i = first; i < end; ++i) {
                          limit = visit(bvh.primitive_order[i], limit);
                          if (limit < 0) return limit;
                        }
                        return limit;
                      });
}

}  // namespace tessera
