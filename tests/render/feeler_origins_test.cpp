// FeelerOrigins (common/render/feeler_origins.h) against offset_ray_origin_by, bit for bit.
#include "common/render/feeler_origins.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tessera {
namespace {

// Hits anywhere from 1e-3 to 1e6 from the origin, with normals along the axes (whose offsets
// have zero components) or anywhere, and feelers to either side of the surface and along it
// (a direction at right angles to an axis normal: its dot product is exactly 0, the side
// offset_ray_origin_by takes for the front).
TEST(FeelerOrigins, AreOffsetRayOriginByForEveryDirection) {
  std::mt19937_64 random(18);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_real_distribution<double> exponent(-3, 6);
  const auto any_vector = [&] { return Vec3{unit(random), unit(random), unit(random)}; };
  const Vec3 axes[] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}};
  int back = 0, along_surface = 0;
  for (int i = 0; i < 20000; ++i) {
    WorldHit hit;
    hit.point = any_vector() * std::pow(10.0, exponent(random));
    hit.point_error = abs(hit.point) * 1e-15;
    hit.normal = i % 2 ? axes[i / 2 % 3] : normalize_or(any_vector(), Vec3{0, 0, 1});
    const Vec3 offset = surface_offset(hit.point_error, hit.normal, i % 3 ? 0.0 : 1e-9);
    const FeelerOrigins origins(hit, offset);
    for (int k = 0; k < 4; ++k) {
      Vec3 d = any_vector();
      if (k == 3 && i % 2) d = cross(hit.normal, d);  // along the surface, dot exactly 0
      back += dot(d, hit.normal) < 0;
      along_surface += dot(d, hit.normal) == 0;
      ASSERT_TRUE(
          same_bits(origins.along(d), offset_ray_origin_by(hit.point, offset, hit.normal, d)))
          << "hit " << i << " direction " << k;
    }
  }
  EXPECT_GT(back, 20000);  // both sides were tried
  EXPECT_GT(along_surface, 1000);
}

}  // namespace
}  // namespace tessera
