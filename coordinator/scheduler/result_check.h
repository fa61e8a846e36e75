// What a worker's result must satisfy before it touches a job (docs/PROTOCOL.md, "Results").
// A worker is trusted with the shared secret, not with its output: a buggy or compromised one
// must not put NaN into a final image or a year of render time into the statistics. Decoding
// (common/protocol/messages.h) has already refused mistyped fields; these checks compare the
// result with the unit it answers. Each throws ProtocolError naming what is wrong; the
// scheduler's caller then drops the worker.
#pragma once

#include "common/protocol/messages.h"

namespace tessera {

// A result for a unit of `pixels` pixels that was sent `wall_seconds` ago:
//  - its values are the unit's `pixels` × 3, each finite (the tracer zeroes non-finite
//    samples). Negative values are let through: an honest worker renders them for a VRML world
//    with negative colours (the VRML loader takes them as written, tessera-render writes them),
//    and refusing them would drop every worker that takes such a job, again and again;
//  - its statistics count the unit's pixels, NaN samples are among the samples, `seconds` is
//    finite and not beyond the wall time (plus a second of slack for the two clocks), and no
//    count exceeds what any machine could do in that time.
void check_result(const ResultMessage& result, long long pixels, double wall_seconds);

}  // namespace tessera
