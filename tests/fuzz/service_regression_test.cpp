// Replays the regression corpus of the coordinator's fuzz targets (tests/fuzz/regressions/
// job_request/ and worker_frames/) through their own checks, in every build with the
// coordinator.
#include <gtest/gtest.h>

#include "tests/fuzz/replay.h"
#include "tests/fuzz/service_fuzz_checks.h"

namespace tessera::fuzz {
namespace {

TEST(FuzzRegressions, JobRequest) { replay("job_request", check_job_request_input); }
TEST(FuzzRegressions, WorkerFrames) { replay("worker_frames", check_worker_frames_input); }

}  // namespace
}  // namespace tessera::fuzz
