// The sector boxes by which a torus enters the light buffer (prepared_scene.h,
// light_buffer_pieces) each hold the world image of every point of their sector's surface: a
// dense grid over each sector's arc (ends included) and around the tube, on random tori under
// random placements. Geometry alone, no feelers: it pins each box's extremes, which a feeler test
// reaches only when a feeler happens to graze them.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/render/prepared_scene.h"
#include "tests/render/random_placement.h"

namespace tessera {
namespace {

bool holds(const Bounds3& box, const Vec3& p) {
  for (int i = 0; i < 3; ++i)
    if (!(p[i] >= box.lo[i] && p[i] <= box.hi[i])) return false;
  return true;
}

TEST(TorusSectorPieces, HoldEverySurfacePointOfTheirSector) {
  std::mt19937_64 rng(20261129);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kArcSteps = 24, kTubeSteps = 48;
  long checked = 0, outside = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double big_r = 0.3 + 2 * unit(rng);
    const double r = big_r * (trial % 3 == 0 ? 1 + 2 * unit(rng) : 0.02 + 0.9 * unit(rng));
    // Every third torus turned only about its axis: its boxes then touch the surface.
    const Affine placement = trial % 3 == 1
                                 ? Affine::translation(random_offset(rng)) *
                                       *Affine::rotation(360 * unit(rng), {0, 0, 1}) *
                                       Affine::scaling(Vec3{1, 1, 1} * (0.3 + 2 * unit(rng)))
                                 : random_placement(rng);
    const Instance torus = *make_instance(Torus{r, big_r}, placement, nullptr);
    std::vector<Bounds3> pieces;
    light_buffer_pieces(torus, pieces);
    ASSERT_EQ(pieces.size(), static_cast<std::size_t>(kTorusLightBufferSectors));
    const double sector = 2 * std::numbers::pi / kTorusLightBufferSectors;
    for (int k = 0; k < kTorusLightBufferSectors; ++k) {
      for (int a = 0; a <= kArcSteps; ++a) {
        const double theta = (k + static_cast<double>(a) / kArcSteps) * sector;
        for (int t = 0; t < kTubeSteps; ++t) {
          const double phi = 2 * std::numbers::pi * t / kTubeSteps;
          const double rho = big_r + r * std::cos(phi);
          const Vec3 local{rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)};
          ++checked;
          // A spindle's inner part (rho < 0) lies across the axis, in the opposite sector.
          const int owner =
              rho >= 0 ? k : (k + kTorusLightBufferSectors / 2) % kTorusLightBufferSectors;
          if (!holds(pieces[owner], torus.to_world.apply_point(local))) ++outside;
        }
      }
    }
  }
  EXPECT_EQ(outside, 0) << "of " << checked << " surface points";
}

// A piece is no larger than the whole torus's box (grown by its padding): else the sectors would
// leave out nothing, and the test above could not fail.
TEST(TorusSectorPieces, AreSmallerThanTheWholeBox) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Instance torus = *make_instance(Torus{0.25, 1.0}, random_placement(rng), nullptr);
    std::vector<Bounds3> pieces;
    light_buffer_pieces(torus, pieces);
    const Vec3 whole = torus.world_bounds.diagonal();
    for (const Bounds3& piece : pieces) {
      const Vec3 size = piece.diagonal();
      EXPECT_LT(size.x * size.y * size.z, 0.25 * whole.x * whole.y * whole.z);
    }
  }
}

}  // namespace
}  // namespace tessera
