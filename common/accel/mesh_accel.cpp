#include "common/accel/mesh_accel.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "common/geometry/triangle.h"

namespace tessera {
namespace {

// Moves every leaf of the binary tree to an even position of primitive_order, leaving a gap
// (MeshAccel::kNoTriangle) after each leaf of odd size, so that a leaf's triangles fill whole
// pairs. Before make_bvh_wide, which copies the leaves' ranges.
void start_leaves_at_even_positions(Bvh& bvh) {
  std::vector<BvhNode*> leaves;
  for (BvhNode& node : bvh.nodes)
    if (node.count > 0) leaves.push_back(&node);
  std::sort(leaves.begin(), leaves.end(), [](const BvhNode* a, const BvhNode* b) {
    return a->first_or_second_child < b->first_or_second_child;
  });
  std::vector<std::uint32_t> order;
  order.reserve(bvh.primitive_order.size() + leaves.size());
  for (BvhNode* leaf : leaves) {
    const auto first = static_cast<std::uint32_t>(order.size());
    const auto old_first = bvh.primitive_order.begin() + leaf->first_or_second_child;
    order.insert(order.end(), old_first, old_first + leaf->count);
    if (order.size() % 2 != 0 && leaf != leaves.back()) order.push_back(MeshAccel::kNoTriangle);
    leaf->first_or_second_child = first;
  }
  bvh.primitive_order = std::move(order);
}

}  // namespace

MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode, int threads) {
  MeshAccel accel;
  accel.mesh = &mesh;
  std::vector<Bounds3> bounds(mesh.triangles.size());
  std::vector<bool> degenerate(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& v = mesh.triangles[i].v;
    for (const std::uint32_t corner : v) bounds[i].extend(mesh.positions.at(corner));
    accel.bounds.extend(bounds[i]);
    degenerate[i] =
        triangle_is_degenerate(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]);
    // Never hit, so not worth a place in the tree (an empty box keeps it out).
    if (degenerate[i]) bounds[i] = Bounds3{};
  }
  accel.bvh = build_bvh_nodes(bounds, mode, threads, kMeshLeafTests);
  start_leaves_at_even_positions(accel.bvh);
  make_bvh_wide(accel.bvh);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  TrianglePair never_hit;
  for (int lane = 0; lane < 2; ++lane)
    for (int c = 0; c < 3; ++c) set_pair_corner(never_hit, c, lane, Vec3{kNaN, kNaN, kNaN});
  const std::vector<std::uint32_t>& order = accel.bvh.primitive_order;
  accel.leaf_pairs.assign((order.size() + 1) / 2, never_hit);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t index = order[i];
    if (index == MeshAccel::kNoTriangle || degenerate[index]) continue;
    for (int c = 0; c < 3; ++c)
      set_pair_corner(accel.leaf_pairs[i / 2], c, static_cast<int>(i % 2),
                      mesh.positions[mesh.triangles[index].v[c]]);
  }
  return accel;
}

}  // namespace tessera
