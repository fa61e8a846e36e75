// A mesh prepared for tracing: its triangles' data and their own BVH.
#pragma once

#include "common/accel/bvh.h"
#include "common/scene/mesh.h"

namespace tessera {

struct MeshAccel {
  const Mesh* mesh = nullptr;
  Bvh bvh;
  Bounds3 bounds;
};

MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode);

}  // namespace tessera
