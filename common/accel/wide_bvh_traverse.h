// The traversal of a mesh's BVH (common/accel/bvh.h, Bvh::wide): depth-first with an explicit
// stack over the wide nodes. A step tests a node's (up to) eight children's boxes in float
// (float_child_boxes.h, conservative: it reaches every leaf the double slab test would), with the
// kernel chosen at run time (wide_box_kernel.h), descends into the child the ray enters first
// and keeps the others with their entry distances, the nearer ones on top (or, for occlusion, in
// slot order: WideBvhOrder); a kept child is skipped when a closer hit found meanwhile lies
// before its entry. The order only decides how
// soon t_max shrinks: callers choose among hits at equal t by primitive index, so results do not
// depend on it.
#pragma once

#include <bit>
#include <cstdint>
#include <type_traits>

#include "common/accel/bvh.h"
#include "common/accel/wide_box_kernel.h"
#include "common/accel/wide_bvh_pending.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

// The order a traversal visits the children a ray enters: nearest first (kNearestFirst), for
// nearest hits, whose t_max shrinks sooner so; or slot order (kAnyOrder), without sorting, for
// queries whose t_max never shrinks (occlusion, which ends at its first hit, and every hit): a
// shadow ray that is not blocked, most of them, visits the same children in any order, and the
// sort was about 5 % of its time (docs/PERFORMANCE.md "Shadow rays in slot order").
enum class WideBvhOrder { NearestFirst, Any };
template <WideBvhOrder kOrder>
using WideBvhOrderTag = std::integral_constant<WideBvhOrder, kOrder>;
inline constexpr WideBvhOrderTag<WideBvhOrder::NearestFirst> kNearestFirst;
inline constexpr WideBvhOrderTag<WideBvhOrder::Any> kAnyOrder;

#if defined(__SSE2__)
// leaf_children for the AVX2 kernel (compiled for AVX2 apart: an always-inline function cannot
// take another target's instructions, and gnu::flatten inlines this one into that kernel's loop).
[[gnu::target("avx2")]] inline unsigned leaf_children_avx2(const BvhWideNode& node) {
  const __m256i count = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.count));
  return static_cast<unsigned>(
      _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(count, _mm256_setzero_si256()))));
}
#endif

// The children of `node` that are leaves (count > 0), as bits (bit c for slot c), with the
// kernel's instructions: they depend on the node's load alone, not on its box test. Counts are
// compared as signed 32-bit integers: a wide node's leaves hold a few dozen at most.
template <typename Kernel>
[[gnu::always_inline]] inline unsigned leaf_children(const BvhWideNode& node, Kernel) {
  static_assert(kWideChildren == 8);
#if defined(__SSE2__)
  if constexpr (has_avx2(Kernel::value)) {
    return leaf_children_avx2(node);
  } else if constexpr (Kernel::value == WideBoxKernel::Sse2) {
    const __m128i zero = _mm_setzero_si128();
    const auto* count = reinterpret_cast<const __m128i*>(node.count);
    const int low = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_load_si128(count), zero)));
    const int high =
        _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_load_si128(count + 1), zero)));
    return static_cast<unsigned>(low | high << 4);
  }
#endif
  unsigned bits = 0;
  for (int c = 0; c < kWideChildren; ++c) bits |= static_cast<unsigned>(node.count[c] > 0) << c;
  return bits;
}

// The loop below the root, making the ray's constants with `set_box_ray(box_ray, ray)`, testing
// boxes with `test_boxes(node.boxes, box_ray, far_limit, entry)` and passing `kernel` to the leaf
// visitor. Instantiated once per kernel, each inlined
// whole (gnu::flatten) into a function compiled for that kernel's instruction set, so that the
// visitor and the box test run in one loop without calls.
template <WideBvhOrder kOrder, typename Kernel, typename SetBoxRay, typename TestBoxes,
          typename VisitLeaf>
