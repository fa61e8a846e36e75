// What a worker's result must satisfy before it touches a job (docs/PROTOCOL.md, "Results").
// A worker is trusted with the shared secret, not with its output: a buggy or compromised one
// must not put NaN into a final image or a year of render time into the statistics. Each check
// throws ProtocolError naming what is wrong; the scheduler's caller then drops the worker.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/render/stats.h"

namespace tessera {

// The unit's `pixels` × 3 float32 values, each finite (the tracer zeroes non-finite samples).
// Negative values are let through: an honest worker renders them for a VRML world with
// negative colours (the VRML loader takes them as written, tessera-render writes them), and
// refusing them would drop every worker that takes such a job, again and again.
std::vector<float> checked_pixels(const std::string& payload, long long pixels);

// The statistics of a unit of `pixels` pixels that was sent `wall_seconds` ago: counts are
// non-negative integers, `pixels` is the unit's, NaN samples are among the samples, `seconds`
// is finite and not beyond the wall time (plus a second of slack for the two clocks), and no
// count exceeds what any machine could do in that time.
RenderStats checked_stats(const nlohmann::json& stats, long long pixels, double wall_seconds);

}  // namespace tessera
