#include "coordinator/scheduler/prediction_calibration.h"

#include <algorithm>
#include <vector>

namespace tessera {

void PredictionCalibration::observe(double uncalibrated_seconds, double render_seconds_per_thread,
                                    double actual_seconds) {
  if (!(uncalibrated_seconds > 0) || !(render_seconds_per_thread > 0) || !(actual_seconds > 0))
    return;
  speeds_.push_back(render_seconds_per_thread / uncalibrated_seconds);
  overheads_.push_back(std::max(0.0, actual_seconds - render_seconds_per_thread));
  if (speeds_.size() > kWindow) speeds_.pop_front();
  if (overheads_.size() > kWindow) overheads_.pop_front();
}

double PredictionCalibration::median(const std::deque<double>& values, double none) {
  if (values.empty()) return none;
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  return n % 2 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
}

}  // namespace tessera