inline void traverse_wide_bvh_below_root(const Bvh& bvh, const Ray& ray, double t_max,
                                         std::uint64_t& nodes_visited, VisitLeaf& visit_leaf,
                                         Kernel kernel, SetBoxRay set_box_ray,
                                         TestBoxes test_boxes) {
  FloatBoxRay box_ray;
  set_box_ray(box_ray, ray);
  FloatBoxLimit far_limit(float_far_limit(t_max));
  // A step pushes at most 7 a level; the AVX2 one stores past the top (wide_bvh_pending.h).
  WideBvhPending stack[(kWideChildren - 1) * kBvhMaxDepth + kWideBvhStackSlack];
  int size = 0;
  WideBvhPending current{0, 0, 0};
  const BvhWideNode* wide = bvh.wide.data();
  // Each way to the next child branches to the leaf visit (`leaf:`) or the next node step (the
  // loop's head) itself: a flag tested at the loop's head cost a setcc and a test after each
  // (docs/PERFORMANCE.md "The wide traversal's own instructions").
  for (;;) {
    {
      const BvhWideNode& node = wide[current.index];
      alignas(32) float entry[kWideChildren];
      nodes_visited += kWideChildren;
      const unsigned leaf_bits = leaf_children(node, kernel);
      const unsigned hits = test_boxes(node.boxes, box_ray, far_limit, entry);
      if (hits == 0) goto pop;
      if ((hits & (hits - 1)) == 0) {  // one child: nothing to order
        const int c = std::countr_zero(hits);
        current = {node.child[c], node.count[c], entry[c]};
        // Whether it is a leaf, from the node's leaf bits (leaf_children), ready as soon as the
        // box test's hits are, instead of from the child's count, which can only be loaded once
        // the hits have named the child: the branch on it, mispredicted about once in four for
        // incoherent rays, resolves a load sooner (docs/PERFORMANCE.md "The leaf-or-node branch
        // from the node's leaf bits").
        if ((hits & leaf_bits) != 0) goto leaf;
        continue;
      }
#if defined(__SSE2__)
      if constexpr (kOrder == WideBvhOrder::NearestFirst && has_avx2(Kernel::value)) {
        current = push_hits_nearest_first_avx2(node, entry, hits, stack, size);
        if (current.count > 0) goto leaf;
        continue;
      }
#endif
      if constexpr (kOrder == WideBvhOrder::Any) {
        unsigned rest = hits;
        const int c0 = std::countr_zero(rest);
        for (rest &= rest - 1; rest != 0; rest &= rest - 1) {
          const int c = std::countr_zero(rest);
          stack[size++] = {node.child[c], node.count[c], entry[c]};
        }
        current = {node.child[c0], node.count[c0], entry[c0]};
        if (current.count > 0) goto leaf;
        continue;
      }
      // The children hit, nearest first (the lower slot on a tie): an insertion sort of at
      // most eight.
      int order[kWideChildren], n = 0;
      for (unsigned rest = hits; rest != 0; rest &= rest - 1) {
        const int c = std::countr_zero(rest);
        int i = n++;
        for (; i > 0 && entry[order[i - 1]] > entry[c]; --i) order[i] = order[i - 1];
        order[i] = c;
      }
      for (int i = n - 1; i > 0; --i)
        stack[size++] = {node.child[order[i]], node.count[order[i]], entry[order[i]]};
      current = {node.child[order[0]], node.count[order[0]], entry[order[0]]};
      if (current.count > 0) goto leaf;
      continue;
    }
  leaf : {
    const double limit = visit_leaf(current.index, current.count, t_max, kernel);
    if (limit < 0) break;
    if (limit != t_max) t_max = limit, far_limit = FloatBoxLimit(float_far_limit(t_max));
  }
  pop:
    if (size == 0) break;
    current = stack[--size];
    // Without the order, entries are no reason to skip: t_max does not shrink.
    if (kOrder == WideBvhOrder::NearestFirst && !(current.entry <= far_limit.far)) goto pop;
    if (current.count > 0) goto leaf;
  }
}

