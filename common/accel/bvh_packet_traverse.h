// Up to four rays (camera rays of neighbouring pixels) walking the scene BVH of bvh.h together:
// a node's two boxes are loaded once and tested for every ray of the packet, with per lane the
// operations of intersect_child_boxes (child_boxes.h), so each ray's answers are bit for bit its
// own (tests/accel/bvh_packet_traverse_test.cpp). Each ray also visits the leaves in the order
// and with the t_max its own traversal (traverse_bvh_leaves) would: a shape's answer may depend on
// the t_max it is given (a torus searches its quartic's roots up to it), so the nearest hit of a
// ray depends on the order it meets the shapes. Where the rays that enter both children of a node
// disagree on which comes first, the packet splits, each part walking on in its own order.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include "common/accel/bvh.h"
#include "common/accel/wide_box_kernel.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

inline constexpr int kPacketLanes = 4;

// The lanes in a mask of kPacketLanes bits: std::popcount is a call into libgcc on x86-64
// without POPCNT (some 10 instructions a pair test).
inline constexpr unsigned char kLaneCount[1 << kPacketLanes] = {0, 1, 1, 2, 1, 2, 2, 3,
                                                                1, 2, 2, 3, 2, 3, 3, 4};

// The lanes of a mask of kPacketLanes bits as bools, lane l for bit l.
inline constexpr bool kLaneBools[1 << kPacketLanes][kPacketLanes] = {
    {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}, {0, 0, 1, 0}, {1, 0, 1, 0},
    {0, 1, 1, 0}, {1, 1, 1, 0}, {0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {1, 1, 0, 1},
    {0, 0, 1, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}, {1, 1, 1, 1}};

// The per-ray constants of the box tests, a lane per ray (those of BoxRay).
struct PacketRays {
  alignas(16) double origin[3][kPacketLanes];
  alignas(16) double inv_dir[3][kPacketLanes];
  bool backward[3][kPacketLanes];  // inv_dir < 0 (BoxRay::near_side 1): the near side is hi
  unsigned lanes;                  // bit l set for a ray in lane l
  // Whether on every axis all four lanes have the same near side (neighbouring camera rays
  // mostly do): then the box test picks each axis's near and far bounds once for all lanes.
  bool same_sides = true;

  // `count` rays, 1 to kPacketLanes; lanes beyond them repeat the first ray, unused.
  PacketRays(const Ray* rays, int count) : lanes((1u << count) - 1) {
#if defined(__SSE2__)
    // Two lanes a register, each lane's division and compare those of the loop below, in
    // straight-line code: the same bits for about a third of its instructions (some 260 a
    // packet).
    const Ray& r0 = rays[0];
    const Ray& r1 = rays[count > 1 ? 1 : 0];
    const Ray& r2 = rays[count > 2 ? 2 : 0];
    const Ray& r3 = rays[count > 3 ? 3 : 0];
    const __m128d one = _mm_set1_pd(1), zero = _mm_setzero_pd();
    // Axis a (coordinate c of a Vec3): its origins and inverse directions stored, and its
    // backward lanes returned as bits.
    const auto axis = [&](int a, double Vec3::*c) {
      _mm_store_pd(origin[a], _mm_setr_pd(r0.origin.*c, r1.origin.*c));
      _mm_store_pd(origin[a] + 2, _mm_setr_pd(r2.origin.*c, r3.origin.*c));
      const __m128d inv01 = _mm_div_pd(one, _mm_setr_pd(r0.direction.*c, r1.direction.*c));
      const __m128d inv23 = _mm_div_pd(one, _mm_setr_pd(r2.direction.*c, r3.direction.*c));
      _mm_store_pd(inv_dir[a], inv01);
      _mm_store_pd(inv_dir[a] + 2, inv23);
      const int back = _mm_movemask_pd(_mm_cmpnge_pd(inv01, zero)) |
                       _mm_movemask_pd(_mm_cmpnge_pd(inv23, zero)) << 2;
      std::memcpy(backward[a], kLaneBools[back], kPacketLanes);
      return back;
    };
    const int x = axis(0, &Vec3::x), y = axis(1, &Vec3::y), z = axis(2, &Vec3::z);
    const auto uniform = [](int back) { return back == 0 || back == (1 << kPacketLanes) - 1; };
    same_sides = uniform(x) && uniform(y) && uniform(z);
#else
    for (int l = 0; l < kPacketLanes; ++l) {
      const Ray& ray = rays[l < count ? l : 0];
      for (int a = 0; a < 3; ++a) {
        origin[a][l] = ray.origin[a];
        inv_dir[a][l] = 1 / ray.direction[a];  // as BoxRay's divpd and divsd round
        backward[a][l] = !(inv_dir[a][l] >= 0);
        same_sides = same_sides && backward[a][l] == backward[a][0];
      }
    }
#endif
  }
};

// For child c of `boxes`, bit l of hits[c] is set when ray l [0, t_max[l]] meets its box, and
// entry[c][l] receives where it enters, as intersect_child_boxes gives them for ray l alone.
[[gnu::always_inline]] inline void intersect_child_boxes_packet(const ChildBoxes& boxes,
                                                                const PacketRays& rays,
                                                                const double* t_max,
                                                                double entry[2][kPacketLanes],
                                                                unsigned hits[2]) {
  constexpr double kFarScale = 1 + 2 * gamma_bound(3);
#if defined(__SSE2__)
  if (rays.same_sides) {
    // Two lanes a register, the operations of the loop below in the same order.
    const __m128d far_scale = _mm_set1_pd(kFarScale);
    for (int c = 0; c < 2; ++c) {
      __m128d t0[2] = {_mm_setzero_pd(), _mm_setzero_pd()};
      __m128d t1[2] = {_mm_loadu_pd(t_max), _mm_loadu_pd(t_max + 2)};
      for (int a = 0; a < 3; ++a) {
        const int near = rays.backward[a][0] ? 1 : 0;
        const __m128d near_bound = _mm_set1_pd(boxes.bound[a][near][c]);
        const __m128d far_bound = _mm_set1_pd(boxes.bound[a][1 - near][c]);
        for (int h = 0; h < 2; ++h) {
          const __m128d o = _mm_load_pd(rays.origin[a] + 2 * h);
          const __m128d inv = _mm_load_pd(rays.inv_dir[a] + 2 * h);
          const __m128d t_near = _mm_mul_pd(_mm_sub_pd(near_bound, o), inv);
          const __m128d t_far = _mm_mul_pd(_mm_mul_pd(_mm_sub_pd(far_bound, o), inv), far_scale);
          t0[h] = _mm_max_pd(t_near, t0[h]);
          t1[h] = _mm_min_pd(t_far, t1[h]);
        }
      }
      _mm_storeu_pd(entry[c], t0[0]);
      _mm_storeu_pd(entry[c] + 2, t0[1]);
      hits[c] = static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(t0[0], t1[0])) |
                                      (_mm_movemask_pd(_mm_cmple_pd(t0[1], t1[1])) << 2));
    }
    return;
  }
