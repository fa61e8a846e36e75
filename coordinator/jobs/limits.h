// Limits that protect the service from any one request (docs/ARCHITECTURE.md, "Limits on every
// input"; docs/SECURITY.md lists them all).
#pragma once

#include <cstddef>

namespace tessera {

struct ServiceLimits {
  std::size_t max_body_bytes = 32u << 20;  // POST /api/jobs, scene bundle included
  int max_side = 4096;                     // width and height
  long long max_pixels = 4LL << 20;        // about 180 MB of frame buffers at most
  int max_passes = 256;
  int max_cone_samples = 64;  // rays per gloss, translucency and soft-shadow cone
  int max_depth = 16;         // maxRecursionDepth after overrides
  double max_job_seconds = 600;
  int max_jobs = 64;  // kept in memory; the oldest finished ones go first
};

}  // namespace tessera
