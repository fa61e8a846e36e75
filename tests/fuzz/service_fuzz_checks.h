// What the coordinator's fuzz targets check on every input (tests/fuzz/job_request_fuzz.cpp,
// tests/fuzz/worker_frames_fuzz.cpp), shared with the replay of their regression corpus. A
// refusal (ApiError, ProtocolError) is a normal outcome; past it, what the coordinator accepts
// must keep the invariants the rest of the service relies on:
//   - a job request's settings are within the service's limits, its plan agrees with them and
//     every bundle path is a plain relative path inside the bundle, the scene among them;
//   - a refused request gets a status in 400..599 and a JSON body with "error" and "detail",
//     serialised the way the HTTP server does it;
//   - a decoded frame stays within the frame limits and encodes back to itself; a result the
//     coordinator accepts has the unit's count of finite pixels and sane statistics.
// Anything else escaping (a std::exception other than those, a sanitizer report) is a crash.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/protocol/bundle.h"
#include "common/protocol/frame.h"
#include "common/protocol/messages.h"
#include "coordinator/http/refusal_status.h"
#include "coordinator/http/submission.h"
#include "coordinator/jobs/api_error.h"
#include "coordinator/jobs/intake_budget.h"
#include "coordinator/jobs/limits.h"
#include "coordinator/scheduler/result_check.h"
#include "tests/fuzz/fuzz_checks.h"

namespace tessera::fuzz {

// Lowered so that each input is fast (the defaults are tested in tests/coordinator/), but not
// below the defaults of RenderSettings (9 cone samples) and of a scene (depth 5).
inline ServiceLimits fuzz_service_limits() {
  ServiceLimits limits;
  limits.max_side = 64;
  limits.max_pixels = 1024;
  limits.max_passes = 4;
  limits.max_cone_samples = 9;
  limits.max_depth = 6;
  return limits;
}

inline void check_accepted_request(const JobRequest& request, const ServiceLimits& limits) {
  const RenderSettings& s = request.spec.settings;
  require(
      s.width >= 1 && s.width <= limits.max_side && s.height >= 1 && s.height <= limits.max_side,
      "an accepted request's width or height is outside [1, max_side]");
  require(static_cast<long long>(s.width) * s.height <= limits.max_pixels,
          "an accepted request has more pixels than max_pixels");
  require(s.passes >= 1 && s.passes <= limits.max_passes,
          "an accepted request's passes are outside [1, max_passes]");
  require(s.cone_samples >= 1 && s.cone_samples <= limits.max_cone_samples,
          "an accepted request's cone samples are outside [1, max_cone_samples]");
  require(
      !request.spec.overrides.max_depth || (*request.spec.overrides.max_depth >= 0 &&
                                            *request.spec.overrides.max_depth <= limits.max_depth),
      "an accepted request's max_depth is outside [0, max_depth]");
  require(request.plan.width == s.width && request.plan.height == s.height &&
              request.plan.passes == s.passes,
          "an accepted request's plan disagrees with its settings");
  require(std::isfinite(request.seconds_per_pixel_pass) && request.seconds_per_pixel_pass >= 0,
          "an accepted request's probed cost is not a finite non-negative time");
  require(request.bundle.format == "sdl" || request.bundle.format == "vrml",
          "an accepted request's format is neither sdl nor vrml");
  require(is_plain_relative_path(request.bundle.main) &&
              request.bundle.files.count(request.bundle.main) == 1,
          "an accepted request's scene is not a plain path inside its bundle");
  for (const auto& [path, bytes] : request.bundle.files)
    require(is_plain_relative_path(path), "an accepted bundle holds the path \"" + path + "\"");
}

inline void check_refusal(const ApiError& e) {
  const int status = http_status(e.refusal());
  require(status >= 400 && status <= 599, "a refusal's status is outside 400..599");
  const nlohmann::json body = e.body();
  const auto non_empty_string = [&](const char* key) {
    return body.contains(key) && body.at(key).is_string() &&
           !body.at(key).get<std::string>().empty();
  };
  require(body.is_object() && non_empty_string("error") && non_empty_string("detail"),
          "a refusal's body lacks \"error\" or \"detail\"");
  // As coordinator/http/http_server.cpp sends it: bytes from the request may be in the detail.
  require(!body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).empty(),
          "a refusal's body does not serialise");
}

