// The children a wide BVH traversal (wide_bvh_traverse.h) keeps to visit later, and the AVX2
// node step that orders two or more of them without branches on their distances or number: for
// incoherent rays the insertion sort's compares and loops are coin tosses (docs/PERFORMANCE.md
// "The nearest-first order without branches").
#pragma once

#include <bit>
#include <cstdint>

#include "common/accel/bvh.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera {

// A child to visit: an interior one (count 0, index into Bvh::wide) or a leaf's range. Sixteen
// bytes (four of padding), so that the AVX2 step writes one with one store.
struct alignas(16) WideBvhPending {
  std::uint32_t index;
  std::uint32_t count;
  float entry;
};
static_assert(sizeof(WideBvhPending) == 16);

// Room beyond a traversal's deepest stack for the AVX2 step's stores past its top.
inline constexpr int kWideBvhStackSlack = kWideChildren + 1;

#if defined(__SSE2__)
// Adds to each lane c of `rank` whether the entry in lane (c + k) % 8 comes before c's in the
// order nearest first, the lower slot first on a tie: lanes (c + k) % 8 above c compare with <,
// the ones below (c >= 8 - k) with <=. A NaN key (a child not entered) is before none and has
// none before it.
template <int k>
[[gnu::target("avx2"), gnu::always_inline]] inline void count_nearer_avx2(__m256i& rank,
                                                                          const __m256& key) {
  const __m256i rotate = _mm256_setr_epi32(k % 8, (1 + k) % 8, (2 + k) % 8, (3 + k) % 8,
                                           (4 + k) % 8, (5 + k) % 8, (6 + k) % 8, (7 + k) % 8);
  const __m256 other = _mm256_permutevar8x32_ps(key, rotate);
  const __m256 before =
      _mm256_blend_ps(_mm256_cmp_ps(other, key, _CMP_LT_OQ), _mm256_cmp_ps(other, key, _CMP_LE_OQ),
                      (0xff << (8 - k)) & 0xff);
  rank = _mm256_sub_epi32(rank, _mm256_castps_si256(before));
}

// push_hits_nearest_first_avx2 for three children or more: each child's place is its rank, the
// count of children before it (seven rotations, compares and adds); all eight are stored whether
// entered or not (those not entered, and the nearest, above the new top), so that nothing
// branches on the hits or their distances.
[[gnu::target("avx2"), gnu::flatten]] inline WideBvhPending push_ranked_hits_avx2(
    const BvhWideNode& node, const float entry[kWideChildren], unsigned hits, WideBvhPending* stack,
    int& size) {
  const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256i hit = _mm256_cmpeq_epi32(
      _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(hits)), lane_bit), lane_bit);
  const __m256i entry_bits = _mm256_load_si256(reinterpret_cast<const __m256i*>(entry));
  // All ones (a NaN) where not entered.
  const __m256 key = _mm256_castsi256_ps(
      _mm256_or_si256(entry_bits, _mm256_xor_si256(hit, _mm256_set1_epi32(-1))));
  __m256i rank = _mm256_setzero_si256();
  count_nearer_avx2<1>(rank, key);
  count_nearer_avx2<2>(rank, key);
  count_nearer_avx2<3>(rank, key);
  count_nearer_avx2<4>(rank, key);
  count_nearer_avx2<5>(rank, key);
  count_nearer_avx2<6>(rank, key);
  count_nearer_avx2<7>(rank, key);
  // Rank r of the n entered goes to slot size + n - 1 - r (the nearest, r = 0, just above the
  // new top, where it is read back), the others to size + n (hit is -1 where entered).
  const int n = std::popcount(hits);
  const __m256i slot = _mm256_add_epi32(_mm256_sub_epi32(_mm256_set1_epi32(size + n), rank), hit);
  alignas(32) std::int32_t offset[kWideChildren];
  _mm256_store_si256(reinterpret_cast<__m256i*>(offset),
                     _mm256_slli_epi32(slot, 4));  // sizeof(WideBvhPending)
  // The pending records, lanes c and c + 4 in one vector: {child, count, entry, 0}.
  const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.child));
  const __m256i count = _mm256_load_si256(reinterpret_cast<const __m256i*>(node.count));
  const __m256i zero = _mm256_setzero_si256();
  const __m256i child_count_lo = _mm256_unpacklo_epi32(child, count);
  const __m256i child_count_hi = _mm256_unpackhi_epi32(child, count);
  const __m256i entry_lo = _mm256_unpacklo_epi32(entry_bits, zero);
  const __m256i entry_hi = _mm256_unpackhi_epi32(entry_bits, zero);
  const __m256i record[4] = {_mm256_unpacklo_epi64(child_count_lo, entry_lo),
                             _mm256_unpackhi_epi64(child_count_lo, entry_lo),
                             _mm256_unpacklo_epi64(child_count_hi, entry_hi),
                             _mm256_unpackhi_epi64(child_count_hi, entry_hi)};
  auto* const base = reinterpret_cast<char*>(stack);
#pragma GCC unroll 4
  for (int c = 0; c < 4; ++c) {
    _mm_store_si128(reinterpret_cast<__m128i*>(base + offset[c]),
                    _mm256_castsi256_si128(record[c]));
    _mm_store_si128(reinterpret_cast<__m128i*>(base + offset[c + 4]),
                    _mm256_extracti128_si256(record[c], 1));
  }
  size += n - 1;
  return stack[size];
}

// The children of `node` in `hits` (at least two; one needs no order), entry distances in
// `entry` (not NaN, not -0: the box test's max with +0): returns the nearest (the lowest slot on
// a tie) and pushes the others onto `stack` above `size`, the nearer ones on top: the insertion
// sort's order exactly. Two children, most often, take one comparison and selections by masks;
// more take push_ranked_hits_avx2. `stack` needs kWideBvhStackSlack slots past the traversal's
// deepest.
[[gnu::target("avx2"), gnu::flatten]] inline WideBvhPending push_hits_nearest_first_avx2(
    const BvhWideNode& node, const float entry[kWideChildren], unsigned hits, WideBvhPending* stack,
    int& size) {
  const unsigned rest = hits & (hits - 1);
  if ((rest & (rest - 1)) != 0) return push_ranked_hits_avx2(node, entry, hits, stack, size);
  const int a = std::countr_zero(hits), b = std::countr_zero(rest);
  const int b_nearer = -static_cast<int>(entry[b] < entry[a]);  // a on a tie
  const int near = a ^ ((a ^ b) & b_nearer), far = a ^ b ^ near;
  stack[size++] = {node.child[far], node.count[far], entry[far]};
  return {node.child[near], node.count[near], entry[near]};
}
#endif

}  // namespace tessera