#endif
  for (int c = 0; c < 2; ++c) {
    double t0[kPacketLanes], t1[kPacketLanes];
    for (int l = 0; l < kPacketLanes; ++l) t0[l] = 0, t1[l] = t_max[l];
    for (int a = 0; a < 3; ++a) {
      const double lo = boxes.bound[a][0][c], hi = boxes.bound[a][1][c];
      for (int l = 0; l < kPacketLanes; ++l) {
        const double o = rays.origin[a][l], inv = rays.inv_dir[a][l];
        const bool back = rays.backward[a][l];
        const double t_near = ((back ? hi : lo) - o) * inv;
        const double t_far = ((back ? lo : hi) - o) * inv * kFarScale;
        t0[l] = t_near > t0[l] ? t_near : t0[l];
        t1[l] = t_far < t1[l] ? t_far : t1[l];
      }
    }
    unsigned mask = 0;
    for (int l = 0; l < kPacketLanes; ++l) {
      entry[c][l] = t0[l];
      mask |= (t0[l] <= t1[l] ? 1u : 0u) << l;
    }
    hits[c] = mask;
  }
}

#if defined(__SSE2__)
// intersect_child_boxes_packet with the four lanes in one AVX register when they share their
// near sides: the same operations per lane (max and min keep their operand order, and the
// ordered-signaling <= is cmplepd's), so the same bits. Both children are tested together, the
// axes and children unrolled, so that an axis's origins, inverse directions and near side are
// loaded once for the two boxes: a child at a time in loops, each pair test took some 200
// instructions, most of them the loops' index arithmetic.
[[gnu::target("avx2")]] inline void intersect_child_boxes_packet_avx2(const ChildBoxes& boxes,
                                                                      const PacketRays& rays,
                                                                      const double* t_max,
                                                                      double entry[2][kPacketLanes],
                                                                      unsigned hits[2]) {
  static_assert(kPacketLanes == 4);
  if (!rays.same_sides) return intersect_child_boxes_packet(boxes, rays, t_max, entry, hits);
  const __m256d far_scale = _mm256_set1_pd(1 + 2 * gamma_bound(3));
  const __m256d limit = _mm256_loadu_pd(t_max);
  __m256d t0[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
  __m256d t1[2] = {limit, limit};
#pragma GCC unroll 3
  for (int a = 0; a < 3; ++a) {
    const int near = rays.backward[a][0] ? 1 : 0;
    const __m256d o = _mm256_loadu_pd(rays.origin[a]);
    const __m256d inv = _mm256_loadu_pd(rays.inv_dir[a]);
#pragma GCC unroll 2
    for (int c = 0; c < 2; ++c) {
      const __m256d near_bound = _mm256_set1_pd(boxes.bound[a][near][c]);
      const __m256d far_bound = _mm256_set1_pd(boxes.bound[a][1 - near][c]);
      const __m256d t_near = _mm256_mul_pd(_mm256_sub_pd(near_bound, o), inv);
      const __m256d t_far =
          _mm256_mul_pd(_mm256_mul_pd(_mm256_sub_pd(far_bound, o), inv), far_scale);
      t0[c] = _mm256_max_pd(t_near, t0[c]);
      t1[c] = _mm256_min_pd(t_far, t1[c]);
    }
  }
  for (int c = 0; c < 2; ++c) {
    _mm256_storeu_pd(entry[c], t0[c]);
    hits[c] = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(t0[c], t1[c], _CMP_LE_OS)));
  }
}
#endif

