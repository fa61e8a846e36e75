// The nearest hits of up to four rays from one origin on the cube [-1, 1]^3 (camera rays of
// neighbouring pixels reaching the same cube instance together, as the floor of
// features/torus.sdl): the slab span and nearest face are found four lanes at once with AVX2, with
// per lane the IEEE operations of intersect_cube (cube.cpp) in the same order, so the same bits;
// each hit lane then writes its hit as intersect_cube does.
#pragma once

#include "common/geometry/local_hit.h"

namespace tessera {

// intersect_cube for the rays from `origin` along directions[l] with limit t_max[l], for the
// lanes l in `lanes` (bit l): bit l of the answer set when ray l hits, hits[l] then written. Needs
// AVX2 (wide_box_kernel_supported); every entry of directions must hold a ray.
unsigned intersect_cube_packet_avx2(const Vec3& origin, const Vec3 directions[4], unsigned lanes,
                                    const double t_max[4], LocalHit hits[4]);

}  // namespace tessera
