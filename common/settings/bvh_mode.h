// How the scene's and the meshes' BVHs are built: a render setting that the acceleration layer
// takes. On its own, below accel/, so that the settings and the wire name it without depending
// on the tracer (docs/ARCHITECTURE.md, "Layers").
#pragma once

namespace tessera {

// Sah: the surface area heuristic (common/accel/bvh.h); None: one leaf holding every primitive,
// the seeds' "acceleration off".
enum class BvhMode { Sah, None };

}  // namespace tessera
