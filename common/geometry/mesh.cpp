// Ray / triangle mesh intersection through the mesh's own BVH (shapes.h).
#include <algorithm>
#include <utility>

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

std::vector<LocalHit> mesh_crossings(const MeshAccel& accel, bool interpolate_normals,
                                     const Ray& ray, double t_max, IntersectionCounters& counters) {
  std::vector<LocalHit> crossings;
  if (accel.mesh == nullptr) return crossings;
  const Mesh& mesh = *accel.mesh;
  std::vector<std::pair<TriangleHit, std::uint32_t>> hits;
  traverse_bvh(accel.bvh, ray, t_max, counters.bvh_nodes, [&](std::uint32_t index, double limit) {
    ++counters.triangle_tests;
    const MeshTriangle& tri = mesh.triangles[index];
    TriangleHit h;
    if (intersect_triangle(mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                           mesh.positions[tri.v[2]], ray, limit, h))
      hits.emplace_back(h, index);
    return limit;  // every hit, not only the nearest
  });
  // By t, then by triangle, so that the order does not depend on the traversal.
  std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) {
    return a.first.t != b.first.t ? a.first.t < b.first.t : a.second < b.second;
  });
  for (const auto& [h, index] : hits) {
    const LocalHit hit = triangle_local_hit(mesh, index, interpolate_normals, h);
    // A ray through an edge or vertex shared by triangles that face the same way crosses the
    // surface once, however many of them report it.
    if (!crossings.empty()) {
      const LocalHit& last = crossings.back();
      const bool same_sense =
          (dot(last.normal, ray.direction) < 0) == (dot(hit.normal, ray.direction) < 0);
      const double reach = length(last.point_error) + length(hit.point_error);
      if (same_sense && length(hit.point - last.point) <= 4 * reach) continue;
    }
    crossings.push_back(hit);
  }
  return crossings;
}

}  // namespace tessera
