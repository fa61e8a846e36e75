// A result's values are refused when any one is not finite, wherever it is (the check runs a
// cache line at a time while it reads a page ahead, then four values at a time, then the rest
// one by one), and the error names the first such pixel.
#include "coordinator/scheduler/result_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tessera {
namespace {

ResultMessage result_of(long long pixels) {
  ResultMessage result;
  result.values.assign(static_cast<std::size_t>(pixels) * 3, 0.5f);
  result.stats.pixels = static_cast<std::uint64_t>(pixels);
  result.stats.samples = result.stats.pixels;
  return result;
}

TEST(ResultCheck, ANonFiniteValueAnywhereIsRefusedAndNamed) {
  // 21 values: five groups of four and one left over; 1,203: ten cache lines read a page
  // (1,024 values) ahead, 260 groups of four and three left over.
  for (const long long pixels : {7, 401})
    for (const float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()})
      for (std::size_t at = 0; at < 3 * static_cast<std::size_t>(pixels); ++at) {
        ResultMessage result = result_of(pixels);
        result.values[at] = bad;
        try {
          check_result(result, pixels, 1.0);
          ADD_FAILURE() << bad << " at value " << at << " of " << 3 * pixels << " was let through";
        } catch (const ProtocolError& e) {
          EXPECT_NE(std::string(e.what()).find(" at " + std::to_string(at / 3) + " is not finite"),
                    std::string::npos)
              << e.what();
        }
      }
}

TEST(ResultCheck, FiniteExtremesAndNegativesPass) {
  ResultMessage result = result_of(3);
  result.values = {std::numeric_limits<float>::max(),
                   -std::numeric_limits<float>::max(),
                   std::numeric_limits<float>::denorm_min(),
                   -0.0f,
                   -3.5f,
                   std::nextafter(std::numeric_limits<float>::infinity(), 0.0f),
                   0,
                   1,
                   1e-30f};
  EXPECT_NO_THROW(check_result(result, 3, 1.0));
}

}  // namespace
}  // namespace tessera
