// Ray / triangle mesh intersection through the mesh's own BVH (shapes.h).
#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"

namespace tessera {

bool intersect_mesh(const MeshAccel& accel, bool interpolate_normals, const Ray& ray, double t_max,
                    LocalHit& hit, IntersectionCounters& counters) {
  if (accel.mesh == nullptr) return false;
  const Mesh& mesh = *accel.mesh;
  bool found = false;
  std::uint32_t found_index = 0;
  TriangleHit nearest;
  traverse_bvh(accel.bvh, ray, t_max, counters.bvh_nodes, [&](std::uint32_t index, double t_limit) {
    ++counters.triangle_tests;
    const MeshTriangle& tri = mesh.triangles[index];
    TriangleHit h;
    if (!intersect_triangle(mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                            mesh.positions[tri.v[2]], ray, t_limit, h))
      return t_limit;
    nearest = h;
    found_index = index;
    found = true;
    return h.t;
  });
  if (!found) return false;
  hit = triangle_local_hit(mesh, found_index, interpolate_normals, nearest);
  return true;
}

}  // namespace tessera