template <WideBvhOrder kOrder, typename VisitLeaf>
[[gnu::flatten]] void traverse_wide_bvh_scalar(const Bvh& bvh, const Ray& ray, double t_max,
                                               std::uint64_t& nodes_visited,
                                               VisitLeaf& visit_leaf) {
  traverse_wide_bvh_below_root<kOrder>(
      bvh, ray, t_max, nodes_visited, visit_leaf, WideBoxKernelTag<WideBoxKernel::Scalar>{},
      set_float_box_ray_per_axis, intersect_float_child_boxes_scalar);
}

#if defined(__SSE2__)
template <WideBvhOrder kOrder, typename VisitLeaf>
[[gnu::flatten]] void traverse_wide_bvh_sse2(const Bvh& bvh, const Ray& ray, double t_max,
                                             std::uint64_t& nodes_visited, VisitLeaf& visit_leaf) {
  traverse_wide_bvh_below_root<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf,
                                       WideBoxKernelTag<WideBoxKernel::Sse2>{},
                                       set_float_box_ray_sse2, intersect_float_child_boxes_sse2);
}

// Compiled for AVX2 (no FMA): the visitor's double arithmetic, inlined here, keeps its IEEE
// operations, only their encoding changes.
template <WideBvhOrder kOrder, typename VisitLeaf>
[[gnu::flatten, gnu::target("avx2")]] void traverse_wide_bvh_avx2(const Bvh& bvh, const Ray& ray,
                                                                  double t_max,
                                                                  std::uint64_t& nodes_visited,
                                                                  VisitLeaf& visit_leaf) {
  traverse_wide_bvh_below_root<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf,
                                       WideBoxKernelTag<WideBoxKernel::Avx2>{},
                                       set_float_box_ray_avx2, intersect_float_child_boxes_avx2);
}

// The same code for a CPU with AVX-512F, VL, DQ and BW (WideBoxKernel::Avx512Vl): the AVX2
// functions inlined here are compiled for this target, so the loop has 32 vector registers.
template <WideBvhOrder kOrder, typename VisitLeaf>
[[gnu::flatten, gnu::target(TESSERA_AVX512VL_TARGET)]] void traverse_wide_bvh_avx512vl(
    const Bvh& bvh, const Ray& ray, double t_max, std::uint64_t& nodes_visited,
    VisitLeaf& visit_leaf) {
  traverse_wide_bvh_below_root<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf,
                                       WideBoxKernelTag<WideBoxKernel::Avx512Vl>{},
                                       set_float_box_ray_avx2, intersect_float_child_boxes_avx2);
}
#endif

// Whether a ray from `origin` certainly enters `box` for every direction: the origin lies in the
// closed box and t_max >= 0, in which case intersect_bounds (common/math/ray.h) accepts the box
// whatever the direction, so the root test can skip its three divisions and its branches on the
// direction's signs, which mispredict for incoherent rays (about one a ray in callgrind's model).
// Why it accepts: per axis, the near plane minus the origin is <= 0 forward (>= 0 backward) and
// keeps its sign through the rounded subtraction, so t_near is <= 0 (+-0 included) or NaN, and
// t0 stays 0; the far plane minus the origin has the other sign, so t_far is >= 0 (or -0 or NaN)
// and t1 stays >= 0 (t_max >= 0 excludes a NaN t_max); t0 <= t1 holds. Secondary rays (shadow
// feelers, reflections) start on the mesh, inside its root box.
[[gnu::always_inline]] inline bool starts_inside(const Bounds3& box, const Vec3& origin,
                                                 double t_max) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Bounds3) == 2 * sizeof(Vec3));