// The first byte picks the content type (0 JSON, 1 multipart with the boundary
// "tesseraFuzzBoundary", 2 tar); for a tar, a query string ("main=a.sdl&width=8") and a newline
// come before the body. The scene may only read files of the request (no --scenes-dir).
// Returns true when the request was accepted, false when it was refused with an ApiError.
inline bool check_job_request_input(std::string_view bytes) {
  if (bytes.empty()) return false;
  JobUpload upload;
  upload.body = bytes.substr(1);
  switch (static_cast<unsigned char>(bytes[0]) % 3) {
    case 0:
      upload.content_type = "application/json";
      break;
    case 1:
      upload.content_type = "multipart/form-data; boundary=tesseraFuzzBoundary";
      break;
    default: {
      upload.content_type = "application/x-tar";
      const std::size_t newline = upload.body.find('\n');
      const std::string_view query =
          newline == std::string_view::npos ? std::string_view{} : upload.body.substr(0, newline);
      upload.body =
          newline == std::string_view::npos ? upload.body : upload.body.substr(newline + 1);
      for (std::size_t at = 0; at < query.size();) {
        const std::size_t end = std::min(query.find('&', at), query.size());
        const std::string_view pair = query.substr(at, end - at);
        const std::size_t eq = pair.find('=');
        if (eq != std::string_view::npos)
          upload.query[std::string(pair.substr(0, eq))] = std::string(pair.substr(eq + 1));
        at = end + 1;
      }
    }
  }
  const ServiceLimits limits = fuzz_service_limits();
  try {
    check_accepted_request(
        parse_job_request(upload, limits, std::nullopt, IntakeBudget::starting_now(2.0)), limits);
  } catch (const ApiError& e) {
    check_refusal(e);
    return false;
  }
  return true;
}

// The unit every result in a fuzzed stream answers: its pixel count and how long ago it was
// sent. Frame limits are lowered so that the limit is within the fuzzer's reach.
constexpr long long kFuzzUnitPixels = 4;
constexpr double kFuzzUnitWallSeconds = 2.0;
inline FrameLimits fuzz_frame_limits() { return {.max_body = 4096, .max_header = 1024}; }

inline void check_accepted_result(const Frame& frame) {
  const ResultMessage result = decode<ResultMessage>(frame);
  check_result(result, kFuzzUnitPixels, kFuzzUnitWallSeconds);
  const RenderStats& stats = result.stats;
  const FloatValues& pixels = result.values;
  require(pixels.size() == static_cast<std::size_t>(kFuzzUnitPixels) * 3,
          "an accepted result does not have the unit's pixel count");
  for (const float value : pixels) require(std::isfinite(value), "an accepted pixel is not finite");
  require(stats.pixels == static_cast<std::uint64_t>(kFuzzUnitPixels),
          "accepted statistics count another number of pixels");
  require(std::isfinite(stats.seconds) && stats.seconds >= 0 &&
              stats.seconds <= kFuzzUnitWallSeconds + 1,
          "accepted statistics claim a time beyond the unit's wall time");
  require(stats.nan_samples <= stats.samples, "accepted statistics have more NaN than samples");
}

inline void check_decoded_frame(const Frame& frame, const FrameLimits& limits) {
  require(frame.payload.size() <= limits.max_body, "a decoded payload is over max_body");
  // What the coordinator would send back of it: the same frame, or a ProtocolError when its
  // re-serialised header no longer fits.
  std::string encoded;
  try {
    encoded = encode_frame(frame, limits);
  } catch (const ProtocolError&) {
    return;
  }
  const Frame again = decode_body(std::string_view(encoded).substr(kFramePrefix), limits);
  require(
      again.type == frame.type && again.header == frame.header && again.payload == frame.payload,
      "a decoded frame does not encode back to itself");
}

// The first byte sets the size of the chunks (1..256) the rest is fed in, as a socket would
// deliver it. Returns true when the whole stream decoded and every result in it was accepted,
// false when the connection would be closed (a ProtocolError: a malformed frame, a message that
// does not decode, or a result that fails result_check.h).
inline bool check_worker_frames_input(std::string_view bytes) {
  if (bytes.empty()) return false;
  const std::size_t chunk = static_cast<unsigned char>(bytes[0]) + 1u;
  const std::string_view stream = bytes.substr(1);
  const FrameLimits limits = fuzz_frame_limits();
  FrameDecoder decoder(limits);
  try {
    for (std::size_t at = 0; at < stream.size(); at += chunk) {
      decoder.feed(stream.substr(at, chunk));
      while (const std::optional<Frame> frame = decoder.next()) {
        check_decoded_frame(*frame, limits);
        if (frame->type == MessageType::Result) check_accepted_result(*frame);
      }
    }
  } catch (const ProtocolError&) {
    return false;
  }
  return true;
}

}  // namespace tessera::fuzz
