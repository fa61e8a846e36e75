// How the coordinator corrects its cost probe's predictions (common/render/time_prediction.h)
// by what finished jobs took.
#pragma once

#include <cstddef>
#include <deque>

namespace tessera {

// Learns what the probe cannot see from the jobs that finished alone, in two parts measured
// separately on each job:
//  - speed: the workers' render seconds per thread against the probe's prediction (their
//    speed against the probing coordinator's, how their threads scale);
//  - overhead: the wall seconds beyond the workers' render seconds per thread (preparing the
//    scene on each worker, round trips, the last units' tail), nearly the same for every job.
// Each is the median of the last kWindow jobs, so that one odd job moves neither; a
// prediction is overhead + speed × uncalibrated.
class PredictionCalibration {
 public:
  static constexpr std::size_t kWindow = 9;

  double factor() const { return median(speeds_, 1); }
  double overhead_seconds() const { return median(overheads_, 0); }
  double apply(double uncalibrated_seconds) const {
    return overhead_seconds() + factor() * uncalibrated_seconds;
  }
  // A job that ran alone: its uncalibrated prediction, its workers' render seconds divided by
  // the threads it was predicted for, and the wall seconds it took.
  void observe(double uncalibrated_seconds, double render_seconds_per_thread,
               double actual_seconds);

 private:
  static double median(const std::deque<double>& values, double none);
  std::deque<double> speeds_, overheads_;
};

}  // namespace tessera