// The walk of traverse_bvh_packet_leaves: run() tests boxes with intersect_child_boxes_packet,
// run_avx2() with intersect_child_boxes_packet_avx2 (wide_box_kernel() chooses).
template <typename VisitLeaf>
class BvhPacketWalk {
 public:
  BvhPacketWalk(const Bvh& bvh, const PacketRays& rays, double* t_max, std::uint64_t& nodes_visited,
                VisitLeaf& visit_leaf)
      : pairs_(bvh.pairs.data()),
        rays_(rays),
        t_max_(t_max),
        nodes_visited_(nodes_visited),
        visit_leaf_(visit_leaf) {}

  // A child to visit, by the lanes in `lanes`: an interior one (count 0, index into bvh.pairs)
  // or a leaf's range; entry[l] is where lane l enters it.
  struct Pending {
    std::uint32_t index;
    std::uint32_t count;
    unsigned lanes;
    double entry[kPacketLanes];
  };

  // Walks the lanes `walk` from `current` on, then through `stack` (`size` entries, the top
  // last), which it consumes.
  void run(unsigned walk, Pending current, Pending* stack, int size) {
    walk_from<WideBoxKernel::Sse2>(walk, current, stack, size);
  }
#if defined(__SSE2__)
  // Compiled for AVX2 (no FMA), flattened: the leaf visitor inlined here keeps its IEEE
  // operations, only their encoding changes. The box test stays a call (GCC inlines no
  // target-specific function into the always-inline walk_from; inlining it through a flattened,
  // not always-inline walk_from measured the same).
  [[gnu::flatten, gnu::target("avx2")]] void run_avx2(unsigned walk, Pending current,
                                                      Pending* stack, int size) {
    walk_from<WideBoxKernel::Avx2>(walk, current, stack, size);
  }
#endif

