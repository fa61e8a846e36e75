// The scene BVH's traversal under AVX2 (Bvh::quads, quad_child_boxes.h): depth-first with an
// explicit stack, a step testing a node's four children's boxes in double, descending into the
// child the ray enters first and keeping the others, the nearer on top; a kept child is skipped
// when a closer hit found meanwhile lies before its entry. Without AVX2 (or quads), the binary
// traversal of bvh_traverse.h.
#pragma once

#include <bit>
#include <cstdint>

#include "common/accel/bvh_traverse.h"
#include "common/accel/wide_box_kernel.h"

namespace tessera {

#if defined(__x86_64__)
template <typename VisitLeaf>
[[gnu::flatten, gnu::target("avx2")]] void traverse_bvh_quads_avx2(const Bvh& bvh, const Ray& ray,
                                                                   double t_max,
                                                                   std::uint64_t& nodes_visited,
                                                                   VisitLeaf& visit_leaf) {
  const BoxRay box_ray(ray);
  struct Pending {
    std::uint32_t index;
    std::uint32_t count;
    double entry;
  };
  Pending stack[(kQuadChildren - 1) * kBvhMaxDepth];
  int size = 0;
  Pending current{0, 0, 0};
  const BvhQuadNode* quads = bvh.quads.data();
  for (;;) {
    if (current.count > 0) {
      const double limit = visit_leaf(current.index, current.count, t_max);
      if (limit < 0) return;
      t_max = limit;
    } else {
      const BvhQuadNode& node = quads[current.index];
      alignas(32) double entry[kQuadChildren];
      nodes_visited += kQuadChildren;
      const unsigned hits = intersect_quad_child_boxes_avx2(node.boxes, box_ray, t_max, entry);
      if (hits != 0) {
        if ((hits & (hits - 1)) == 0) {
          const int c = std::countr_zero(hits);
          current = {node.child[c], node.count[c], entry[c]};
          continue;
        }
        // Nearest first (the lower slot on a tie): an insertion sort of at most four.
        int order[kQuadChildren], n = 0;
        for (unsigned rest = hits; rest != 0; rest &= rest - 1) {
          const int c = std::countr_zero(rest);
          int i = n++;
          for (; i > 0 && entry[order[i - 1]] > entry[c]; --i) order[i] = order[i - 1];
          order[i] = c;
        }
        for (int i = n - 1; i > 0; --i)
          stack[size++] = {node.child[order[i]], node.count[order[i]], entry[order[i]]};
        current = {node.child[order[0]], node.count[order[0]], entry[order[0]]};
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
#endif

template <typename VisitLeaf>
void traverse_scene_bvh_leaves(const Bvh& bvh, const Ray& ray, double t_max,
                               std::uint64_t& nodes_visited, VisitLeaf&& visit_leaf) {
#if defined(__x86_64__)
  if (!bvh.quads.empty() && wide_box_kernel() == WideBoxKernel::Avx2)
    return traverse_bvh_quads_avx2(bvh, ray, t_max, nodes_visited, visit_leaf);
#endif
  traverse_bvh_leaves(bvh, ray, t_max, nodes_visited, visit_leaf);
}

template <typename Visit>
void traverse_scene_bvh(const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
                        Visit&& visit) {
  traverse_scene_bvh_leaves(bvh, ray, t_max, nodes_visited,
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
