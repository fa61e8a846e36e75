// Progress on a terminal: a single self-rewriting line on stderr, only when stderr is a tty.
#pragma once

#include <chrono>
#include <mutex>

namespace tessera {

class TerminalProgress {
 public:
  TerminalProgress();
  void update(long long done, long long total);
  void finish();

 private:
  bool enabled_;
  std::mutex mutex_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace tessera
