// Perlin noise for the solid textures that need it (marble, cow spots; SDL §4.3.1): Ken
// Perlin's "improved noise" (SIGGRAPH 2002) with his fixed permutation table, so that it has no
// state, no seed and the same value on every worker.
#pragma once

#include "common/math/vec3.h"

namespace tessera {

// Gradient noise at `p`: zero at every integer lattice point, smooth, in [-1, 1].
double perlin_noise(const Vec3& p);

// Perlin's turbulence: the sum over `octaves` of |noise(2^i p)| / 2^i, in [0, 2).
double turbulence(const Vec3& p, int octaves);

}  // namespace tessera
