// Ray / triangle mesh intersection through the mesh's own BVH (shapes.h).
#include <algorithm>
#include <utility>

#include "common/accel/wide_bvh_traverse.h"
#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"
#include "common/math/float_error.h"

namespace tessera {

bool intersect_mesh(const MeshAccel& accel, bool interpolate_normals, const Ray& ray, double t_max,
                    LocalHit& hit, IntersectionCounters& counters) {
  if (accel.mesh == nullptr) return false;
  const TriangleRay triangle_ray = prepare_triangle_ray(ray);
  const Vec3* corners = accel.leaf_corners.data();
  bool found = false;
  std::uint32_t found_triangle = 0;
  TriangleHit nearest;
  // Hits at equal t go to the smaller triangle index, whichever the traversal meets first: once
  // one is found, triangles are tested up to the next double above its t.
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes,
                           [&](std::uint32_t first, std::uint32_t count, double t_limit) {
                             counters.triangle_tests += count;
                             for (std::uint32_t i = first; i < first + count; ++i) {
                               const Vec3* p = corners + 3 * static_cast<std::size_t>(i);
                               const double limit = found ? next_up(t_limit) : t_limit;
                               TriangleHit h;
                               if (!intersect_triangle(p[0], p[1], p[2], triangle_ray, limit, h))
                                 continue;
                               const std::uint32_t triangle = accel.bvh.primitive_order[i];
                               if (found && h.t == nearest.t && triangle > found_triangle) continue;
                               nearest = h, found_triangle = triangle, found = true;
                               t_limit = h.t;
                             }
                             return t_limit;
                           });
  if (!found) return false;
  hit = triangle_local_hit(*accel.mesh, found_triangle, interpolate_normals, nearest);
  return true;
}

bool occluded_mesh(const MeshAccel& accel, const Ray& ray, double t_max,
                   IntersectionCounters& counters) {
  if (accel.mesh == nullptr) return false;
  const TriangleRay triangle_ray = prepare_triangle_ray(ray);
  const Vec3* corners = accel.leaf_corners.data();
  bool found = false;
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes,
                           [&](std::uint32_t first, std::uint32_t count, double t_limit) {
                             for (std::uint32_t i = first; i < first + count; ++i) {
                               ++counters.triangle_tests;
                               const Vec3* p = corners + 3 * static_cast<std::size_t>(i);
                               TriangleHit h;
                               if (intersect_triangle(p[0], p[1], p[2], triangle_ray, t_limit, h)) {
                                 found = true;
                                 return -1.0;  // any hit will do
                               }
                             }
                             return t_limit;
                           });
  return found;
}

std::vector<LocalHit> mesh_crossings(const MeshAccel& accel, bool interpolate_normals,
                                     const Ray& ray, double t_max, IntersectionCounters& counters) {
  std::vector<LocalHit> crossings;
  if (accel.mesh == nullptr) return crossings;
  const Mesh& mesh = *accel.mesh;
  const TriangleRay triangle_ray = prepare_triangle_ray(ray);
  const Vec3* corners = accel.leaf_corners.data();
  std::vector<std::pair<TriangleHit, std::uint32_t>> hits;
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes,
                           [&](std::uint32_t first, std::uint32_t count, double limit) {
                             counters.triangle_tests += count;
                             for (std::uint32_t i = first; i < first + count; ++i) {
                               const Vec3* p = corners + 3 * static_cast<std::size_t>(i);
                               TriangleHit h;
                               if (intersect_triangle(p[0], p[1], p[2], triangle_ray, limit, h))
                                 hits.emplace_back(h, accel.bvh.primitive_order[i]);
                             }
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
