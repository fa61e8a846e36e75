// The CPU time of the calling thread, as a std::chrono clock. A measurement timed by it leaves
// out the time the thread was not running: preempted by other processes on a shared machine,
// or asleep. The coordinator's cost probe (common/render/time_prediction.h) uses it, so a probe
// that another process preempts halfway does not predict a job several times too slow.
#pragma once

#include <chrono>
#include <ctime>

namespace tessera {

struct ThreadCpuClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<ThreadCpuClock>;
  static constexpr bool is_steady = true;

  static time_point now() noexcept {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return time_point(std::chrono::seconds(now.tv_sec) + std::chrono::nanoseconds(now.tv_nsec));
  }
};

}  // namespace tessera
