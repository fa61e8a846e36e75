// The accept backoff and the log limiter of coordinator/net/: exact delays and counts.
#include <gtest/gtest.h>

#include "coordinator/net/backoff.h"
#include "coordinator/net/log_limiter.h"

namespace tessera {
namespace {

using std::chrono::milliseconds;

TEST(Backoff, DoublesFromTheFirstDelayToTheCapAndStartsOverAfterASuccess) {
  Backoff backoff(milliseconds(50), milliseconds(1000));
  std::vector<long long> delays;
  for (int i = 0; i < 7; ++i) delays.push_back(backoff.next().count());
  EXPECT_EQ(delays, (std::vector<long long>{50, 100, 200, 400, 800, 1000, 1000}));
  backoff.reset();
  EXPECT_EQ(backoff.next(), milliseconds(50));
}

TEST(LogLimiter, OneLineAnIntervalWithTheCountSuppressedMeanwhile) {
  LogLimiter limiter(milliseconds(1000));
  const LogLimiter::Clock::time_point t0{};
  EXPECT_EQ(limiter.allow(t0), 0u);
  for (int i = 1; i <= 5; ++i) EXPECT_FALSE(limiter.allow(t0 + milliseconds(i * 100)));
  EXPECT_EQ(limiter.allow(t0 + milliseconds(1000)), 5u);
  EXPECT_FALSE(limiter.allow(t0 + milliseconds(1999)));
  EXPECT_EQ(limiter.allow(t0 + milliseconds(2000)), 1u);
  EXPECT_EQ(suppressed_note(0), "");
  EXPECT_EQ(suppressed_note(5), " (5 more suppressed)");
}

}  // namespace
}  // namespace tessera
