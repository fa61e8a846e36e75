// Limits that protect the service from any one request (docs/ARCHITECTURE.md, "Limits on every
// input"; docs/SECURITY.md lists them all).
#pragma once

#include <cstddef>

namespace tessera {

struct ServiceLimits {
  std::size_t max_body_bytes = 32u << 20;  // POST /api/jobs, scene bundle included
  int max_side = 16384;  // width and height; the page's tile records hold 16-bit coordinates
  // Width x height, --max-pixels: 7680 x 4320 (8K UHD), 464 MB of frame buffer at 14 bytes a
  // pixel (docs/SERVICE.md, "Memory").
  long long max_pixels = 7680LL * 4320;
  int max_passes = 256;
  int max_cone_samples = 64;  // rays per gloss, translucency and soft-shadow cone
  int max_depth = 16;         // maxRecursionDepth after overrides
  double max_job_seconds = 600;
  int max_jobs = 64;  // kept in memory; the oldest finished ones go first
};

}  // namespace tessera
