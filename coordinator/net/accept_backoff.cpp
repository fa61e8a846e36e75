#include "coordinator/net/accept_backoff.h"

#include <algorithm>

namespace tessera {

AcceptBackoff::AcceptBackoff(std::chrono::milliseconds first, std::chrono::milliseconds longest)
    : first_(first), longest_(std::max(first, longest)), next_(first) {}

std::chrono::milliseconds AcceptBackoff::after_failure() {
  const auto delay = next_;
  next_ = std::min(next_ * 2, longest_);
  return delay;
}

}  // namespace tessera
