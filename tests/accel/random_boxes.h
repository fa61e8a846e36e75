// Random axis-aligned boxes for the BVH tests: centres uniform in [0, world)^3, half-extents
// uniform in [0, size) per axis.
#pragma once

#include <random>
#include <vector>

#include "common/math/ray.h"

namespace tessera {

inline std::vector<Bounds3> random_boxes(std::mt19937_64& rng, int n, double world, double size) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Bounds3> boxes;
  for (int i = 0; i < n; ++i) {
    const Vec3 c{world * u(rng), world * u(rng), world * u(rng)};
    const Vec3 h{size * u(rng), size * u(rng), size * u(rng)};
    boxes.push_back({c - h, c + h});
  }
  return boxes;
}

}  // namespace tessera
