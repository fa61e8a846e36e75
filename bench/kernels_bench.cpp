// The tracer's inner kernels: ray/shape intersection and BVH traversal.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "common/geometry/instance.h"
#include "common/geometry/shapes.h"

namespace tessera {
namespace {

// Rays from a sphere of radius 4 towards random points near the origin: about half hit.
std::vector<Ray> random_rays(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 o = normalize_or({u(rng), u(rng), u(rng)}, {0, 0, 1}) * 4;
    const Vec3 target{u(rng) * 1.5, u(rng) * 1.5, u(rng) * 1.5};
    rays.push_back(Ray{o, normalize_or(target - o, {0, 0, -1}), 0});
  }
  return rays;
}

template <typename Intersect>
void run_kernel(benchmark::State& state, Intersect&& intersect) {
  const std::vector<Ray> rays = random_rays(4096);
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    LocalHit hit;
    hits += intersect(rays[i++ & 4095], hit) ? 1 : 0;
    benchmark::DoNotOptimize(hit);
  }
  state.counters["hit_rate"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}

void BM_Sphere(benchmark::State& state) {
  run_kernel(state, [](const Ray& r, LocalHit& h) { return intersect_sphere(r, kInfinity, h); });
}
void BM_Cube(benchmark::State& state) {
  run_kernel(state, [](const Ray& r, LocalHit& h) { return intersect_cube(r, kInfinity, h); });
}
void BM_Cone(benchmark::State& state) {
  const TaperedCylinder cone{0, false};
  run_kernel(state, [&](const Ray& r, LocalHit& h) {
    return intersect_tapered_cylinder(cone, r, kInfinity, h);
  });
}
// A ring torus (R = 1, r = 0.4), from the rays above: about a third hit.
void BM_Torus(benchmark::State& state) {
  const Torus torus{0.4, 1};
  run_kernel(state,
             [&](const Ray& r, LocalHit& h) { return intersect_torus(torus, r, kInfinity, h); });
}
// Rays within 1e-6 of tangent to the top of the tube: near-double roots, the solver's worst
// case (their critical points must be told from roots).
void BM_TorusGrazing(benchmark::State& state) {
  const Torus torus{0.4, 1};
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Ray> rays;
  for (int i = 0; i < 4096; ++i) {
    const Vec3 o{-4, u(rng) * 0.5, 0.4 + u(rng) * 1e-6};
    rays.push_back(Ray{o, normalize_or({1, u(rng) * 0.1, 0}, {1, 0, 0}), 0});
  }
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    LocalHit hit;
    hits += intersect_torus(torus, rays[i++ & 4095], kInfinity, hit) ? 1 : 0;
    benchmark::DoNotOptimize(hit);
  }
  state.counters["hit_rate"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}
// The tooth cube, a quartic algebraic surface; t up to 10 holds its extent for these rays.
void BM_ToothCube(benchmark::State& state) {
  const AlgebraicSurface tooth{AlgebraicKind::ToothCube, {3, 3, 3}};
  run_kernel(state,
             [&](const Ray& r, LocalHit& h) { return intersect_algebraic(tooth, r, 0, 10, h); });
}
void BM_TransformedSphereInstance(benchmark::State& state) {
  const Affine t = Affine::translation({0.1, 0.2, 0.3}) * Affine::rotation(30, {1, 1, 0}).value() *
                   Affine::scaling({1.2, 0.8, 1});
  const Instance instance = make_instance(Sphere{}, t, nullptr).value();
  const std::vector<Ray> rays = random_rays(4096);
  IntersectionCounters counters;
  std::size_t i = 0;
  for (auto _ : state) {
    WorldHit hit;
    benchmark::DoNotOptimize(
        intersect_instance(instance, rays[i++ & 4095], kInfinity, hit, counters));
  }
  state.SetItemsProcessed(state.iterations());
}

// A mesh of n x n quads (2 n^2 triangles) bent into a wave, traversed through its BVH.
Mesh wave_mesh(int n) {
  Mesh mesh;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      mesh.positions.push_back({x, y, 0.2 * std::sin(6 * x) * std::cos(5 * y)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto v = [&](int a, int b) { return static_cast<std::uint32_t>(b * (n + 1) + a); };
      mesh.triangles.push_back(MeshTriangle{{v(i, j), v(i + 1, j), v(i + 1, j + 1)}});
      mesh.triangles.push_back(MeshTriangle{{v(i, j), v(i + 1, j + 1), v(i, j + 1)}});
    }
  return mesh;
}

void BM_MeshBvh(benchmark::State& state) {
  const Mesh mesh = wave_mesh(static_cast<int>(state.range(0)));
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const std::vector<Ray> rays = random_rays(4096);
  IntersectionCounters counters;
  std::size_t i = 0;
  for (auto _ : state) {
    LocalHit hit;
    benchmark::DoNotOptimize(
        intersect_mesh(accel, false, rays[i++ & 4095], kInfinity, hit, counters));
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
  state.counters["tests_per_ray"] =
      static_cast<double>(counters.triangle_tests) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}

// Arguments: the wave mesh's size, the build's threads.
void BM_MeshBvhBuild(benchmark::State& state) {
  const Mesh mesh = wave_mesh(static_cast<int>(state.range(0)));
  const auto threads = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(build_mesh_accel(mesh, BvhMode::Sah, threads));
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}

BENCHMARK(BM_Sphere);
BENCHMARK(BM_Cube);
BENCHMARK(BM_Cone);
BENCHMARK(BM_Torus);
BENCHMARK(BM_TorusGrazing);
BENCHMARK(BM_ToothCube);
BENCHMARK(BM_TransformedSphereInstance);
BENCHMARK(BM_MeshBvh)->Arg(16)->Arg(64)->Arg(224);
BENCHMARK(BM_MeshBvhBuild)
    ->Args({224, 1})
    ->Args({224, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tessera
