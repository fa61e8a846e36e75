#include "common/accel/mesh_accel.h"

#include <vector>

namespace tessera {

MeshAccel build_mesh_accel(const Mesh& mesh, BvhMode mode) {
  MeshAccel accel;
  accel.mesh = &mesh;
  std::vector<Bounds3> bounds(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (const std::uint32_t v : mesh.triangles[i].v) bounds[i].extend(mesh.positions.at(v));
    accel.bounds.extend(bounds[i]);
  }
  accel.bvh = build_bvh(bounds, mode);
  return accel;
}

}  // namespace tessera
