// next_up / next_down and step_away (common/math/float_error.h) against std::nextafter, bit for
// bit.
#include "common/math/float_error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

using Limits = std::numeric_limits<double>;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_as_nextafter(double x) {
  EXPECT_EQ(bits(next_up(x)), bits(std::nextafter(x, Limits::infinity()))) << x;
  EXPECT_EQ(bits(next_down(x)), bits(std::nextafter(x, -Limits::infinity()))) << x;
}

TEST(NextUpDown, AgreeWithNextafterOnEveryKindOfDouble) {
  const std::vector<double> edges = {0.0,
                                     -0.0,
                                     1.0,
                                     -1.0,
                                     Limits::denorm_min(),
                                     -Limits::denorm_min(),
                                     Limits::min(),
                                     -Limits::min(),
                                     std::nextafter(Limits::min(), 0.0),
                                     Limits::max(),
                                     -Limits::max(),
                                     Limits::infinity(),
                                     -Limits::infinity(),
                                     1e5,
                                     -1e-300};
  for (double x : edges) expect_as_nextafter(x);
  EXPECT_TRUE(std::isnan(next_up(Limits::quiet_NaN())));
  EXPECT_TRUE(std::isnan(next_down(Limits::quiet_NaN())));

  // Random bit patterns cover every exponent, both signs and subnormals alike.
  std::mt19937_64 random(7);
  for (int i = 0; i < 100000; ++i) {
    const double x = std::bit_cast<double>(random());
    if (!std::isnan(x)) expect_as_nextafter(x);
  }
}

// What step_away replaced: branches on `by`'s sign, here with nextafter. A NaN `moved` stays as it
// is, as next_up leaves it (nextafter would quieten a signalling one).
double stepped_by_nextafter(double moved, double by) {
  if (std::isnan(moved)) return moved;
  if (by > 0) return std::nextafter(moved, Limits::infinity());
  if (by < 0) return std::nextafter(moved, -Limits::infinity());
  return moved;
}

// The scalar step_away on (moved, by) and on (by, moved), and the SSE2 one with those two pairs
// in its two lanes.
void expect_stepped_as_nextafter(double moved, double by) {
  const double expected[2] = {stepped_by_nextafter(moved, by), stepped_by_nextafter(by, moved)};
  EXPECT_EQ(bits(step_away(moved, by)), bits(expected[0])) << moved << " by " << by;
  EXPECT_EQ(bits(step_away(by, moved)), bits(expected[1])) << by << " by " << moved;
#if defined(__SSE2__)
  double lanes[2];
  _mm_storeu_pd(lanes, step_away(_mm_set_pd(by, moved), _mm_set_pd(moved, by)));
  EXPECT_EQ(bits(lanes[0]), bits(expected[0])) << moved << " by " << by << " (SSE2)";
  EXPECT_EQ(bits(lanes[1]), bits(expected[1])) << by << " by " << moved << " (SSE2)";
#endif
}

TEST(StepAway, MovesAsNextafterTowardsTheSignOfBy) {
  const std::vector<double> values = {0.0,
                                      -0.0,
                                      1.0,
                                      -1.0,
                                      Limits::denorm_min(),
                                      -Limits::denorm_min(),
                                      Limits::min(),
                                      -Limits::min(),
                                      Limits::max(),
                                      -Limits::max(),
                                      Limits::infinity(),
                                      -Limits::infinity(),
                                      Limits::quiet_NaN(),
                                      -Limits::quiet_NaN(),
                                      3e-12,
                                      -7e8};
  for (double moved : values)
    for (double by : values) expect_stepped_as_nextafter(moved, by);

  // Random bit patterns for both: every exponent, both signs, subnormals and NaN payloads.
  std::mt19937_64 random(11);
  for (int i = 0; i < 100000; ++i)
    expect_stepped_as_nextafter(std::bit_cast<double>(random()), std::bit_cast<double>(random()));
}

}  // namespace
}  // namespace tessera
