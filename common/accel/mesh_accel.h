// A mesh prepared for tracing: its triangles' data and their own BVH.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "common/accel/bvh.h"
#include "common/geometry/triangle_float_reject.h"
#include "common/geometry/triangle_pair.h"
#include "common/scene/mesh.h"

namespace tessera {

struct MeshAccel {
  // bvh.primitive_order's entries between leaves (see leaf_pairs), which name no triangle.
  static constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();
  // Every leaf starts at a multiple of this position, so that it fills whole leaf_quads.
  static constexpr std::uint32_t kLeafAlignment = 4;

  const Mesh* mesh = nullptr;
  Bvh bvh;
  Bounds3 bounds;
  // The corners of the triangle at each position i of bvh.primitive_order, in lane i % 2 of
  // leaf_pairs[i / 2], so that a leaf's triangles lie together in memory and are tested two at a
  // time, or four (two adjacent pairs) with AVX2 (intersect_triangle_pair.h). Every leaf starts at
  // a multiple of kLeafAlignment: a leaf is followed by a gap in primitive_order (kNoTriangle) up
  // to the next multiple, whose lanes' corners are NaN, as are a degenerate triangle's: the
  // triangle test rejects them (their determinant is not finite). The SAH tree leaves degenerate
  // triangles out, but the flat "acceleration off" keeps every one. Read only for the lanes that
  // leaf_quads' float test cannot reject, and for hits.
  std::vector<TrianglePair> leaf_pairs;
  // The same corners in float, position i in lane i % 4 of leaf_quads[i / 4], tested first by
  // the reject-only float test (triangle_float_reject.h): half the bytes a leaf's test loads
  // (docs/PERFORMANCE.md "A float reject test for leaves"). Gaps and degenerate triangles have a
  // NaN magnitude, which the float test rejects. As many quads as leaf_pairs holds pairs, halved.
  std::vector<FloatTriangleQuad> leaf_quads;
};

// `threads` as for build_bvh.
MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode, int threads = 1);

}  // namespace tessera
