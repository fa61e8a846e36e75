// A mesh prepared for tracing: its triangles' data and their own BVH.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "common/accel/bvh.h"
#include "common/geometry/triangle_pair.h"
#include "common/scene/mesh.h"

namespace tessera {

// How a mesh's SAH prices its leaves: triangles tested four at a time with AVX2
// (intersect_triangle_pair.h), a node step worth two such tests (it waits on memory), leaves of
// up to 16; nodes of more than four are split all the same, so that a wide node fills its eight
// slots (Embree's n-ary build) before the SAH's leaves are taken (make_bvh_wide). Fewer, fuller
// nodes, at the price of more triangles a ray (docs/PERFORMANCE.md "The mesh tree").
inline constexpr BvhLeafTests kMeshLeafTests{
    .group = 4, .max_size = 16, .step_cost = 2, .split_above = 4};

struct MeshAccel {
  // bvh.primitive_order's entries between leaves (see leaf_quads), which name no triangle.
  static constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

  const Mesh* mesh = nullptr;
  Bvh bvh;
  Bounds3 bounds;
  // The corners of the triangle at each position i of bvh.primitive_order, in lane i % 4 of
  // leaf_quads[i / 4], so that a leaf's triangles lie together in memory and are tested four at a
  // time with AVX2, each coordinate one aligned load, or two (a quad's halves) with SSE2
  // (intersect_triangle_pair.h). Every leaf starts at a multiple of four: a leaf whose size is
  // not one is followed by gaps in primitive_order (kNoTriangle) up to the next, whose lanes'
  // corners are NaN, as are a degenerate triangle's: the triangle test rejects them (their
  // determinant is not finite). The SAH tree leaves degenerate triangles out, but the flat
  // "acceleration off" keeps every one.
  std::vector<TriangleQuad> leaf_quads;
};

// `threads` as for build_bvh.
MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode, int threads = 1);

}  // namespace tessera
