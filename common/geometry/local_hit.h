// What a ray/shape intersection routine reports, in the shape's own object space. A routine that
// reports a hit writes every member: intersect_instance hands them a LocalHit left unzeroed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>

#include "common/math/vec3.h"

namespace tessera {

struct LocalHit {
  double t = 0;         // ray parameter of the hit (the ray's direction need not be unit length)
  Vec3 point;           // hit point, re-projected onto the surface where the shape allows it
  Vec3 point_error;     // per-component bound on |point - exact hit point|
  Vec3 normal;          // outward geometric normal (not necessarily unit length)
  Vec3 shading_normal;  // interpolated normal for smooth meshes, else equal to `normal`
  // Which part of the shape was hit (cube face 0..5; tapered cylinder 0 wall, 1 base cap at
  // z = 0, 2 top cap at z = 1; mesh triangle index), for texture mapping.
  std::uint32_t part = 0;
};

// Room for N LocalHits left unzeroed, for the routines that hand them to shapes
// (intersect_instance): the members' initializers cost a `rep stos` at every shape test, and a
// shape writes every member on a hit (LocalHit.EveryMemberIsWrittenOnAHit) while none is read after
// a miss. The byte array's lifetime implicitly creates the LocalHits, aggregates and so
// implicit-lifetime types, within it (C++20 [intro.object]).
template <int N>
struct UnzeroedLocalHits {
  alignas(LocalHit) std::byte bytes[N * sizeof(LocalHit)];
  LocalHit* hits() { return std::launder(reinterpret_cast<LocalHit*>(bytes)); }
};

}  // namespace tessera
