#include "coordinator/scheduler/result_check.h"

#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace tessera {

namespace {

// The worker times a unit from receiving it to sending its result, inside the coordinator's
// dispatch-to-arrival interval; the slack covers timer granularity and clock rate differences.
constexpr double kSecondsSlack = 1.0;
// Rays, intersection tests or samples a single unit could claim per second of wall time: a
// thread does a few tens of millions of each; 1e10 leaves two orders of magnitude to faster
// hardware and still keeps the job totals (64-bit) from overflowing.
constexpr double kMaxEventsPerSecond = 1e10;

// Whether every value is finite: branch-free over the exponent bits, four values at a time with
// SSE2 (a result holds up to 196,608 values, and one arrives with every unit). The values are
// read a 4 kB page ahead (a cache line an iteration): the coordinator reads a result's floats
// here first after the kernel's copy, mostly no longer in the cache, and a prefetch a page
// ahead took a third of this loop's samples off the io thread (docs/SCALING.md, io9), likely
// because the processor's own stream prefetcher stops at each 4 kB page of the payload.
bool all_finite(const float* values, std::size_t count) {
  std::size_t i = 0;
#if defined(__SSE2__)
  constexpr std::size_t kAhead = 1024, kLine = 16;  // in floats: 4 kB, 64 bytes
  const __m128i exponent = _mm_set1_epi32(0x7f800000);
  __m128i not_finite = _mm_setzero_si128();
  const auto check_four = [&](std::size_t at) {
    const __m128i bits = _mm_loadu_si128(reinterpret_cast<const __m128i*>(values + at));
    not_finite = _mm_or_si128(not_finite, _mm_cmpeq_epi32(_mm_and_si128(bits, exponent), exponent));
  };
  for (; i + kAhead + kLine <= count; i += kLine) {
    _mm_prefetch(reinterpret_cast<const char*>(values + i + kAhead), _MM_HINT_T0);
    for (std::size_t j = 0; j < kLine; j += 4) check_four(i + j);
  }
  for (; i + 4 <= count; i += 4) check_four(i);
  if (_mm_movemask_epi8(not_finite) != 0) return false;
#endif
  for (; i < count; ++i)
    if (!std::isfinite(values[i])) return false;
  return true;
}

void check_pixels(const FloatValues& values, long long pixels) {
  if (values.size() != static_cast<std::size_t>(pixels) * 3)
    throw ProtocolError("result of " + std::to_string(values.size() / 3) +
                        " pixels for a unit of " + std::to_string(pixels));
  if (all_finite(values.data(), values.size())) return;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw ProtocolError("pixel value " + std::to_string(values[i]) + " at " +
                          std::to_string(i / 3) + " is not finite");
}

void check_stats(const RenderStats& s, long long pixels, double wall_seconds) {
  const double wall = wall_seconds + kSecondsSlack;
  if (!(std::isfinite(s.seconds) && s.seconds >= 0 && s.seconds <= wall))
    throw ProtocolError("render time of " + std::to_string(s.seconds) + " s for a unit sent " +
                        std::to_string(wall_seconds) + " s ago");
  if (s.pixels != static_cast<std::uint64_t>(pixels))
    throw ProtocolError("statistics count " + std::to_string(s.pixels) + " pixels for a unit of " +
                        std::to_string(pixels));
  if (s.nan_samples > s.samples)
    throw ProtocolError("more NaN samples than samples in the statistics");
  const double most = kMaxEventsPerSecond * wall;
  for (const std::uint64_t count :
       {s.camera_rays, s.shadow_rays, s.reflection_rays, s.refraction_rays,
        s.intersections.shape_tests, s.intersections.triangle_tests, s.intersections.bvh_nodes,
        s.samples})
    if (static_cast<double>(count) > most)
      throw ProtocolError("statistics claim " + std::to_string(count) + " events in " +
                          std::to_string(wall_seconds) + " s");
}

}  // namespace

void check_result(const ResultMessage& result, long long pixels, double wall_seconds) {
  check_pixels(result.values, pixels);
  check_stats(result.stats, pixels, wall_seconds);
}

}  // namespace tessera
