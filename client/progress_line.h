// tessera-submit's progress: on a terminal one line redrawn in place (a bar, the level, the pass,
// the time left); otherwise a plain line whenever the level, the pass or the state changes, so
// logs stay short.
#pragma once

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace tessera {

class ProgressLine {
 public:
  ProgressLine(std::FILE* out, bool terminal) : out_(out), terminal_(terminal) {}
  // A job's status (GET /api/jobs/{id}): state, level, levels, pass, passes, percent,
  // elapsed_seconds, eta_seconds (null until the coordinator can tell).
  void show(const nlohmann::json& job);
  // Ends the redrawn line.
  void finish();

 private:
  std::FILE* out_;
  bool terminal_;
  std::string last_plain_;  // the last plain line's level, pass and state
  bool drawn_ = false;
};

// "level 7/10, pass 1/2" (a direct render without levels: "pass 1/2").
std::string stage_text(const nlohmann::json& job);
// "12.3 s", "4 min 5 s", or "—" for an unknown time (null).
std::string seconds_text(const nlohmann::json& seconds);

}  // namespace tessera
