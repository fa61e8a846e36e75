#include "coordinator/scheduler/worker_pipeline.h"

#include <algorithm>
#include <cmath>

#include "common/progressive/plan.h"

namespace tessera {

namespace {

// Units beyond those covering the round trip, so that the next unit is already there when
// one ends.
int prefetch(int threads) { return std::max(1, threads / 2); }

// A bound on the units one thread may hold, so that a lost worker or a cancelled job throws
// away little work; at 16 a unit may take an eighth of the round trip and the pipeline still
// stays full.
constexpr int kMaxUnitsPerThread = 16;

// How many round trips the units in transit cover (see the header).
constexpr double kRoundTripsCovered = 2;

// Weight of the newest unit in the moving average of render time.
constexpr double kUnitTimeWeight = 0.125;

}  // namespace

WorkerPipeline::WorkerPipeline(int threads, double handshake_round_trip)
    : threads_(threads), unit_seconds_(kUnitTargetSeconds) {
  if (handshake_round_trip > 0) round_trip_ = handshake_round_trip;
}

void WorkerPipeline::observe(double elapsed, double render, bool full_sized) {
  const double transit = std::max(0.0, elapsed - render);
  round_trip_ = round_trip_ < 0 ? transit : std::min(round_trip_, transit);
  if (!full_sized) return;
  unit_seconds_ = observed_ ? unit_seconds_ + kUnitTimeWeight * (render - unit_seconds_) : render;
  observed_ = true;
}

double WorkerPipeline::round_trip_seconds() const { return std::max(0.0, round_trip_); }

int WorkerPipeline::slots() const {
  double per_thread = 1;  // the unit each thread renders
  if (round_trip_ > 0 && unit_seconds_ > 0)
    per_thread =
        std::min<double>(kMaxUnitsPerThread, 1 + kRoundTripsCovered * round_trip_ / unit_seconds_);
  return static_cast<int>(std::ceil(threads_ * per_thread)) + prefetch(threads_);
}

}  // namespace tessera
