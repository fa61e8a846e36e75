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

}  // namespace
}  // namespace tessera
