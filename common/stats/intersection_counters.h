// Work counters that intersection routines add to; merged into render statistics. On their own,
// below geometry/, so that the statistics the wire carries do not depend on the tracer
// (docs/ARCHITECTURE.md, "Layers").
#pragma once

#include <cstdint>

namespace tessera {

struct IntersectionCounters {
  std::uint64_t shape_tests = 0;     // object-level intersection routine calls
  std::uint64_t triangle_tests = 0;  // ray/triangle tests inside meshes
  std::uint64_t bvh_nodes = 0;       // BVH boxes tested (scene and mesh hierarchies)
};

}  // namespace tessera
