// Measures a sweep (bench/accuracy/sweep.h): the time of every variant (median of repeats)
// and its error against the reference, and the error after each progressive level.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/accuracy/sweep.h"
#include "common/image/image_metrics.h"

namespace tessera {

struct Measured {
  Variant variant;
  double seconds = 0;     // median render time
  double time_ratio = 1;  // to the cheapest variant of the whole sweep
  ImageError error;       // against the reference
  bool pareto = false;    // no other variant is both faster and closer
};

// One refinement level of the progressive sequence (docs/ARCHITECTURE.md, "The progressive plan"),
// at the base settings.
struct LevelRow {
  int level = 0;
  int block = 1;         // block side in pixels
  long long blocks = 0;  // blocks in the image at this size
  long long traced = 0;  // new anchors traced by this level
  double seconds = 0;    // time to trace them
  double cumulative_seconds = 0;
  ImageError error;  // of the preview after this level, against the reference
};

struct AccuracyReport {
  std::string scene_name;
  std::vector<std::string> effects;
  int width = 0, height = 0, threads = 0, repeats = 0;
  Variant reference;
  double reference_seconds = 0;
  std::vector<Measured> measured;
  std::vector<LevelRow> levels;
  std::vector<std::string> not_swept;
};

struct AccuracyOptions {
  RenderSettings base;  // size and seed
  int repeats = 3;
  int threads = 0;                                   // 0: all cores
  std::function<void(const std::string&)> progress;  // one line per step, may be empty
};

AccuracyReport measure_accuracy(const Scene& scene, const std::string& scene_name,
                                const AccuracyOptions& options);

// Marks the variants on the time/error Pareto front (exposed for tests).
void mark_pareto_front(std::vector<Measured>& measured);

}  // namespace tessera
