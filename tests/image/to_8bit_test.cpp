#include "common/image/to_8bit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace tessera {
namespace {

// The run converts as to_8bit one value at a time does: at every rounding boundary (the values
// whose scaled intensity is k + 0.5, a few units in the last place either side), beyond the
// clamps, for negative zero, infinities and NaN, and for random bit patterns.
TEST(To8Bit, ARunConvertsAsOneValueAtATime) {
  std::vector<float> values = {0.0f,
                               -0.0f,
                               1.0f,
                               -1.0f,
                               2.0f,
                               1e30f,
                               -1e30f,
                               std::numeric_limits<float>::infinity(),
                               -std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN(),
                               std::numeric_limits<float>::denorm_min()};
  for (int k = -2; k <= 256; ++k) {
    float v = (static_cast<float>(k) + 0.5f) / 255.0f;
    for (int ulp = 0; ulp < 4; ++ulp) v = std::nextafter(v, -1.0f);
    for (int step = 0; step < 8; ++step, v = std::nextafter(v, 2.0f)) values.push_back(v);
  }
  std::mt19937 rng(5);
  for (int i = 0; i < 200000; ++i) {
    const auto bits = static_cast<std::uint32_t>(rng());
    float v;
    std::memcpy(&v, &bits, sizeof v);
    values.push_back(i % 2 ? v : std::uniform_real_distribution<float>(-0.1f, 1.1f)(rng));
  }
  std::vector<std::uint8_t> converted(values.size());
  to_8bit_run(values.data(), values.size(), converted.data());
  for (std::size_t i = 0; i < values.size(); ++i)
    ASSERT_EQ(converted[i], to_8bit(values[i])) << "value " << values[i] << " at " << i;
}

}  // namespace
}  // namespace tessera
