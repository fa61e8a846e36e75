#include "common/render/mapping_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace tessera {
namespace {

#if defined(__linux__)
using namespace std::chrono_literals;

constexpr std::size_t kMB = std::size_t{1} << 20;

bool all_zero(const void* p, std::size_t bytes) {
  const auto* b = static_cast<const unsigned char*>(p);
  return std::all_of(b, b + bytes, [](unsigned char c) { return c == 0; });
}

// A freed mapping is the next one taken, of that size or smaller, and comes back all zeros.
TEST(MappingPool, HandsAFreedMappingToTheNextTakeZeroed) {
  MappingPool pool({.max_bytes = 64 * kMB, .idle = 10s});
  const auto now = MappingPool::Clock::now();
  void* first = pool.take(8 * kMB, now);
  std::memset(first, 0x5a, 8 * kMB);
  pool.give(first, 8 * kMB, now);
  EXPECT_EQ(pool.kept_bytes(), 8 * kMB);
  void* again = pool.take(6 * kMB, now + 1s);
  EXPECT_EQ(again, first);
  EXPECT_TRUE(all_zero(again, 6 * kMB));
  EXPECT_EQ(pool.kept_bytes(), 0u);
  pool.give(again, 6 * kMB, now + 1s);
}

// The smallest mapping that holds the request is taken: the larger one stays for a larger job.
TEST(MappingPool, TakesTheSmallestKeptMappingThatFits) {
  MappingPool pool({.max_bytes = 64 * kMB, .idle = 10s});
  const auto now = MappingPool::Clock::now();
  void* large = pool.take(16 * kMB, now);
  void* small = pool.take(4 * kMB, now);
  pool.give(large, 16 * kMB, now);
  pool.give(small, 4 * kMB, now);
  EXPECT_EQ(pool.take(3 * kMB, now), small);
  EXPECT_EQ(pool.kept_bytes(), 16 * kMB);
  void* other = pool.take(20 * kMB, now);  // larger than anything kept: a new mapping
  EXPECT_NE(other, large);
  EXPECT_TRUE(all_zero(other, 20 * kMB));
  pool.give(other, 20 * kMB, now);
  pool.give(small, 3 * kMB, now);
}

// At most max_bytes are kept, the oldest unmapped first; a mapping larger than that is not kept.
TEST(MappingPool, KeepsAtMostItsByteCapTheNewestFirst) {
  MappingPool pool({.max_bytes = 20 * kMB, .idle = 10s});
  const auto now = MappingPool::Clock::now();
  void* a = pool.take(8 * kMB, now);
  void* b = pool.take(8 * kMB, now);
  void* c = pool.take(8 * kMB, now);
  void* huge = pool.take(24 * kMB, now);
  pool.give(a, 8 * kMB, now);
  pool.give(b, 8 * kMB, now + 1s);
  pool.give(c, 8 * kMB, now + 2s);
  EXPECT_EQ(pool.kept_bytes(), 16 * kMB);
  pool.give(huge, 24 * kMB, now + 3s);
  EXPECT_EQ(pool.kept_bytes(), 16 * kMB);
  const void* first = pool.take(8 * kMB, now + 4s);
  const void* second = pool.take(8 * kMB, now + 4s);
  EXPECT_TRUE((first == b && second == c) || (first == c && second == b));
  pool.give(const_cast<void*>(first), 8 * kMB, now + 4s);
  pool.give(const_cast<void*>(second), 8 * kMB, now + 4s);
}

// What nobody took within the idle limit goes back to the system.
TEST(MappingPool, ReleasesWhatStayedIdle) {
  MappingPool pool({.max_bytes = 64 * kMB, .idle = 5s});
  const auto now = MappingPool::Clock::now();
  pool.give(pool.take(4 * kMB, now), 4 * kMB, now);
  pool.give(pool.take(4 * kMB, now + 3s), 4 * kMB, now + 3s);  // the same mapping, kept anew
  pool.release_idle(now + 7s);
  EXPECT_EQ(pool.kept_bytes(), 4 * kMB);
  pool.release_idle(now + 8s);
  EXPECT_EQ(pool.kept_bytes(), 0u);
}

// A renewed mapping stays the idle limit from its renewal, not from its give: a finished job's
// buffer waits through a running job longer than the limit for the job after it.
TEST(MappingPool, KeepsARenewedMappingTheIdleLimitFromItsRenewal) {
  MappingPool pool({.max_bytes = 64 * kMB, .idle = 5s});
  const auto now = MappingPool::Clock::now();
  void* mapping = pool.take(4 * kMB, now);
  pool.give(mapping, 4 * kMB, now);
  pool.renew(now + 4s);
  pool.renew(now + 8s);
  pool.release_idle(now + 12s);
  EXPECT_EQ(pool.kept_bytes(), 4 * kMB);
  EXPECT_EQ(pool.take(4 * kMB, now + 12s), mapping);
  pool.give(mapping, 4 * kMB, now + 12s);
  pool.release_idle(now + 17s);
  EXPECT_EQ(pool.kept_bytes(), 0u);
}
#endif

}  // namespace
}  // namespace tessera
