// Ray / triangle mesh intersection through the mesh's own BVH (shapes.h).
#include <algorithm>
#include <bit>
#include <utility>

#include "common/accel/wide_bvh_traverse.h"
#include "common/geometry/intersect_triangle_pair.h"
#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"
#include "common/math/float_error.h"

namespace tessera {
namespace {

// Tests a quad of a leaf's triangles, `remaining` of the leaf's triangles from its first lane
// on: at once in the traversals compiled for AVX2 (has_avx2; lanes past the leaf's end are NaN,
// never hit), else as its halves, the second only where the leaf reaches it. Returns the lanes hit
// as bits.
template <typename Kernel>
[[gnu::always_inline]] inline unsigned intersect_leaf_quad(Kernel, const TriangleQuad& quad,
                                                           std::uint32_t remaining,
                                                           const TriangleLanesRay& lanes_ray,
                                                           double t_max, TriangleLaneHits& hits) {
#if defined(__SSE2__)
  if constexpr (has_avx2(Kernel::value))
    return intersect_triangle_quad(quad, lanes_ray, t_max, hits);
#endif
  const unsigned lanes = intersect_triangle_pair(quad, 0, lanes_ray, t_max, hits);
  if (remaining <= 2) return lanes;
  return lanes | intersect_triangle_pair(quad, 1, lanes_ray, t_max, hits);
}

// The quad holding position `first` of the mesh's primitive order, the first of a leaf (a
// multiple of four: a leaf starts a quad). The leaf visitors step a pointer from it, one quad
// per four positions, rather than index the quads by position at each quad: the division and
// the scaling by the quad's size were four instructions a quad.
const TriangleQuad* leaf_first_quad(const MeshAccel& accel, std::uint32_t first) {
  return accel.leaf_quads.data() + first / 4;
}

// The corners of the triangle at `position` of the mesh's primitive order, from its leaf.
Vec3 leaf_corner(const MeshAccel& accel, std::uint32_t position, int c) {
  return quad_corner(accel.leaf_quads[position / 4], c, static_cast<int>(position % 4));
}

}  // namespace

// Each traversal prepares the ray for the lane tests (prepare_triangle_lanes_ray) only once it
// enters the mesh's root box. The leaf visitors are forced inline into the traversal loop: as
// calls, each leaf paid a stack frame and six saved registers, 5-10 % of a shadow ray's time
// (tessera-embree-bench --cpu-time). GCC's attribute syntax: [[gnu::always_inline]] in that place
// applies to the lambda's type, which GCC 12 rejects.
bool intersect_mesh(const MeshAccel& accel, bool interpolate_normals, const Ray& ray, double t_max,
                    LocalHit& hit, IntersectionCounters& counters) {
  if (accel.mesh == nullptr) return false;
  bool found = false;
  std::uint32_t found_triangle = 0, found_position = 0;
  TriangleHit nearest;
  // Hits at equal t go to the smaller triangle index, whichever the traversal meets first: once
  // one is found, triangles are tested up to the next double above its t.
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes, kNearestFirst, [&] {
    return [&, lanes_ray = prepare_triangle_lanes_ray(ray) ](
        std::uint32_t first, std::uint32_t count, double t_limit, auto kernel)
        __attribute__((always_inline)) {
      counters.triangle_tests += count;
      // The limit triangles are tested against, kept in a local that only a hit taken changes,
      // rather than worked out from `found` and t_limit at each quad: `found` is the caller's,
      // held by reference, which the compiler reloaded at each quad (the stores of a hit taken
      // might change it) (docs/PERFORMANCE.md "The leaf visit").
      double limit = found ? next_up(t_limit) : t_limit;
      const auto take = [&](const TriangleHit& h, std::uint32_t position) {
        const std::uint32_t triangle = accel.bvh.primitive_order[position];
        if (found && h.t == nearest.t && triangle > found_triangle) return;
        nearest = h, found_triangle = triangle, found_position = position, found = true;
        t_limit = h.t;
        limit = next_up(t_limit);
      };
      const std::uint32_t end = first + count;
      const TriangleQuad* quad = leaf_first_quad(accel, first);
      for (std::uint32_t i = first; i < end; i += 4, ++quad) {
        const double quad_limit = limit;
        TriangleLaneHits hits;
        const unsigned lanes =
            intersect_leaf_quad(kernel, *quad, end - i, lanes_ray, quad_limit, hits);
        for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
          const int lane = std::countr_zero(rest);
          // One triangle at a time, a lane would have been tested against the limit after the
          // earlier lanes' hits, never a larger one: in the rare case that it changed, test it
          // again with it.
          const std::uint32_t position = i + static_cast<std::uint32_t>(lane);
          TriangleHit h = hits.lane(lane);
          if (limit == quad_limit ||
              intersect_triangle(leaf_corner(accel, position, 0), leaf_corner(accel, position, 1),
                                 leaf_corner(accel, position, 2), lanes_ray.ray, limit, h))
            take(h, position);
        }
      }
      return t_limit;
    };
  });
  if (!found) return false;
  hit = triangle_local_hit(*accel.mesh, found_triangle, leaf_corner(accel, found_position, 0),
                           leaf_corner(accel, found_position, 1),
                           leaf_corner(accel, found_position, 2), interpolate_normals, nearest);
  return true;
}