#if defined(__SSE2__)
  // The six comparisons as three of two lanes (cmplepd is <=, false with a NaN), from the box's
  // and the origin's doubles read in pairs: (lo.x, lo.y) <= (o.x, o.y), (lo.z, o.x) <= (o.z,
  // hi.x), (o.y, o.z) <= (hi.y, hi.z). Compared one at a time, with their loads, setcc and ands,
  // they were some 30 instructions of a mesh ray's set-up.
  const double* b = &box.lo.x;
  const __m128d lo_xy = _mm_loadu_pd(b), lo_z_hi_x = _mm_loadu_pd(b + 2);
  const __m128d hi_yz = _mm_loadu_pd(b + 4);
  const __m128d o_xy = _mm_loadu_pd(&origin.x), o_yz = _mm_loadu_pd(&origin.y);
  const __m128d in_xy = _mm_cmple_pd(lo_xy, o_xy), in_yz = _mm_cmple_pd(o_yz, hi_yz);
  const __m128d in_zx =
      _mm_cmple_pd(_mm_shuffle_pd(lo_z_hi_x, o_xy, 0b00), _mm_shuffle_pd(o_yz, lo_z_hi_x, 0b11));
  return (_mm_movemask_pd(_mm_and_pd(_mm_and_pd(in_xy, in_yz), in_zx)) == 3) & (t_max >= 0);
#else
  // Non-short-circuit operators: one branch instead of seven.
  return (box.lo.x <= origin.x) & (origin.x <= box.hi.x) & (box.lo.y <= origin.y) &
         (origin.y <= box.hi.y) & (box.lo.z <= origin.z) & (origin.z <= box.hi.z) & (t_max >= 0);
#endif
}

// Visits the leaves whose boxes the ray [0, t_max] may enter, in the order `order` names:
// `visit_leaf(first, count, t_max, kernel)` gets the leaf's range [first, first + count) of
// Bvh::primitive_order and returns the possibly shrunk t_max (closest hit) or a negative value to
// stop the traversal (any-hit queries); `kernel`, a WideBoxKernelTag, names the instruction set
// the loop around it was compiled for (a root that is a leaf is visited outside it: Scalar).
// `make_visit_leaf()` makes it once the ray enters the root's box, so that a ray that misses the
// whole tree (most rays of a scene, for a mesh that fills little of it) skips the leaves' per-ray
// preparation. Counts the boxes tested in `nodes_visited` (kWideChildren per wide node).
template <WideBvhOrder kOrder, typename MakeVisitLeaf>
void traverse_wide_bvh_leaves(const Bvh& bvh, const Ray& ray, double t_max,
                              std::uint64_t& nodes_visited, WideBvhOrderTag<kOrder>,
                              MakeVisitLeaf&& make_visit_leaf) {
  if (bvh.nodes.empty()) return;
  ++nodes_visited;
  const BvhNode& root = bvh.nodes[0];
  if (!starts_inside(root.bounds, ray.origin, t_max)) {
    const Vec3 inv_dir{1 / ray.direction.x, 1 / ray.direction.y, 1 / ray.direction.z};
    if (!intersect_bounds(root.bounds, ray.origin, inv_dir, t_max)) return;
  }
  auto visit_leaf = make_visit_leaf();
  if (root.count > 0) {
    // A root that is a leaf (a mesh of a few triangles) is visited out of line: inlined here, it
    // made the compiler keep a second copy of the leaf visitor's state for it, a dozen stores a
    // ray on the common path (docs/PERFORMANCE.md "An incoherent ray's set-up").
    const auto visit_root = [&visit_leaf, &root, t_max ]() __attribute__((noinline, cold)) {
      visit_leaf(root.first_or_second_child, root.count, t_max,
                 WideBoxKernelTag<WideBoxKernel::Scalar>{});
    };
    visit_root();
    return;
  }
  switch (wide_box_kernel()) {
#if defined(__SSE2__)
    case WideBoxKernel::Avx512Vl:
      return traverse_wide_bvh_avx512vl<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf);
    case WideBoxKernel::Avx2:
      return traverse_wide_bvh_avx2<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf);
    case WideBoxKernel::Sse2:
      return traverse_wide_bvh_sse2<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf);
#endif
    default:
      return traverse_wide_bvh_scalar<kOrder>(bvh, ray, t_max, nodes_visited, visit_leaf);
  }
}

}  // namespace tessera
