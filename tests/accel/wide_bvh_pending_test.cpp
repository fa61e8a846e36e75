// The AVX2 node step of the nearest-first mesh traversal (wide_bvh_pending.h) orders the
// children a ray enters as the insertion sort of the other kernels' traversal does (nearest
// first, the lower slot on a tie), so that every kernel visits the same nodes and leaves in the
// same order (the counters of wide_box_kernels_test.cpp). Checked here against that sort on
// random nodes whose entries tie often, with every number of children entered.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "common/accel/wide_box_kernel.h"
#include "common/accel/wide_bvh_pending.h"

namespace tessera {
namespace {

#if defined(__SSE2__)
// The children in `hits`, nearest first, the lower slot first on a tie.
std::vector<int> insertion_sorted(const float entry[kWideChildren], unsigned hits) {
  std::vector<int> order;
  for (unsigned rest = hits; rest != 0; rest &= rest - 1) {
    const int c = std::countr_zero(rest);
    auto at = order.end();
    while (at != order.begin() && entry[*(at - 1)] > entry[c]) --at;
    order.insert(at, c);
  }
  return order;
}

using PushHits = WideBvhPending (*)(const BvhWideNode&, const float*, unsigned, WideBvhPending*,
                                    int&);

// The AVX2 step as the AVX-512VL kernel compiles it (wide_box_kernel.h): inlined into a function
// for its target.
[[gnu::target(TESSERA_AVX512VL_TARGET), gnu::flatten]] WideBvhPending push_hits_avx512vl(
    const BvhWideNode& node, const float* entry, unsigned hits, WideBvhPending* stack, int& size) {
  return push_hits_nearest_first_avx2(node, entry, hits, stack, size);
}

void expect_insertion_sort_order(PushHits push_hits) {
  std::mt19937_64 rng(12);
  // Few distinct values, so that ties are common; the box test's entries are >= +0, not NaN.
  const std::vector<float> values = {0.0f, 1e-30f, 0.5f, 0.5000001f, 1.0f, 2.0f, 1e30f, INFINITY};
  int ties = 0;
  for (int i = 0; i < 200000; ++i) {
    BvhWideNode node;
    alignas(32) float entry[kWideChildren];
    for (int c = 0; c < kWideChildren; ++c) {
      node.child[c] = static_cast<std::uint32_t>(rng());
      node.count[c] = static_cast<std::uint32_t>(rng() % 17);
      entry[c] = values[rng() % (i % 2 == 0 ? 3 : values.size())];
    }
    unsigned hits = static_cast<unsigned>(rng() % 256);
    if (std::popcount(hits) < 2) hits |= 0x81;  // the step's callers handle one child apart
    const std::vector<int> order = insertion_sorted(entry, hits);
    for (std::size_t k = 1; k < order.size(); ++k) ties += entry[order[k - 1]] == entry[order[k]];

    const int below = static_cast<int>(rng() % 20);
    std::vector<WideBvhPending> stack(static_cast<std::size_t>(below + kWideBvhStackSlack));
    for (int s = 0; s < below; ++s) stack[static_cast<std::size_t>(s)] = {7u, 3u, 1.5f};
    int size = below;
    const WideBvhPending nearest = push_hits(node, entry, hits, stack.data(), size);

    ASSERT_EQ(size, below + static_cast<int>(order.size()) - 1) << "case " << i;
    const auto expect = [&](const WideBvhPending& got, int c) {
      EXPECT_EQ(got.index, node.child[c]) << "case " << i << " child " << c;
      EXPECT_EQ(got.count, node.count[c]) << "case " << i << " child " << c;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(got.entry), std::bit_cast<std::uint32_t>(entry[c]))
          << "case " << i << " child " << c;
    };
    expect(nearest, order[0]);
    // The farthest deepest, the second nearest on top.
    for (std::size_t k = 1; k < order.size(); ++k)
      expect(stack[static_cast<std::size_t>(size) - k], order[k]);
    for (int s = 0; s < below; ++s) {
      ASSERT_EQ(stack[static_cast<std::size_t>(s)].index, 7u) << "case " << i;
      ASSERT_EQ(stack[static_cast<std::size_t>(s)].count, 3u) << "case " << i;
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(ties, 100000);
}

TEST(WideBvhPending, TheAvx2StepOrdersChildrenAsTheInsertionSort) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx2)) GTEST_SKIP() << "no AVX2";
  expect_insertion_sort_order(push_hits_nearest_first_avx2);
}

TEST(WideBvhPending, TheAvx512VlStepOrdersChildrenAsTheInsertionSort) {
  if (!wide_box_kernel_supported(WideBoxKernel::Avx512Vl))
    GTEST_SKIP() << "no AVX-512F, VL, DQ and BW on this CPU";
  expect_insertion_sort_order(push_hits_avx512vl);
}
#endif

}  // namespace
}  // namespace tessera
