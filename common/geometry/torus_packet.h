// The nearest hits of up to four rays from one origin on a torus (camera rays of neighbouring
// pixels reaching the same torus instance together): each ray's frame, quartic and first-root
// bracket (torus.h) are formed four lanes at once with AVX2, with per lane the IEEE operations of
// torus_frame in the same order (no FMA: the build has -ffp-contract=off), so the same bits; each
// ray then searches its quartic's roots alone.
#pragma once

#include "common/geometry/local_hit.h"
#include "common/geometry/torus.h"

namespace tessera {

inline constexpr int kTorusPacketLanes = 4;

// torus_frame for the rays from `origin` along directions[l] with limit t_max[l], l = 0..3, all
// four computed (each entry must hold a ray); bit l of the answer is set when ray l's frame was
// formed, frames[l] then written. Needs AVX2 (wide_box_kernel_supported).
unsigned torus_frames_avx2(const Torus& torus, const Vec3& origin, const Vec3 directions[4],
                           const double t_max[4], TorusFrame frames[4]);

// torus_root_hit for the lanes l in `lanes` (bit l, at least one), each root roots[l] of
// frames[l]: hits[l] written, per lane the same operations in the same order. Needs AVX2.
void torus_root_hits_avx2(const Torus& torus, const TorusFrame frames[4], const TorusRoot roots[4],
                          unsigned lanes, LocalHit hits[4]);

// intersect_torus for the lanes l in `lanes` (bit l): bit l of the answer set when ray l hits,
// hits[l] then written. Needs AVX2; every entry of directions must hold a ray.
unsigned intersect_torus_packet_avx2(const Torus& torus, const Vec3& origin,
                                     const Vec3 directions[4], unsigned lanes,
                                     const double t_max[4], LocalHit hits[4]);

}  // namespace tessera
