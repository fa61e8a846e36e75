// Rays that stress a slab test against the unit box [0, 1]^3 (and boxes near it): zero and
// negative-zero direction components, an origin on a box plane (a NaN slab), from a corner,
// away from the box, tiny and infinite components. The box tests of both traversals
// (child_boxes_test.cpp, float_child_boxes_test.cpp) run them.
#pragma once

#include <random>
#include <vector>

#include "common/math/ray.h"

namespace tessera {

inline std::vector<Ray> edge_case_rays() {
  return {
      {{0.5, 0.5, -1}, {0, 0, 1}},     // along z, zero x and y components
      {{0.5, 0.5, -1}, {-0.0, 0, 1}},  // negative zero
      {{0, 0.5, -1}, {0, 0, 1}},       // on the x = 0 plane of the box: NaN slab
      {{1, 1, 1}, {-1, -1, -1}},       // from a corner
      {{2, 2, 2}, {1, 1, 1}},          // away
      {{0.5, 0.5, 0.5}, {1e-300, 0, 0}},
      {{0.5, 0.5, 0.5}, {kInfinity, 1, 1}},
  };
}

// A direction component for random rays: uniform in (-2, 2) by `u`, exactly 0 or -0 one time in
// eight each (slabs the ray runs along).
inline double direction_component(std::mt19937_64& rng, std::uniform_real_distribution<double>& u) {
  const double r = u(rng);
  return r > 1.5 ? 0.0 : (r < -1.5 ? -0.0 : r);
}

}  // namespace tessera