bool occluded_mesh(const MeshAccel& accel, const Ray& ray, double t_max,
                   IntersectionCounters& counters) {
  if (accel.mesh == nullptr) return false;
  bool found = false;
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes, kAnyOrder, [&] {
    return [&, lanes_ray = prepare_triangle_lanes_ray(ray) ](
        std::uint32_t first, std::uint32_t count, double t_limit, auto kernel)
        __attribute__((always_inline)) {
      const std::uint32_t end = first + count;
      const TriangleQuad* quad = leaf_first_quad(accel, first);
      for (std::uint32_t i = first; i < end; i += 4, ++quad) {
        TriangleLaneHits hits;
        const unsigned lanes =
            intersect_leaf_quad(kernel, *quad, end - i, lanes_ray, t_limit, hits);
        if (lanes != 0) {
          // Counted as one at a time: up to the first triangle hit.
          counters.triangle_tests +=
              i - first + static_cast<std::uint32_t>(std::countr_zero(lanes)) + 1;
          found = true;
          return -1.0;  // any hit will do
        }
      }
      counters.triangle_tests += count;
      return t_limit;
    };
  });
  return found;
}

std::vector<LocalHit> mesh_crossings(const MeshAccel& accel, bool interpolate_normals,
                                     const Ray& ray, double t_max, IntersectionCounters& counters) {
  std::vector<LocalHit> crossings;
  if (accel.mesh == nullptr) return crossings;
  const Mesh& mesh = *accel.mesh;
  std::vector<std::pair<TriangleHit, std::uint32_t>> hits;
  traverse_wide_bvh_leaves(accel.bvh, ray, t_max, counters.bvh_nodes, kAnyOrder, [&] {
    return [&, lanes_ray = prepare_triangle_lanes_ray(ray) ](
        std::uint32_t first, std::uint32_t count, double limit, auto kernel)
        __attribute__((always_inline)) {
      counters.triangle_tests += count;
      const std::uint32_t end = first + count;
      const TriangleQuad* quad = leaf_first_quad(accel, first);
      for (std::uint32_t i = first; i < end; i += 4, ++quad) {
        TriangleLaneHits lane_hits;
        const unsigned lanes =
            intersect_leaf_quad(kernel, *quad, end - i, lanes_ray, limit, lane_hits);
        for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
          const auto lane = static_cast<std::uint32_t>(std::countr_zero(rest));
          hits.emplace_back(lane_hits.lane(static_cast<int>(lane)),
                            accel.bvh.primitive_order[i + lane]);
        }
      }
      return limit;  // every hit, not only the nearest
    };
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
