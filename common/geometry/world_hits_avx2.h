// Up to four local hits of one instance back in world space at once (the hits of a camera
// packet's lanes, intersect_instance_packet): to_world_hit's point, error bound and normals with
// AVX2, per lane the same IEEE operations in the same order (no FMA: the build has
// -ffp-contract=off), so the same bits.
#pragma once

#include "common/geometry/instance.h"

namespace tessera {

// to_world_hit(instance, locals[l], *hits[l]) for each lane l in `lanes` (bit l). The instance's
// transforms must be full ones (no Instance::diagonal) and it must have no face normals (those
// take to_world_hit a lane at a time). Needs AVX2 (wide_box_kernel_supported).
void to_world_hits_avx2(const Instance& instance, const LocalHit locals[4], unsigned lanes,
                        WorldHit* const hits[4]);

}  // namespace tessera
