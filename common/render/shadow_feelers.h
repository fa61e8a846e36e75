// Shadow feelers through the scene BVH (eq. 4.24): a feeler alone, or the feelers of up to
// kPacketLanes neighbouring camera hits walking the tree together (accel/bvh_packet_traverse.h),
// each lane getting bit for bit the answer, and the counts, of its own walk.
#pragma once

#include "common/accel/bvh_packet_traverse.h"
#include "common/render/prepared_scene.h"
#include "common/stats/intersection_counters.h"

namespace tessera {

// The product of the transparencies of the objects `ray` meets for t in (0, t_max), each object
// once however often it crosses its surface; 0 as soon as an opaque one blocks it (the walk
// stops there).
double feeler_transmittance(const PreparedScene& scene, const Ray& ray, double t_max,
                            IntersectionCounters& counters);

// factors[k] = feeler_transmittance(scene, rays[k], t_max[k], counters) for k < count (1 to
// kPacketLanes), with the same counts; each lane stops where its own walk would.
void feeler_transmittance_packet(const PreparedScene& scene, const Ray* rays, const double* t_max,
                                 int count, double* factors, IntersectionCounters& counters);

}  // namespace tessera
