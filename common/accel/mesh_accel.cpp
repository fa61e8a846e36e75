#include "common/accel/mesh_accel.h"

#include <limits>
#include <utility>
#include <vector>

#include "common/geometry/triangle.h"

namespace tessera {
namespace {

// Moves every leaf the traversal reads (the wide tree's, or a root that is a leaf) to a multiple
// of four in primitive_order, with gaps (MeshAccel::kNoTriangle) before it, so that a leaf's
// triangles fill whole quads from its quad's first lane. After make_bvh_wide, as a wide leaf may
// be a subtree of binary leaves (leaf_preferred), which stay together, no gaps between them; the
// binary tree's leaves move with the wide leaves that hold them.
void start_leaves_at_multiples_of_four(Bvh& bvh) {
  const std::vector<std::uint32_t>& old_order = bvh.primitive_order;
  std::vector<bool> starts_leaf(old_order.size(), false);
  for (const BvhWideNode& node : bvh.wide)
    for (int c = 0; c < kWideChildren; ++c)
      if (node.count[c] > 0) starts_leaf[node.child[c]] = true;
  std::vector<std::uint32_t> order, new_position(old_order.size());
  order.reserve(old_order.size() + 3 * bvh.wide.size() * kWideChildren);
  for (std::size_t i = 0; i < old_order.size(); ++i) {
    if (starts_leaf[i]) order.resize((order.size() + 3) / 4 * 4, MeshAccel::kNoTriangle);
    new_position[i] = static_cast<std::uint32_t>(order.size());
    order.push_back(old_order[i]);
  }
  for (BvhNode& node : bvh.nodes)
    if (node.count > 0) node.first_or_second_child = new_position[node.first_or_second_child];
  for (BvhWideNode& node : bvh.wide)
    for (int c = 0; c < kWideChildren; ++c)
      if (node.count[c] > 0) node.child[c] = new_position[node.child[c]];
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
  make_bvh_wide(accel.bvh);
  start_leaves_at_multiples_of_four(accel.bvh);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  TriangleQuad never_hit;
  for (int lane = 0; lane < 4; ++lane)
    for (int c = 0; c < 3; ++c) set_quad_corner(never_hit, c, lane, Vec3{kNaN, kNaN, kNaN});
  const std::vector<std::uint32_t>& order = accel.bvh.primitive_order;
  accel.leaf_quads.assign((order.size() + 3) / 4, never_hit);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t index = order[i];
    if (index == MeshAccel::kNoTriangle || degenerate[index]) continue;
    for (int c = 0; c < 3; ++c)
      set_quad_corner(accel.leaf_quads[i / 4], c, static_cast<int>(i % 4),
                      mesh.positions[mesh.triangles[index].v[c]]);
  }
  return accel;
}

}  // namespace tessera
