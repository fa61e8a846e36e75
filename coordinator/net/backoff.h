// Delays between retries of an operation that fails for a reason time may cure (accept at the
// descriptor limit: EMFILE, ENFILE, ENOBUFS): doubling from `first` up to `cap`, back to
// `first` after a success. A shortage then costs a few wake-ups a second, not a spinning core.
#pragma once

#include <algorithm>
#include <chrono>

namespace tessera {

class Backoff {
 public:
  explicit Backoff(std::chrono::milliseconds first = std::chrono::milliseconds(50),
                   std::chrono::milliseconds cap = std::chrono::seconds(1))
      : first_(first), cap_(cap), next_(first) {}

  // The delay before the next try; each failure doubles the one after.
  std::chrono::milliseconds next() {
    const auto delay = next_;
    next_ = std::min(cap_, next_ * 2);
    return delay;
  }
  void reset() { next_ = first_; }

 private:
  std::chrono::milliseconds first_, cap_, next_;
};

}  // namespace tessera
