// Large zeroed mappings (ZeroedAllocator's, 2 MB and more: a coordinator job's frame buffer)
// kept for a while after they are freed and handed to the next buffer that asks, zero-filled
// again with memset. On the virtual machines measured here a new mapping's first writes cost
// 86-154 ms for 56 MB (the kernel, and the host below it, making and zeroing the pages: a
// quarter of the coordinator's io thread while it merged a 2048x2048 job), a memset of the
// same pages still mapped 1-1.6 ms (docs/SCALING.md).
//
// Bounded both ways, so that the memory still goes back to the system: at most max_bytes are
// kept (the oldest go first), and a mapping kept longer than `idle` is unmapped at the next
// call. The coordinator renews the kept mappings on its tick while jobs run and lets them go
// `idle` after the last one (idle_memory.h). Linux only; elsewhere the allocator uses calloc.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <vector>

namespace tessera {

struct MappingPoolLimits {
  // One 3840x2160 job's frame buffer (116 MB), or two of 2048x2048 (56 MB each): while a
  // finished job's buffer is still encoded the next job starts in another, so the one after
  // it takes the first back.
  std::size_t max_bytes = std::size_t{128} << 20;
  std::chrono::milliseconds idle{5000};
};

class MappingPool {
 public:
  using Clock = std::chrono::steady_clock;
  explicit MappingPool(MappingPoolLimits limits = {}) : limits_(limits) {}
  ~MappingPool();
  MappingPool(const MappingPool&) = delete;
  MappingPool& operator=(const MappingPool&) = delete;

  // The one ZeroedAllocator uses.
  static MappingPool& shared();

  // `bytes` of zeros: the smallest kept mapping that holds them (its tail beyond them
  // unmapped), else a new one advised to use transparent huge pages. Throws std::bad_alloc.
  void* take(std::size_t bytes, Clock::time_point now = Clock::now());
  // A mapping from take(), of the same `bytes`, kept for the next take() or unmapped.
  void give(void* mapping, std::size_t bytes, Clock::time_point now = Clock::now());
  // Unmaps what was kept longer than the idle limit.
  void release_idle(Clock::time_point now = Clock::now());
  // Starts every kept mapping's idle time again at `now`. A finished job's buffer is taken by
  // the job after next (the next one starts while it is still encoded), so it waits a whole
  // job; kept only `idle` from its give, it was unmapped during jobs longer than that, and
  // the job after next zeroed new pages again (docs/SCALING.md).
  void renew(Clock::time_point now = Clock::now());
  std::size_t kept_bytes() const;

 private:
  struct Kept {
    void* mapping;
    std::size_t bytes;
    Clock::time_point since;
  };
  void release_idle_locked(Clock::time_point now);

  MappingPoolLimits limits_;
  mutable std::mutex mutex_;
  std::vector<Kept> kept_;  // oldest first
  std::size_t kept_bytes_ = 0;
};

}  // namespace tessera
