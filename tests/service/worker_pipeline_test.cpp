// The units a worker holds: its threads plus a prefetch on loopback, and enough more to cover
// the round trip when the network is slow (synthetic timings).
#include "coordinator/scheduler/worker_pipeline.h"

#include <gtest/gtest.h>

#include "common/progressive/plan.h"

namespace tessera {
namespace {

TEST(WorkerPipeline, BeforeAnyResultThreadsPlusPrefetch) {
  EXPECT_EQ(WorkerPipeline(1).slots(), 2);
  EXPECT_EQ(WorkerPipeline(4).slots(), 6);
  EXPECT_EQ(WorkerPipeline(4).round_trip_seconds(), 0);
}

TEST(WorkerPipeline, TheHandshakeRoundTripDeepensThePipelineBeforeAnyResult) {
  // 20 ms to the worker, units sized to take kUnitTargetSeconds (20 ms): two round trips are
  // two more units a thread.
  WorkerPipeline p(2, 0.020);
  EXPECT_DOUBLE_EQ(p.round_trip_seconds(), 0.020);
  EXPECT_EQ(p.slots(), 2 * 3 + 1);
  p.observe(0.030, 0.005);  // the first result replaces the target unit time...
  EXPECT_DOUBLE_EQ(p.unit_seconds(), 0.005);
  EXPECT_EQ(p.slots(), 2 * 9 + 1);
  p.observe(0.016, 0.005);  // ...and a shorter transit the handshake's round trip
  EXPECT_DOUBLE_EQ(p.round_trip_seconds(), 0.011);
}

TEST(WorkerPipeline, CoversTheRoundTripWithUnitsInTransit) {
  WorkerPipeline p(2);
  p.observe(0.030, 0.010);  // 20 ms in transit, 10 ms a unit: four more units per thread
  EXPECT_DOUBLE_EQ(p.round_trip_seconds(), 0.020);
  EXPECT_DOUBLE_EQ(p.unit_seconds(), 0.010);
  EXPECT_EQ(p.slots(), 2 * 5 + 1);
}

TEST(WorkerPipeline, TheRoundTripIsTheSmallestTransitSeen) {
  WorkerPipeline p(1);
  p.observe(0.050, 0.010);  // waited 20 ms in the worker's queue
  p.observe(0.030, 0.010);
  p.observe(0.090, 0.010);
  EXPECT_DOUBLE_EQ(p.round_trip_seconds(), 0.020);
  EXPECT_EQ(p.slots(), 5 + 1);
}

TEST(WorkerPipeline, UnitTimeIsAMovingAverage) {
  WorkerPipeline p(1);
  p.observe(0.010, 0.010);
  p.observe(0.090, 0.090);
  EXPECT_DOUBLE_EQ(p.unit_seconds(), 0.010 + 0.125 * 0.080);
}

TEST(WorkerPipeline, ASmallUnitTeachesTheRoundTripButNotTheUnitTime) {
  // A fresh worker's first results are a coarse level's units of a few pixels: 0.2 ms each.
  // Learning from them would ask for 1 + 2 x 2 ms / 0.2 ms units a thread (capped at 16).
  WorkerPipeline p(1, 0.002);
  p.observe(0.0022, 0.0002, false);
  EXPECT_DOUBLE_EQ(p.round_trip_seconds(), 0.002);
  EXPECT_DOUBLE_EQ(p.unit_seconds(), kUnitTargetSeconds);
  EXPECT_EQ(p.slots(), 2 + 1);
  p.observe(0.022, 0.020, true);  // a full-sized unit does teach it
  EXPECT_DOUBLE_EQ(p.unit_seconds(), 0.020);
}

TEST(WorkerPipeline, AFastLinkAddsAtMostOneUnitAThread) {
  WorkerPipeline p(4);
  p.observe(0.0102, 0.0100);  // 0.2 ms round trip
  EXPECT_EQ(p.slots(), 5 + 2);
}

TEST(WorkerPipeline, SlowLinksAreBoundedPerThread) {
  WorkerPipeline p(2);
  p.observe(1.001, 0.001);  // a second's round trip for a millisecond's unit
  EXPECT_EQ(p.slots(), 2 * 16 + 1);
}

}  // namespace
}  // namespace tessera
