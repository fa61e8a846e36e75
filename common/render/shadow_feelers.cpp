#include "common/render/shadow_feelers.h"

#include "common/accel/bvh_traverse.h"

namespace tessera {

namespace {

// The object `index` of the scene's instances along `ray` before `t_limit`: multiplies `factor`
// by its transparency when it is in the way, and returns t_limit, or -1 (stop) once the factor
// is 0.
[[gnu::always_inline]] inline double pass_object(const PreparedScene& scene, std::uint32_t index,
                                                 const Ray& ray, double t_limit, double& factor,
                                                 IntersectionCounters& counters) {
  std::uint32_t object = 0;
  if (!occluded_instance(scene.instances()[index], ray, t_limit, object, counters)) return t_limit;
  factor *= scene.scene().objects[object].material.transparency;
  return factor > 0 ? t_limit : -1.0;
}

}  // namespace

double feeler_transmittance(const PreparedScene& scene, const Ray& ray, double t_max,
                            IntersectionCounters& counters) {
  double factor = 1;
  traverse_bvh(scene.bvh(), ray, t_max, counters.bvh_nodes,
               [&](std::uint32_t index, double t_limit) {
                 return pass_object(scene, index, ray, t_limit, factor, counters);
               });
  return factor;
}

void feeler_transmittance_packet(const PreparedScene& scene, const Ray* rays, const double* t_max,
                                 int count, double* factors, IntersectionCounters& counters) {
  double limits[kPacketLanes];
  for (int l = 0; l < count; ++l) {
    limits[l] = t_max[l];
    factors[l] = 1;
  }
  const std::vector<std::uint32_t>& order = scene.bvh().primitive_order;
  // traverse_bvh's leaf visit, per lane: a negative limit stops the lane.
  traverse_bvh_packet_leaves(scene.bvh(), PacketRays(rays, count), limits, counters.bvh_nodes,
                             [&](int lane, std::uint32_t first, std::uint32_t size, double limit) {
                               for (std::uint32_t i = first; i < first + size; ++i) {
                                 limit = pass_object(scene, order[i], rays[lane], limit,
                                                     factors[lane], counters);
                                 if (limit < 0) return limit;
                               }
                               return limit;
                             });
}

}  // namespace tessera
