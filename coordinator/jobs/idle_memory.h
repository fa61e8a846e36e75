// Gives memory back to the system once the coordinator has had no unfinished job for a while:
// finished jobs' frame buffers kept for the next job (common/render/mapping_pool.h, renewed
// while jobs run however long they take) and the heap freed since (malloc_trim). Not while
// jobs run: a trim after each finished job also
// released the freed result buffers the next job's results were about to reuse, and the io
// thread faulted them in again (about 10,000 page faults a 2048x2048 job, docs/SCALING.md).
// Buffers of 1 MB and more are mapped and go back when freed anyway (main.cpp).
#pragma once

#include <chrono>

#include "common/render/mapping_pool.h"

namespace tessera {

class IdleMemory {
 public:
  using Clock = std::chrono::steady_clock;
  // By default as long after the last job as the pool keeps frame buffers.
  explicit IdleMemory(Clock::duration after = MappingPoolLimits{}.idle,
                      MappingPool& pool = MappingPool::shared())
      : after_(after), pool_(pool) {}
  // On the io thread's tick. Returns true when it trimmed the heap: once, `after` the last
  // tick with unfinished jobs.
  bool tick(bool jobs_unfinished, Clock::time_point now);

 private:
  Clock::duration after_;
  MappingPool& pool_;
  Clock::time_point busy_{};
  bool trimmed_ = true;  // nothing freed yet
};

}  // namespace tessera
