// The traversal of common/accel/bvh.h: depth-first with an explicit stack, the nearer child
// first by the sign of the ray direction on the node's split axis.
#pragma once

#include <cstdint>

#include "common/accel/bvh.h"

namespace tessera {

// The build keeps trees shallower than this (bvh.cpp), so the fixed stack cannot overflow.
inline constexpr int kBvhMaxDepth = 128;

template <typename Visit>
void traverse_bvh(const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
                  Visit&& visit) {
  if (bvh.nodes.empty()) return;
  const Vec3 inv_dir{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
  const bool negative[3] = {inv_dir.x < 0, inv_dir.y < 0, inv_dir.z < 0};
  std::uint32_t stack[kBvhMaxDepth];
  int size = 0;
  std::uint32_t current = 0;
  for (;;) {
    const BvhNode& node = bvh.nodes[current];
    ++nodes_visited;
    if (intersect_bounds(node.bounds, ray.origin, inv_dir, t_max)) {
      if (node.count > 0) {
        const std::uint32_t end = node.first_or_second_child + node.count;
        for (std::uint32_t i = node.first_or_second_child; i < end; ++i) {
          const double limit = visit(bvh.primitive_order[i], t_max);
          if (limit < 0) return;
          t_max = limit;
        }
      } else if (negative[node.split_axis]) {
        stack[size++] = current + 1;
        current = node.first_or_second_child;
        continue;
      } else {
        stack[size++] = node.first_or_second_child;
        current = current + 1;
        continue;
      }
    }
    if (size == 0) return;
    current = stack[--size];
  }
}

}  // namespace tessera