 private:
  template <WideBoxKernel kKernel>
  [[gnu::always_inline]] void walk_from(unsigned walk, Pending current, Pending* stack, int size) {
    for (;;) {
      if (current.count > 0) {
        visit_leaf_(current.lanes, current.index, current.count);
      } else {
        const BvhPair& pair = pairs_[current.index];
        double entry[2][kPacketLanes];
        unsigned hits[2];
        nodes_visited_ += 2 * kLaneCount[current.lanes];
#if defined(__SSE2__)
        if constexpr (has_avx2(kKernel))
          intersect_child_boxes_packet_avx2(pair.boxes, rays_, t_max_, entry, hits);
        else
#endif
          intersect_child_boxes_packet(pair.boxes, rays_, t_max_, entry, hits);
        hits[0] &= current.lanes;
        hits[1] &= current.lanes;
        // The lanes that enter both children and, as a ray alone would, take the second first.
        unsigned both = hits[0] & hits[1], second_first = 0;
        for (unsigned m = both; m != 0; m &= m - 1) {
          const int l = std::countr_zero(m);
          if (entry[1][l] < entry[0][l]) second_first |= 1u << l;
        }
        if (second_first != 0 && second_first != both) {
          // Split: those lanes walk on alone, on a copy of the stack.
          Pending fork[kBvhMaxDepth];
          std::copy(stack, stack + size, fork);
          const unsigned fork_hits[2] = {hits[0] & second_first, hits[1] & second_first};
          int fork_size = size;
          Pending fork_current = descend(pair, 1, fork_hits, entry, fork, fork_size);
#if defined(__SSE2__)
          if constexpr (has_avx2(kKernel))
            run_avx2(second_first, fork_current, fork, fork_size);
          else
#endif
            run(second_first, fork_current, fork, fork_size);
          walk &= ~second_first;
          hits[0] &= ~second_first;
          hits[1] &= ~second_first;
          second_first = 0;
        }
        if ((hits[0] | hits[1]) != 0) {
          // The second child first when some lane takes it first, or only it is entered.
          const int near = second_first != 0 || hits[0] == 0 ? 1 : 0;
          current = descend(pair, near, hits, entry, stack, size);
          continue;
        }
      }
      for (;;) {
        if (size == 0) return;
        current = stack[--size];
        unsigned lanes = 0;
        for (unsigned m = current.lanes & walk; m != 0; m &= m - 1) {
          const int l = std::countr_zero(m);
          if (current.entry[l] <= t_max_[l]) lanes |= 1u << l;
        }
        current.lanes = lanes;
        if (lanes != 0) break;
      }
    }
  }

  // The child `near` of `pair` to visit next, for the lanes hits[near]; the other one, when some
  // lane enters it, pushed onto `stack` for its lanes hits[1 - near].
  static Pending descend(const BvhPair& pair, int near, const unsigned hits[2],
                         const double entry[2][kPacketLanes], Pending* stack, int& size) {
    const int far = 1 - near;
    if (hits[far] != 0) {
      Pending& kept = stack[size++];
      kept = {pair.child[far], pair.count[far], hits[far], {}};
      std::copy(entry[far], entry[far] + kPacketLanes, kept.entry);
    }
    Pending next{pair.child[near], pair.count[near], hits[near], {}};
    std::copy(entry[near], entry[near] + kPacketLanes, next.entry);
    return next;
  }

  const BvhPair* pairs_;
  const PacketRays& rays_;
  double* t_max_;
  std::uint64_t& nodes_visited_;
  VisitLeaf& visit_leaf_;
};

// Visits, for each ray l of `rays`, the leaves traverse_bvh_leaves would visit for it alone, in
// the same order: `visit_leaf(lanes, first, count)` gets the leaf's range of Bvh::primitive_order
// for the rays whose lanes are set in `lanes` (bit l for ray l; those that reach the leaf together,
// so that they may test its shapes together) and may shrink t_max[l] for each of them (closest
// hit; the walk has no any-hit stop), as ray l's visit alone would. t_max[l] starts as ray l's
// limit and ends as its last. Counts the box tests as the rays' own traversals would in
// `nodes_visited`.
template <typename VisitLeaf>
void traverse_bvh_packet_leaves(const Bvh& bvh, const PacketRays& rays, double* t_max,
                                std::uint64_t& nodes_visited, VisitLeaf&& visit_leaf) {
  if (bvh.nodes.empty()) return;
  const BvhNode& root = bvh.nodes[0];
  if (root.count > 0) {
    for (unsigned m = rays.lanes; m != 0; m &= m - 1) {
      const int l = std::countr_zero(m);
      ++nodes_visited;
      const Vec3 origin{rays.origin[0][l], rays.origin[1][l], rays.origin[2][l]};
      const Vec3 inv_dir{rays.inv_dir[0][l], rays.inv_dir[1][l], rays.inv_dir[2][l]};
      if (intersect_bounds(root.bounds, origin, inv_dir, t_max[l]))
        visit_leaf(1u << l, root.first_or_second_child, root.count);
    }
    return;
  }
  // As traverse_bvh_leaves, the interior root's own box is not tested.
  using Walk = BvhPacketWalk<VisitLeaf>;
  typename Walk::Pending stack[kBvhMaxDepth];
  Walk walk(bvh, rays, t_max, nodes_visited, visit_leaf);
#if defined(__SSE2__)
  if (has_avx2(wide_box_kernel()))
    return walk.run_avx2(rays.lanes, {0, 0, rays.lanes, {}}, stack, 0);
#endif
  walk.run(rays.lanes, {0, 0, rays.lanes, {}}, stack, 0);
}

}  // namespace tessera
