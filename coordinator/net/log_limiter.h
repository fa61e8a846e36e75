// One log line per interval about a repeated event (a failing accept, a refused connection),
// so a flood of thousands a second writes one line a second that says how many it stands for.
#pragma once

#include <chrono>
#include <optional>

namespace tessera {

class LogLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  explicit LogLimiter(Clock::duration interval = std::chrono::seconds(1)) : interval_(interval) {}

  // Counts one occurrence. When a line may be written now, returns how many occurrences were
  // not logged since the last line; otherwise nothing.
  std::optional<long long> admit(Clock::time_point now = Clock::now()) {
    if (logged_once_ && now - last_ < interval_) {
      ++suppressed_;
      return std::nullopt;
    }
    logged_once_ = true;
    last_ = now;
    const long long skipped = suppressed_;
    suppressed_ = 0;
    return skipped;
  }

 private:
  Clock::duration interval_;
  Clock::time_point last_{};
  bool logged_once_ = false;
  long long suppressed_ = 0;
};

}  // namespace tessera
