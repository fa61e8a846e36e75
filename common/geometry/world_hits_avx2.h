// Up to four local hits of one instance back in world space at once (the hits of a camera
// packet's lanes, intersect_instance_packet): to_world_hit's point, error bound and normals with
// AVX2 (the floor's diagonal transforms and face normals too), per lane the same IEEE operations in
// the same order (no FMA: the build has -ffp-contract=off), so the same bits.
#pragma once

#include "common/geometry/instance.h"

namespace tessera {

// to_world_hit(instance, locals[l], *hits[l]) for each lane l in `lanes` (bit l), for full or
// diagonal transforms, with face normals or without. Needs AVX2 (wide_box_kernel_supported).
void to_world_hits_avx2(const Instance& instance, const LocalHit locals[4], unsigned lanes,
                        WorldHit* const hits[4]);

}  // namespace tessera
