// The coordinator's correction of predicted render times by what finished jobs took.
#include "coordinator/scheduler/prediction_calibration.h"

#include <gtest/gtest.h>

namespace tessera {
namespace {

TEST(PredictionCalibration, CalibrationLearnsSpeedAndOverheadAsMediansOfRecentJobs) {
  PredictionCalibration c;
  EXPECT_EQ(c.apply(2.0), 2.0);  // nothing learnt yet
  // Predicted 1 s; the workers rendered 1.2 s a thread; the job took 1.5 s.
  c.observe(1.0, 1.2, 1.5);
  EXPECT_DOUBLE_EQ(c.factor(), 1.2);
  EXPECT_DOUBLE_EQ(c.overhead_seconds(), 0.3);
  EXPECT_DOUBLE_EQ(c.apply(10.0), 0.3 + 1.2 * 10.0);
  // The median of three: a job 4x slower counts as one value above, not by how far.
  c.observe(1.0, 1.4, 1.7);
  c.observe(1.0, 4.0, 9.0);
  EXPECT_DOUBLE_EQ(c.factor(), 1.4);
  EXPECT_NEAR(c.overhead_seconds(), 0.3, 1e-12);
  // An even count takes the mean of the middle two; a job faster than its render time per
  // thread (speculative duplicates) adds no negative overhead.
  c.observe(1.0, 1.0, 0.5);
  EXPECT_DOUBLE_EQ(c.factor(), (1.2 + 1.4) / 2);
  EXPECT_NEAR(c.overhead_seconds(), 0.3, 1e-12);
  c.observe(0.0, 1.0, 1.0);  // nothing to learn from an empty prediction
  EXPECT_DOUBLE_EQ(c.factor(), 1.3);
  // Only the last kWindow jobs count.
  for (std::size_t i = 0; i < PredictionCalibration::kWindow; ++i) c.observe(1.0, 2.0, 2.1);
  EXPECT_DOUBLE_EQ(c.factor(), 2.0);
  EXPECT_NEAR(c.overhead_seconds(), 0.1, 1e-12);
}

}  // namespace
}  // namespace tessera
