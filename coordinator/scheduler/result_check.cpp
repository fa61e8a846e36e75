#include "coordinator/scheduler/result_check.h"

#include <cmath>
#include <cstdint>

#include "common/protocol/frame.h"
#include "common/protocol/job_spec.h"
#include "common/protocol/unit_message.h"

namespace tessera {

namespace {

// The worker times a unit from receiving it to sending its result, inside the coordinator's
// dispatch-to-arrival interval; the slack covers timer granularity and clock rate differences.
constexpr double kSecondsSlack = 1.0;
// Rays, intersection tests or samples a single unit could claim per second of wall time: a
// thread does a few tens of millions of each; 1e10 leaves two orders of magnitude to faster
// hardware and still keeps the job totals (64-bit) from overflowing.
constexpr double kMaxEventsPerSecond = 1e10;

constexpr const char* kCounts[] = {
    "camera_rays",    "shadow_rays", "reflection_rays", "refraction_rays", "shape_tests",
    "triangle_tests", "bvh_nodes",   "pixels",          "samples",         "nan_samples"};

}  // namespace

std::vector<float> checked_pixels(const std::string& payload, long long pixels) {
  std::vector<float> values = unpack_floats(payload, static_cast<std::size_t>(pixels) * 3);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw ProtocolError("pixel value " + std::to_string(values[i]) + " at " +
                          std::to_string(i / 3) + " is not finite");
  return values;
}

RenderStats checked_stats(const nlohmann::json& stats, long long pixels, double wall_seconds) {
  if (!stats.is_object()) throw ProtocolError("statistics are not an object");
  // Read as unsigned, a negative count would wrap around to an absurd one: refuse it here.
  auto non_negative_integer = [](const nlohmann::json& v) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0);
  };
  for (const char* key : kCounts)
    if (stats.contains(key) && !non_negative_integer(stats[key]))
      throw ProtocolError(std::string("statistic ") + key + " is not a non-negative integer");
  if (stats.contains("seconds") && !stats["seconds"].is_number())
    throw ProtocolError("statistic seconds is not a number");
  const RenderStats s = stats_from_json(stats);
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
  return s;
}

}  // namespace tessera
