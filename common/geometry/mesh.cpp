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

// Tests the triangles of the leaf [first, first + count) of Bvh::primitive_order in order:
// `step(i, test)` for each group from position i on, where `test(t_max, hits)` returns the lanes
// hit as bits (lane l for the triangle at i + l, only those inside the leaf); stops when `step`
// returns false, and returns false then. In the traversal compiled for AVX2 the groups are quads
// (two pairs; a last quad reaching past the leaf has those lanes masked off, and reads the next
// leaf's pairs or the NaN pair after the last leaf), elsewhere pairs.
//
// A leaf's quads, up to four (count <= 16, nearly every leaf), run as a jump into a run of four
// (Duff's device), so that how many run is one indirect jump: a loop's exit test after each quad
// mispredicted 1.8 times an incoherent ray in callgrind's model, leaves of 4, 8 and 12 triangles
// being visited about as often (docs/PERFORMANCE.md "A leaf's quads without a loop").
template <typename Kernel, typename Step>
[[gnu::always_inline]] inline bool for_each_leaf_test(Kernel, const MeshAccel& accel,
                                                      std::uint32_t first, std::uint32_t count,
                                                      const TriangleLanesRay& lanes_ray,
                                                      Step&& step) {
#if defined(__SSE2__)
  if constexpr (Kernel::value == WideBoxKernel::Avx2) {
    const auto quad = [&](std::uint32_t i, unsigned inside) {
      return step(i, [&, i, inside](double t_max, TriangleLaneHits& hits) {
        return intersect_triangle_quad(&accel.leaf_pairs[i / 2], lanes_ray, t_max, hits) & inside;
      });
    };
    std::uint32_t i = first, rest = count;
    for (; rest > 16; rest -= 4, i += 4)
      if (!quad(i, 15)) return false;
    const unsigned last_inside = 15u >> ((4 - rest % 4) % 4);
    // Five cases (with 0, and nothing else possible): GCC makes a jump table of five or more,
    // a tree of compares below.
    switch ((rest + 3) / 4) {
      case 4:
        if (!quad(i, 15)) return false;
        i += 4;
        [[fallthrough]];
      case 3:
        if (!quad(i, 15)) return false;
        i += 4;
        [[fallthrough]];
      case 2:
        if (!quad(i, 15)) return false;
        i += 4;
        [[fallthrough]];
      case 1:
        return quad(i, last_inside);
      case 0:
        return true;
      default:
        __builtin_unreachable();
    }
  }
#endif
  for (std::uint32_t i = first; i < first + count; i += 2) {
    const bool go_on = step(i, [&, i](double t_max, TriangleLaneHits& hits) {
      return intersect_triangle_pair(accel.leaf_pairs[i / 2], lanes_ray, t_max, hits);
    });
    if (!go_on) return false;
  }
  return true;
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
      const auto take = [&](const TriangleHit& h, std::uint32_t position) {
        const std::uint32_t triangle = accel.bvh.primitive_order[position];
        if (found && h.t == nearest.t && triangle > found_triangle) return;
        nearest = h, found_triangle = triangle, found_position = position, found = true;
        t_limit = h.t;
      };
      for_each_leaf_test(kernel, accel, first, count, lanes_ray, [&](std::uint32_t i, auto test) {
        const double limit = found ? next_up(t_limit) : t_limit;
        TriangleLaneHits hits;
        const unsigned lanes = test(limit, hits);
        for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
          const int lane = std::countr_zero(rest);
          // One triangle at a time, a lane would have been tested against the limit after the
          // earlier lanes' hits, never a larger one: in the rare case that it changed, test it
          // again with it.
          const double limit_now = found ? next_up(t_limit) : t_limit;
          const TrianglePair& pair = accel.leaf_pairs[(i + static_cast<std::uint32_t>(lane)) / 2];
          TriangleHit h = hits.lane(lane);
          if (limit_now == limit ||
              intersect_triangle(pair_corner(pair, 0, lane % 2), pair_corner(pair, 1, lane % 2),
                                 pair_corner(pair, 2, lane % 2), lanes_ray.ray, limit_now, h))
            take(h, i + static_cast<std::uint32_t>(lane));
        }
        return true;
      });
      return t_limit;
    };
  });
  if (!found) return false;
  const TrianglePair& pair = accel.leaf_pairs[found_position / 2];
  const int lane = static_cast<int>(found_position % 2);
  hit = triangle_local_hit(*accel.mesh, found_triangle, pair_corner(pair, 0, lane),
                           pair_corner(pair, 1, lane), pair_corner(pair, 2, lane),
                           interpolate_normals, nearest);
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
      found = !for_each_leaf_test(
          kernel, accel, first, count, lanes_ray, [&](std::uint32_t i, auto test) {
            TriangleLaneHits hits;
            const unsigned lanes = test(t_limit, hits);
            if (lanes == 0) return true;
            // Counted as one at a time: up to the first triangle hit.
            counters.triangle_tests +=
                i - first + static_cast<std::uint32_t>(std::countr_zero(lanes)) + 1;
            return false;  // any hit will do
          });
      if (found) return -1.0;
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
      for_each_leaf_test(kernel, accel, first, count, lanes_ray, [&](std::uint32_t i, auto test) {
        TriangleLaneHits lane_hits;
        const unsigned lanes = test(limit, lane_hits);
        for (unsigned rest = lanes; rest != 0; rest &= rest - 1) {
          const auto lane = static_cast<std::uint32_t>(std::countr_zero(rest));
          hits.emplace_back(lane_hits.lane(static_cast<int>(lane)),
                            accel.bvh.primitive_order[i + lane]);
        }
        return true;
      });
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
