// The pause before accepting again after an accept error. At the descriptor limit (EMFILE) the
// listening socket stays readable and every accept fails at once: retried immediately, the loop
// spins on the io thread and floods the log. A delay that doubles from `first` to `longest`
// leaves the thread to the connections already open, whose closes free descriptors; a success
// starts over from `first`.
#pragma once

#include <chrono>

namespace tessera {

class AcceptBackoff {
 public:
  explicit AcceptBackoff(std::chrono::milliseconds first = std::chrono::milliseconds(50),
                         std::chrono::milliseconds longest = std::chrono::milliseconds(1000));
  // After a failed accept: how long to wait before the next one.
  std::chrono::milliseconds after_failure();
  // After a successful accept.
  void reset() { next_ = first_; }

 private:
  std::chrono::milliseconds first_, longest_, next_;
};

}  // namespace tessera
