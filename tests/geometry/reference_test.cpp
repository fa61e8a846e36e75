// Randomised property test: random rays at randomly placed shapes (uniform scales 1e-4..1e4,
// any rotation, translations up to 1e8) against a long-double reference intersector that
// inverts the same transform and solves in object space with 64-bit mantissas. The double
// routine must find the same nearest hit, within 16 units of the rounding the world
// coordinates allow (eps * coordinate magnitude / cos; the worst seen is about 3), except at
// grazing incidence (|cos| < 1e-4), where hit and miss are both within rounding.
// Each shape has its own seed, printed with every failure, so any failure reproduces.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <string>

#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"
#include "common/math/float_error.h"
#include "tests/geometry/test_meshes.h"

namespace tessera {
namespace {

using LD = long double;

struct VecL {
  LD x = 0, y = 0, z = 0;
};
VecL operator+(const VecL& a, const VecL& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
VecL operator*(const VecL& a, LD s) { return {a.x * s, a.y * s, a.z * s}; }
LD dot(const VecL& a, const VecL& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct RayL {
  VecL o, d;
  VecL at(LD t) const { return o + d * t; }
};

// The world ray in the object space of `to_world`, exactly to long-double rounding: the
// inverse is taken in long double from the double matrix, which defines the surface.
RayL to_object(const Affine& to_world, const Ray& ray) {
  LD a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = to_world.m[i][j];
  const LD c[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[0][2] * a[2][1] - a[0][1] * a[2][2],
                       a[0][1] * a[1][2] - a[0][2] * a[1][1]},
                      {a[1][2] * a[2][0] - a[1][0] * a[2][2], a[0][0] * a[2][2] - a[0][2] * a[2][0],
                       a[0][2] * a[1][0] - a[0][0] * a[1][2]},
                      {a[1][0] * a[2][1] - a[1][1] * a[2][0], a[0][1] * a[2][0] - a[0][0] * a[2][1],
                       a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
  const LD det = a[0][0] * c[0][0] + a[0][1] * c[1][0] + a[0][2] * c[2][0];
  const LD p[3] = {LD(ray.origin.x) - to_world.m[0][3], LD(ray.origin.y) - to_world.m[1][3],
                   LD(ray.origin.z) - to_world.m[2][3]};
  const LD v[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  LD o[3], d[3];
  for (int i = 0; i < 3; ++i) {
    o[i] = (c[i][0] * p[0] + c[i][1] * p[1] + c[i][2] * p[2]) / det;
    d[i] = (c[i][0] * v[0] + c[i][1] * v[1] + c[i][2] * v[2]) / det;
  }
  return {{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
}

struct ReferenceHit {
  LD t = 0;
  VecL normal;  // object space, not necessarily unit
};

// The smaller positive root of a t^2 + 2 b t + c = 0 (cancellation-free).
std::optional<LD> nearest_positive_root(LD a, LD b, LD c) {
  const LD disc = b * b - a * c;
  if (disc < 0 || a == 0) return std::nullopt;
  const LD q = -(b + std::copysign(std::sqrt(disc), b));
  LD t0 = q / a, t1 = q != 0 ? c / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > 0) return t0;
  if (t1 > 0) return t1;
  return std::nullopt;
}

std::optional<ReferenceHit> reference_sphere(const RayL& r) {
  const std::optional<LD> t =
      nearest_positive_root(dot(r.d, r.d), dot(r.o, r.d), dot(r.o, r.o) - 1);
  if (!t) return std::nullopt;
  return ReferenceHit{*t, r.at(*t)};
}

std::optional<ReferenceHit> reference_cube(const RayL& r) {
  const LD o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
  LD t_in = -INFINITY, t_out = INFINITY;
  int in_axis = 0, out_axis = 0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (std::fabs(o[i]) > 1) return std::nullopt;
      continue;
    }
    LD a = (-1 - o[i]) / d[i], b = (1 - o[i]) / d[i];
    if (a > b) std::swap(a, b);
    if (a > t_in) t_in = a, in_axis = i;
    if (b < t_out) t_out = b, out_axis = i;
  }
  if (t_in > t_out || t_out <= 0) return std::nullopt;
  const LD t = t_in > 0 ? t_in : t_out;
  const int axis = t_in > 0 ? in_axis : out_axis;
  VecL n;
  (axis == 0   ? n.x
   : axis == 1 ? n.y
               : n.z) = (axis == 0   ? r.at(t).x
                         : axis == 1 ? r.at(t).y
                                     : r.at(t).z) > 0
                            ? 1
                            : -1;
  return ReferenceHit{t, n};
}

// The first sign change of the torus's implicit function along the ray inside its bounding
// box, sampled finely and bisected to long-double precision. Root pairs closer than a sample
// are missed: those are grazing rays, which the comparison tolerates.
std::optional<ReferenceHit> reference_torus(const RayL& r, LD tube, LD ring) {
  const auto f = [&](LD t) {
    const VecL p = r.at(t);
    const LD s = dot(p, p) + ring * ring - tube * tube;
    return s * s - 4 * ring * ring * (p.x * p.x + p.y * p.y);
  };
  const LD extent[3] = {ring + tube, ring + tube, tube};
  const LD o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
  LD t0 = 0, t1 = INFINITY;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (std::fabs(o[i]) > extent[i]) return std::nullopt;
      continue;
    }
    LD a = (-extent[i] - o[i]) / d[i], b = (extent[i] - o[i]) / d[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (!(t0 < t1)) return std::nullopt;
  constexpr int kSamples = 2048;
  LD previous_t = t0, previous = f(t0);
  for (int k = 1; k <= kSamples; ++k) {
    const LD t = t0 + (t1 - t0) * k / kSamples;
    const LD value = f(t);
    if ((value < 0) != (previous < 0)) {
      LD lo = previous_t, hi = t;
      for (int i = 0; i < 80; ++i) {
        const LD mid = (lo + hi) / 2;
        ((f(mid) < 0) == (previous < 0) ? lo : hi) = mid;
      }
      const VecL p = r.at(lo);
      const LD s = dot(p, p) + ring * ring - tube * tube;
      return ReferenceHit{
          lo, {4 * p.x * (s - 2 * ring * ring), 4 * p.y * (s - 2 * ring * ring), 4 * p.z * s}};
    }
    previous_t = t;
    previous = value;
  }
  return std::nullopt;
}

// A similarity transform: uniform scale 1e-4..1e4, any rotation, translation up to 1e8.
Affine random_similarity(std::mt19937_64& rng, double& scale) {
  std::uniform_real_distribution<double> unit(0, 1);
  scale = std::pow(10, 8 * unit(rng) - 4);
  const Vec3 t = testing::random_unit(rng) * (unit(rng) < 0.1 ? 0 : std::pow(10, 8 * unit(rng)));
  return Affine::translation(t) * *Affine::rotation(360 * unit(rng), testing::random_unit(rng)) *
         Affine::scaling({scale, scale, scale});
}

// The cosine between the unit ray direction and a (not necessarily unit) normal.
LD cosine(const VecL& d, const VecL& n) {
  return std::fabs(dot(d, n)) / std::sqrt(dot(d, d) * dot(n, n));
}

template <typename Reference>
void compare_with_reference(const char* name, const ShapeGeometry& shape, std::uint64_t seed,
                            Reference reference) {
  SCOPED_TRACE(::testing::Message() << name << ", seed " << seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  int hits = 0, grazing = 0, failures = 0;
  double worst = 0;  // the largest error in units of the tolerance's rounding unit
  constexpr int kTransforms = 100, kRays = 30;
  for (int i = 0; i < kTransforms; ++i) {
    double scale = 1;
    const Affine to_world = random_similarity(rng, scale);
    const std::optional<Instance> inst = make_instance(shape, to_world, nullptr);
    ASSERT_TRUE(inst);
    const Bounds3 local = object_bounds(shape, nullptr);
    const double size = length(inst->world_bounds.diagonal());
    IntersectionCounters counters;
    for (int k = 0; k < kRays; ++k) {
      const Vec3 aim{unit(rng), unit(rng), unit(rng)};
      const Vec3 target = to_world.apply_point(local.lo + mul(local.diagonal(), aim));
      const Vec3 origin = target + testing::random_unit(rng) * (size * (1 + 4 * unit(rng)));
      const Ray ray{origin, target - origin};
      WorldHit hit;
      const bool found = intersect_instance(*inst, ray, kInfinity, hit, counters);
      const RayL object_ray = to_object(to_world, ray);
      const std::optional<ReferenceHit> expected = reference(object_ray);
      const auto fail = [&](const std::string& what) {
        if (++failures <= 5)
          ADD_FAILURE() << "transform " << i << " ray " << k << ": " << what << " (scale " << scale
                        << ", origin " << origin.x << " " << origin.y << " " << origin.z << ")";
      };
      if (expected) {
        const LD cos_expected = cosine(object_ray.d, expected->normal);
        if (cos_expected < 1e-4) {
          ++grazing;  // hit or miss are both within rounding of the silhouette
          continue;
        }
        if (!found) {
          fail("missed; the reference hits at t " + std::to_string(double(expected->t)) +
               " with cos " + std::to_string(double(cos_expected)));
          continue;
        }
        ++hits;
        // The rounding the world coordinates allow, magnified by 1/cos along the ray.
        const double magnitude = max_component(abs(origin)) + max_component(abs(target)) + size;
        const double rounding_unit = kMachineEpsilon * magnitude / double(cos_expected);
        const double tolerance = 16 * rounding_unit;
        const double distance = std::fabs(double(hit.t - expected->t)) * length(ray.direction);
        worst = std::max(worst, distance / rounding_unit);
        if (!(distance <= tolerance))
          fail("t " + std::to_string(hit.t) + " differs from the reference by " +
               std::to_string(distance) + " > " + std::to_string(tolerance));
      } else if (found) {
        if (std::fabs(dot(hit.normal, normalize_or(ray.direction, {}))) < 1e-4) {
          ++grazing;
          continue;
        }
        fail("hit at t " + std::to_string(hit.t) + " where the reference misses");
      }
    }
  }
  EXPECT_EQ(failures, 0);
  ::testing::Test::RecordProperty(std::string(name) + "_worst_in_rounding_units",
                                  std::to_string(worst));
  EXPECT_GT(hits, kTransforms * kRays / 4);
  EXPECT_LT(grazing, kTransforms * kRays / 100);
}

TEST(Reference, SphereAgainstLongDouble) {
  compare_with_reference("sphere", Sphere{}, 401, reference_sphere);
}

TEST(Reference, CubeAgainstLongDouble) {
  compare_with_reference("cube", Cube{}, 402, reference_cube);
}

TEST(Reference, TorusAgainstLongDouble) {
  for (const Torus& torus : {Torus{0.5, 1}, Torus{0.1, 1}, Torus{1, 1}, Torus{0.9, 0.5}}) {
    SCOPED_TRACE(::testing::Message()
                 << "torus " << torus.tube_radius << " " << torus.torus_radius);
    compare_with_reference("torus", torus, 403, [&](const RayL& r) {
      return reference_torus(r, torus.tube_radius, torus.torus_radius);
    });
  }
}

}  // namespace
}  // namespace tessera
