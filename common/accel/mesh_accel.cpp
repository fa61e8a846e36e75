#include "common/accel/mesh_accel.h"

#include <limits>
#include <vector>

#include "common/geometry/triangle.h"

namespace tessera {

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
  accel.bvh = build_bvh_nodes(bounds, mode, threads);
  make_bvh_wide(accel.bvh);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  accel.leaf_corners.reserve(3 * accel.bvh.primitive_order.size());
  for (const std::uint32_t index : accel.bvh.primitive_order)
    for (const std::uint32_t corner : mesh.triangles[index].v)
      accel.leaf_corners.push_back(degenerate[index] ? Vec3{kNaN, kNaN, kNaN}
                                                     : mesh.positions[corner]);
  return accel;
}

}  // namespace tessera
