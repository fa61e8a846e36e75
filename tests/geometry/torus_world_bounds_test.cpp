// A torus instance's world box (make_instance): it holds every hit the instance reports, also
// at the box's faces, where rays graze the torus's extreme points, and it is the torus's own
// extent, not its object box's corners'.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "common/geometry/instance.h"
#include "common/math/float_error.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using testing::random_transform;
using testing::random_unit;

// Ring, horn, spindle and a thin ring: {tube radius r, torus radius R}.
const Torus kTori[] = {{0.4, 1.1}, {0.75, 0.75}, {0.9, 0.5}, {0.01, 1}};

// A point of the torus's surface (object space) at angles u about the axis, v about the tube.
Vec3 surface_point(const Torus& torus, double u, double v) {
  const double rho = torus.torus_radius + torus.tube_radius * std::cos(v);
  return {rho * std::cos(u), rho * std::sin(u), torus.tube_radius * std::sin(v)};
}

// The torus's point (object space) farthest along the object-space direction n: the core
// circle's farthest point, then r further along n.
Vec3 support_point(const Torus& torus, const Vec3& n) {
  const double in_plane = std::hypot(n.x, n.y);
  const Vec3 core = in_plane > 0 ? Vec3{n.x, n.y, 0} * (torus.torus_radius / in_plane) : Vec3{};
  return core + n * (torus.tube_radius / length(n));
}

// The torus's world point farthest towards `sign` on world axis `axis` (the support point along
// that direction, taken into object space by the transpose).
Vec3 extreme_point(const Torus& torus, const Affine& m, int axis, double sign) {
  Vec3 w{};
  w[axis] = sign;
  return m.apply_point(support_point(torus, m.apply_transpose(w)));
}

// f(torus, to_world, instance) for each torus of kTori under `count` random transforms.
template <class F>
void for_each_placed_torus(std::mt19937_64& rng, int count, const F& f) {
  for (const Torus& torus : kTori) {
    for (int k = 0; k < count; ++k) {
      SCOPED_TRACE(k);
      const Affine m = random_transform(rng);
      const std::optional<Instance> inst = make_instance(torus, m, nullptr);
      ASSERT_TRUE(inst.has_value());
      f(torus, m, *inst);
    }
  }
}

bool holds(const Bounds3& b, const Vec3& p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
         p.z <= b.hi.z;
}

TEST(TorusWorldBounds, HoldEveryHitAlsoAtTheirFaces) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0, 1);
  long hits = 0, face_hits = 0;
  for_each_placed_torus(rng, 300, [&](const Torus& torus, const Affine& m, const Instance& inst) {
    const Bounds3& box = inst.world_bounds;
    const double size = length(box.hi - box.lo);
    for (int i = 0; i < 60; ++i) {
      // Half the rays aimed at a point where the torus reaches a face of its box, grazing it along
      // the face or crossing it; the rest at random points of the surface.
      const int axis = i % 3;
      Vec3 target;
      Vec3 d = random_unit(rng);
      if (i % 2 == 0) {
        target = extreme_point(torus, m, axis, i % 4 == 0 ? 1 : -1);
        if (unit(rng) < 0.5) d[axis] = 0;  // along the face
      } else {
        target = m.apply_point(surface_point(torus, 2 * std::numbers::pi * unit(rng),
                                             2 * std::numbers::pi * unit(rng)));
      }
      if (length(d) == 0) continue;
      const Ray ray{target - d * (2 * size / length(d)), d};
      WorldHit hit;
      IntersectionCounters counters;
      if (!intersect_instance(inst, ray, kInfinity, hit, counters)) continue;
      ++hits;
      face_hits += i % 2 == 0;
      ASSERT_TRUE(holds(box, hit.point));
      // And so does the ray at the hit, up to the hit's error bound (which holds the rounding of
      // the object ray, from an origin as far as the translation, up to 1e8) and that of o + t d.
      const Vec3 q = ray.origin + ray.direction * hit.t;
      const Vec3 slack =
          hit.point_error + (abs(ray.origin) + abs(ray.direction * hit.t)) * gamma_bound(2);
      ASSERT_TRUE(holds(Bounds3{box.lo - slack, box.hi + slack}, q));
    }
  });
  EXPECT_GT(face_hits, 5000);
  EXPECT_GT(hits, 15000);
}

TEST(TorusWorldBounds, AreTheTorusOwnExtent) {
  std::mt19937_64 rng(18);
  for_each_placed_torus(rng, 100, [&](const Torus& torus, const Affine& m, const Instance& inst) {
    const Bounds3& box = inst.world_bounds;
    for (int axis = 0; axis < 3; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        // The farthest point, and the box's face no farther than the rounding beyond it.
        const double reach = extreme_point(torus, m, axis, sign)[axis];
        const double face = sign > 0 ? box.hi[axis] : box.lo[axis];
        const double extent = box.hi[axis] - box.lo[axis];
        EXPECT_GE(sign * (face - reach), 0);
        EXPECT_LE(sign * (face - reach), 1e-8 * extent + 1e-14 * std::fabs(m.m[axis][3]));
      }
    }
  });
}

}  // namespace
}  // namespace tessera
