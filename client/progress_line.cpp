#include "client/progress_line.h"

#include <algorithm>
#include <cmath>

namespace tessera {

std::string stage_text(const nlohmann::json& job) {
  const int levels = job.value("levels", 0);
  // Passes count from 1 for people; the coordinator counts them from 0.
  const std::string pass = "pass " + std::to_string(job.value("pass", 0) + 1) + "/" +
                           std::to_string(job.value("passes", 1));
  if (levels == 0) return pass;
  return "level " + std::to_string(job.value("level", 0)) + "/" + std::to_string(levels) + ", " +
         pass;
}

std::string seconds_text(const nlohmann::json& seconds) {
  if (!seconds.is_number()) return "—";
  const double s = std::max(0.0, seconds.get<double>());
  char text[32];
  if (s < 60)
    std::snprintf(text, sizeof text, "%.1f s", s);
  else
    std::snprintf(text, sizeof text, "%d min %d s", static_cast<int>(s / 60),
                  static_cast<int>(std::fmod(s, 60)));
  return text;
}

void ProgressLine::show(const nlohmann::json& job) {
  const std::string state = job.value("state", "?");
  const double percent = job.value("percent", 0.0);
  if (!terminal_) {
    const std::string key = state + " " + stage_text(job);
    if (key == last_plain_) return;
    last_plain_ = key;
    std::fprintf(out_, "%s: %s, %.0f%%, %s elapsed, %s left\n", state.c_str(),
                 stage_text(job).c_str(), percent,
                 seconds_text(job.value("elapsed_seconds", nlohmann::json())).c_str(),
                 seconds_text(job.value("eta_seconds", nlohmann::json())).c_str());
    std::fflush(out_);
    return;
  }
  constexpr int kBar = 24;
  const int filled = std::clamp(static_cast<int>(percent / 100 * kBar), 0, kBar);
  const std::string bar = std::string(filled, '#') + std::string(kBar - filled, '.');
  std::fprintf(out_, "\r[%s] %3.0f%%  %s  %s left   ", bar.c_str(), percent,
               stage_text(job).c_str(),
               seconds_text(job.value("eta_seconds", nlohmann::json())).c_str());
  std::fflush(out_);
  drawn_ = true;
}

void ProgressLine::finish() {
  if (terminal_ && drawn_) std::fprintf(out_, "\n");
  drawn_ = false;
}

}  // namespace tessera
