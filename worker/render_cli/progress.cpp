#include "worker/render_cli/progress.h"

#include <unistd.h>

#include <cstdio>

namespace tessera {

TerminalProgress::TerminalProgress()
    : enabled_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {}

void TerminalProgress::update(long long done, long long total) {
  if (!enabled_ || total <= 0) return;
  const int percent = static_cast<int>(100 * done / total);
  const std::lock_guard lock(mutex_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double left =
      done > 0 ? elapsed * static_cast<double>(total - done) / static_cast<double>(done) : 0;
  std::fprintf(stderr, "\rrendering %3d%%  %.1f s elapsed, ~%.1f s left   ", percent, elapsed,
               left);
  std::fflush(stderr);
}

void TerminalProgress::finish() {
  if (enabled_) std::fprintf(stderr, "\r%60s\r", "");
}

}  // namespace tessera
