// A mesh prepared for tracing: its triangles' data and their own BVH.
#pragma once

#include <vector>

#include "common/accel/bvh.h"
#include "common/scene/mesh.h"

namespace tessera {

struct MeshAccel {
  const Mesh* mesh = nullptr;
  Bvh bvh;
  Bounds3 bounds;
  // The corners of the triangle at each position of bvh.primitive_order, three in a row, so
  // that a leaf's triangles lie together in memory. A degenerate triangle's corners are NaN,
  // which the triangle test rejects (its determinant is not finite): the SAH tree leaves such
  // triangles out, but the flat "acceleration off" keeps every one.
  std::vector<Vec3> leaf_corners;
};

// `threads` as for build_bvh.
MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode, int threads = 1);

}  // namespace tessera
