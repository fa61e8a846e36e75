// Random placements of shapes for the light buffer's randomized tests, and random directions.
#pragma once

#include <random>

#include "common/math/affine.h"
#include "common/math/vec3.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {

using testing::random_unit;

// A point within 20 of the origin in each coordinate, or, one time in ten, within 1e4.
inline Vec3 random_offset(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double far = unit(rng) < 0.1 ? 1e4 : 20;
  return {far * (2 * unit(rng) - 1), far * (2 * unit(rng) - 1), far * (2 * unit(rng) - 1)};
}

// A random rotation, then a scaling (three times in ten not uniform, between two rotations),
// then a translation by random_offset.
inline Affine random_placement(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  Affine transform = *Affine::rotation(360 * unit(rng), random_unit(rng));
  if (unit(rng) < 0.3)
    transform =
        transform *
        Affine::scaling({0.3 + 2.7 * unit(rng), 0.3 + 2.7 * unit(rng), 0.3 + 2.7 * unit(rng)}) *
        *Affine::rotation(360 * unit(rng), random_unit(rng));
  else
    transform = transform * Affine::scaling(Vec3{1, 1, 1} * (0.2 + 3 * unit(rng)));
  return Affine::translation(random_offset(rng)) * transform;
}

}  // namespace tessera
