#include "common/math/ray.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tessera {
namespace {

Vec3 inverse(const Vec3& d) { return {1 / d.x, 1 / d.y, 1 / d.z}; }

bool hits(const Bounds3& b, const Vec3& o, const Vec3& d, double t_max = kInfinity) {
  return intersect_bounds(b, o, inverse(d), t_max);
}

const Bounds3 kUnitBox{{0, 0, 0}, {1, 1, 1}};

TEST(Bounds3, ExtendCentroidArea) {
  Bounds3 b;
  EXPECT_TRUE(b.empty());
  EXPECT_EQ(b.surface_area(), 0);
  b.extend(Vec3{0, 0, 0});
  b.extend(Vec3{1, 2, 3});
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.centroid(), (Vec3{0.5, 1, 1.5}));
  EXPECT_EQ(b.surface_area(), 2 * (2 + 6 + 3));
}

TEST(Bounds3, TransformedHoldsAllCorners) {
  const Affine r = *Affine::rotation(45, {0, 0, 1});
  const Bounds3 b =
      Bounds3{{-1, -1, -1}, {1, 1, 1}}.transformed(Affine::translation({10, 0, 0}) * r);
  const double s = std::sqrt(2.0);
  EXPECT_NEAR(b.lo.x, 10 - s, 1e-14);
  EXPECT_NEAR(b.hi.x, 10 + s, 1e-14);
  EXPECT_NEAR(b.lo.y, -s, 1e-14);
  EXPECT_NEAR(b.hi.y, s, 1e-14);
  EXPECT_EQ(b.lo.z, -1);
  EXPECT_EQ(b.hi.z, 1);
  // A mirror swaps lo and hi, and the result is still ordered.
  const Bounds3 m = kUnitBox.transformed(Affine::scaling({-2, 1, 1}));
  EXPECT_EQ(m.lo, (Vec3{-2, 0, 0}));
  EXPECT_EQ(m.hi, (Vec3{0, 1, 1}));
  EXPECT_TRUE(Bounds3{}.transformed(r).empty());
}

TEST(IntersectBounds, HitsAndMisses) {
  EXPECT_TRUE(hits(kUnitBox, {-1, 0.5, 0.5}, {1, 0, 0}));
  EXPECT_TRUE(hits(kUnitBox, {-1, -1, -1}, {1, 1, 1}));
  EXPECT_FALSE(hits(kUnitBox, {-1, 2, 0.5}, {1, 0, 0}));
  EXPECT_FALSE(hits(kUnitBox, {-1, 0.5, 0.5}, {-1, 0, 0}));  // box behind the ray
  EXPECT_FALSE(hits(kUnitBox, {-1, -1, 0.5}, {1, -1, 0}));
  EXPECT_TRUE(hits(kUnitBox, {0.5, 0.5, 0.5}, {0.3, -0.2, 0.1}));  // origin inside
  EXPECT_FALSE(hits(Bounds3{}, {0, 0, 0}, {1, 1, 1}));             // empty box
  EXPECT_FALSE(hits(Bounds3{}, {0, 0, 0}, {1, 0, 0}));
}

TEST(IntersectBounds, RespectsTMax) {
  EXPECT_FALSE(hits(kUnitBox, {-3, 0.5, 0.5}, {1, 0, 0}, 2.5));
  EXPECT_TRUE(hits(kUnitBox, {-3, 0.5, 0.5}, {1, 0, 0}, 3.5));
  EXPECT_TRUE(hits(kUnitBox, {-3, 0.5, 0.5}, {1, 0, 0}, 3));  // touches the near face
  EXPECT_FALSE(hits(kUnitBox, {-3, 0.5, 0.5}, {2, 0, 0}, 1.4));
}

TEST(IntersectBounds, AxisParallelRaysAndOriginsOnSlabPlanes) {
  // Direction components are zero (and -0): the slab of that axis is in or out as a whole.
  EXPECT_TRUE(hits(kUnitBox, {0.5, 0.5, -2}, {0, 0, 1}));
  EXPECT_TRUE(hits(kUnitBox, {0.5, 0.5, -2}, {-0.0, 0.0, 1}));
  EXPECT_FALSE(hits(kUnitBox, {1.5, 0.5, -2}, {0, 0, 1}));
  // The origin lies exactly on a slab plane with a zero direction component: (lo - o) * inf
  // would be NaN; the ray runs along the face and touches the closed box.
  EXPECT_TRUE(hits(kUnitBox, {0, 0.5, -2}, {0, 0, 1}));
  EXPECT_TRUE(hits(kUnitBox, {0, 0.5, -2}, {-0.0, 0, 1}));
  EXPECT_TRUE(hits(kUnitBox, {1, 1, -2}, {-0.0, -0.0, 1}));  // along an edge
  EXPECT_FALSE(hits(kUnitBox, {std::nextafter(1.0, 2.0), 0.5, -2}, {0, 0, 1}));
  // A flat box (an axis-aligned triangle's bounds) seen edge-on and face-on.
  const Bounds3 flat{{0, 0, 0}, {1, 1, 0}};
  EXPECT_TRUE(hits(flat, {-1, 0.5, 0}, {1, 0, 0}));
  EXPECT_TRUE(hits(flat, {0.5, 0.5, 1}, {0, 0, -1}));
  EXPECT_FALSE(hits(flat, {-1, 0.5, 1e-300}, {1, 0, 0}));
}

TEST(IntersectBounds, GrazingRayIsNotCulledByRounding) {
  // Rays that touch the box only along its edge x = 0.1, y = 0: they enter the y slab and
  // leave the x slab at the same t = v * (1 / v), which rounds to either side of 1.
  const Bounds3 box{{0, 0, 0}, {0.1, 0.7, 0.3}};
  int culled_without_enlargement = 0;
  for (int i = 1; i < 2000; ++i) {
    const Vec3 origin{-0.37 * i, -0.013 * (i % 97 + 1) * i, 0.15};
    const Vec3 d = Vec3{0.1, 0, 0.15} - origin;
    EXPECT_TRUE(hits(box, origin, d)) << i;
    const Vec3 inv = inverse(d);
    if ((0 - origin.y) * inv.y > (0.1 - origin.x) * inv.x) ++culled_without_enlargement;
  }
  // The case the enlargement exists for does occur.
  EXPECT_GT(culled_without_enlargement, 0);
}

}  // namespace
}  // namespace tessera
