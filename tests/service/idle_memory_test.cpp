#include "coordinator/jobs/idle_memory.h"

#include <gtest/gtest.h>

namespace tessera {
namespace {

using namespace std::chrono_literals;

// The heap is trimmed once the coordinator has had no unfinished job for the idle time, never
// while one runs (a trim then faulted the next results' buffers in again), and only once.
TEST(IdleMemory, TrimsOnceAfterTheLastJobNeverWhileOneRuns) {
  IdleMemory memory(5s);
  const auto t = IdleMemory::Clock::now();
  EXPECT_FALSE(memory.tick(false, t));  // nothing ran yet
  EXPECT_FALSE(memory.tick(true, t + 1s));
  EXPECT_FALSE(memory.tick(true, t + 10s));
  EXPECT_FALSE(memory.tick(false, t + 14s));
  EXPECT_TRUE(memory.tick(false, t + 15s));
  EXPECT_FALSE(memory.tick(false, t + 16s));
  EXPECT_FALSE(memory.tick(true, t + 17s));
  EXPECT_FALSE(memory.tick(false, t + 20s));
  EXPECT_TRUE(memory.tick(false, t + 22s));
}

#if defined(__linux__)
// A finished job's frame buffer stays in the pool while jobs run, however long, and goes back
// the idle time after the last one.
TEST(IdleMemory, KeepsPooledBuffersWhileJobsRunAndReleasesThemAfter) {
  constexpr std::size_t kBytes = std::size_t{4} << 20;
  MappingPool pool({.max_bytes = 4 * kBytes, .idle = 5s});
  IdleMemory memory(5s, pool);
  const auto t = IdleMemory::Clock::now();
  pool.give(pool.take(kBytes, t), kBytes, t);
  for (auto s = 1s; s <= 20s; s += 1s) memory.tick(true, t + s);
  memory.tick(false, t + 24s);
  EXPECT_EQ(pool.kept_bytes(), kBytes);
  memory.tick(false, t + 26s);
  EXPECT_EQ(pool.kept_bytes(), 0u);
}
#endif

}  // namespace
}  // namespace tessera
