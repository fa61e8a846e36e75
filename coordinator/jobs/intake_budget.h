// What one heavy request (POST /api/jobs, POST /api/predict) may spend off the io thread: a
// wall deadline (--max-intake-seconds), checked between the stages of intake and handed to
// the loader and the probe. Every limit is reported the same way: over_budget naming the limit
// and its value, refused as unprocessable (too large for a limit on bytes).
#pragma once

#include <chrono>
#include <string>

#include "coordinator/jobs/api_error.h"

namespace tessera {

struct IntakeBudget {
  using Clock = std::chrono::steady_clock;
  Clock::time_point deadline = Clock::time_point::max();
  double seconds = 0;  // the limit the deadline came from, for the message

  static IntakeBudget starting_now(double seconds) {
    return {Clock::now() +
                std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)),
            seconds};
  }
  // Throws the over-budget error once the deadline has passed; `stage` says where.
  void check(const std::string& stage) const {
    if (Clock::now() >= deadline) throw over_time(stage);
  }
  ApiError over_time(const std::string& stage) const {
    return ApiError(Refusal::unprocessable, "over_budget",
                    "the request took longer than --max-intake-seconds " + format_seconds() +
                        " (at " + stage + ")",
                    {{"limit", "max_intake_seconds"}, {"value", seconds}});
  }

 private:
  std::string format_seconds() const {
    std::string s = std::to_string(seconds);
    s.erase(s.find_last_not_of('0') + 1);
    if (s.ends_with('.')) s.pop_back();
    return s;
  }
};

}  // namespace tessera
