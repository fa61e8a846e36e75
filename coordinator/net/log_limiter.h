// At most one log line per interval about one kind of event (an accept error, a refused
// connection): a peer that repeats the event thousands of times a second must not turn the log
// into the resource it exhausts. Each line carries how many of the same event went unlogged
// since the previous one. One limiter per kind of event; single-threaded, like the io thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace tessera {

class LogLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  explicit LogLimiter(std::chrono::milliseconds interval = std::chrono::milliseconds(1000))
      : interval_(interval) {}

  // Records one event. Returns how many were suppressed since the last logged one when this
  // one may be logged, or nullopt when it must not.
  std::optional<std::uint64_t> allow(Clock::time_point now = Clock::now()) {
    if (logged_once_ && now - last_ < interval_) {
      ++suppressed_;
      return std::nullopt;
    }
    logged_once_ = true;
    last_ = now;
    const std::uint64_t suppressed = suppressed_;
    suppressed_ = 0;
    return suppressed;
  }

 private:
  std::chrono::milliseconds interval_;
  Clock::time_point last_;
  bool logged_once_ = false;
  std::uint64_t suppressed_ = 0;
};

// " (N more suppressed)" to end a line with, or nothing when none were.
inline std::string suppressed_note(std::uint64_t suppressed) {
  return suppressed ? " (" + std::to_string(suppressed) + " more suppressed)" : std::string();
}

}  // namespace tessera
