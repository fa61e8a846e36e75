// The same rays through Embree 3 and through Tessera's mesh acceleration (issue 18 §2): coherent
// camera rays, shadow rays (occlusion) and incoherent rays, on one and two threads. Both
// engines trace in the same process, interleaved repeat by repeat, so that the load of a shared
// machine cancels out of the ratio Tessera / Embree (higher is better; 1 is Embree's pace).
//
//   tessera-embree-bench [--repeats N] [--width W] [--height H] [--cpu-time] [--smoke] [--counts]
//                        [--rays camera|shadow|incoherent] [--embree-config CONFIG] [OBJ...]
//
// --cpu-time times each engine by its threads' CPU time (the busiest thread's) instead of the
// wall clock: on a machine shared with other jobs a thread waits for a core much of the time,
// which wall times count and this does not (caches are still shared, so it is not immune).
// Without OBJ files it traces the built-in teapot (6,320 triangles). --smoke traces a tiny
// image once and fails when the engines disagree on which rays hit, so that CTest keeps the
// benchmark from rotting; its speeds mean nothing. --counts prints, instead of timing, Tessera's
// tree (its SAH cost, wide_bvh_cost) and the nodes visited and triangles tested a ray of each
// kind: they show what a change of the tree does, without the noise of times. --rays traces
// only the rays of one kind (still made from the camera rays' hits), so that a profile
// (perf record) shows that kind alone. --embree-config passes its text to rtcNewDevice: "isa=avx2"
// pins Embree to the AVX2 kernels Tessera's traversal uses (by default Embree picks the widest
// ISA the CPU has, AVX-512 on recent Intel and AMD parts), "verbose=1" prints what it chose.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/accel/mesh_accel.h"
#include "common/geometry/shapes.h"
#include "common/loaders/obj_loader.h"
#include "common/loaders/teapot.h"
#include "common/stats/thread_cpu_clock.h"

namespace tessera {
namespace {

enum class RayKind { Camera, Shadow, Incoherent };
const char* kind_name(RayKind kind) {
  switch (kind) {
    case RayKind::Camera:
      return "camera (closest)";
    case RayKind::Shadow:
      return "shadow (any hit)";
    case RayKind::Incoherent:
      return "incoherent (closest)";
  }
  return "";
}

RayKind parse_kind(const std::string& name) {
  for (const RayKind kind : {RayKind::Camera, RayKind::Shadow, RayKind::Incoherent})
    if (std::string(kind_name(kind)).starts_with(name + " ")) return kind;
  throw std::runtime_error("unknown ray kind " + name + " (camera, shadow or incoherent)");
}

struct RaySet {
  RayKind kind;
  std::vector<Ray> rays;
  std::vector<double> t_max;
};

struct Options {
  int repeats = 3;
  int width = 640;
  int height = 480;
  bool smoke = false;
  bool cpu_time = false;
  bool counts = false;
  std::optional<RayKind> only;  // --rays
  std::string embree_config;    // --embree-config
  std::vector<std::string> meshes;
};

// The view and key light of bench/povray/teapot100k.sdl (the mesh unitized, not rotated).
const Vec3 kEye{0.6, 1.6, 3.6};
const Vec3 kLookAt{0, -0.05, 0};
const Vec3 kLight{3, 5, 4};
constexpr double kLightRadius = 0.5;
constexpr double kFieldOfViewDegrees = 40;
// Secondary rays start this far off the surface along its normal (the unitized mesh spans 2).
constexpr double kOffset = 1e-4;

Vec3 unit(const Vec3& v) { return v * (1 / length(v)); }

std::vector<Ray> camera_rays(int width, int height) {
  const Vec3 forward = unit(kLookAt - kEye);
  const Vec3 right = unit(cross(forward, Vec3{0, 1, 0}));
  const Vec3 up = cross(right, forward);
  const double half_height = std::tan(kFieldOfViewDegrees * M_PI / 360);
  const double half_width = half_height * width / height;
  std::vector<Ray> rays;
  rays.reserve(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double u = (2 * (x + 0.5) / width - 1) * half_width;
      const double v = (1 - 2 * (y + 0.5) / height) * half_height;
      rays.push_back({kEye, unit(forward + right * u + up * v)});
    }
  return rays;
}

// Camera rays, then as many shadow rays towards points of a spherical light and random
// hemisphere rays from the points the camera rays hit (found by Tessera, cycled through; both
// engines then trace exactly these rays).
std::vector<RaySet> make_rays(const MeshAccel& accel, int width, int height) {
  RaySet camera{RayKind::Camera, camera_rays(width, height), {}};
  camera.t_max.assign(camera.rays.size(), kInfinity);
  std::vector<Ray> surface;  // origin off the surface, direction its normal towards the eye
  IntersectionCounters counters;
  for (const Ray& ray : camera.rays) {
    LocalHit hit;
    if (!intersect_mesh(accel, false, ray, kInfinity, hit, counters)) continue;
    Vec3 n = unit(hit.normal);
    if (dot(n, ray.direction) > 0) n = -n;
    surface.push_back({hit.point + n * kOffset, n});
  }
  RaySet shadow{RayKind::Shadow, {}, {}}, incoherent{RayKind::Incoherent, {}, {}};
  std::mt19937_64 rng(18);
  std::normal_distribution<double> gauss;
  const auto random_unit = [&] { return unit(Vec3{gauss(rng), gauss(rng), gauss(rng)}); };
  for (std::size_t i = 0; !surface.empty() && i < camera.rays.size(); ++i) {
    const Ray& s = surface[i % surface.size()];
    const Vec3 to_light = kLight + random_unit() * kLightRadius - s.origin;
    shadow.rays.push_back({s.origin, unit(to_light)});
    shadow.t_max.push_back(length(to_light));
    Vec3 d = random_unit();
    if (dot(d, s.direction) < 0) d = -d;
    incoherent.rays.push_back({s.origin, d});
    incoherent.t_max.push_back(kInfinity);
  }
  return {std::move(camera), std::move(shadow), std::move(incoherent)};
}

class EmbreeMesh {
 public:
  EmbreeMesh(const Mesh& mesh, const std::string& config) : device_(rtcNewDevice(config.c_str())) {
    scene_ = rtcNewScene(device_);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
      for (int a = 0; a < 3; ++a) vertices[3 * i + a] = static_cast<float>(mesh.positions[i][a]);
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      for (int k = 0; k < 3; ++k) indices[3 * i + k] = mesh.triangles[i].v[k];
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene_);
  }
  ~EmbreeMesh() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeMesh(const EmbreeMesh&) = delete;
  EmbreeMesh& operator=(const EmbreeMesh&) = delete;

  // Returns the number of rays that hit.
  std::size_t trace(const RaySet& set, std::size_t begin, std::size_t end) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    std::size_t hits = 0;
    for (std::size_t i = begin; i < end; ++i) {
      RTCRayHit rh;
      const Ray& r = set.rays[i];
      rh.ray.org_x = static_cast<float>(r.origin.x);
      rh.ray.org_y = static_cast<float>(r.origin.y);
      rh.ray.org_z = static_cast<float>(r.origin.z);
      rh.ray.dir_x = static_cast<float>(r.direction.x);
      rh.ray.dir_y = static_cast<float>(r.direction.y);
      rh.ray.dir_z = static_cast<float>(r.direction.z);
      rh.ray.tnear = 0;
      rh.ray.tfar = static_cast<float>(set.t_max[i]);
      rh.ray.time = 0;
      rh.ray.mask = 0xffffffffu;
      rh.ray.id = 0;
      rh.ray.flags = 0;
      if (set.kind == RayKind::Shadow) {
        rtcOccluded1(scene_, &context, &rh.ray);
        hits += rh.ray.tfar < 0;
      } else {
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
    }
    return hits;
  }

 private:
  RTCDevice device_;
  RTCScene scene_;
};

std::size_t trace_tessera(const MeshAccel& accel, const RaySet& set, std::size_t begin,
                          std::size_t end) {
  IntersectionCounters counters;
  std::size_t hits = 0;
  // One hit record for the range, as Embree's loop fills its RTCRayHit without clearing it: made
  // in the loop, its zeroing was a `rep stos` of 112 bytes a ray, work a caller need not do
  // (intersect_instance hands shapes unzeroed records, local_hit.h's UnzeroedLocalHits).
  LocalHit hit;
  for (std::size_t i = begin; i < end; ++i) {
    if (set.kind == RayKind::Shadow)
      hits += occluded_mesh(accel, set.rays[i], set.t_max[i], counters);
    else
      hits += intersect_mesh(accel, false, set.rays[i], set.t_max[i], hit, counters);
  }
  return hits;
}

struct Timed {
  double seconds = 0;
  std::size_t hits = 0;
};

// Splits the rays into `threads` contiguous ranges, one per thread. Timed by the wall clock, or
// with `cpu_time` by the CPU time of the busiest thread.
Timed run(int threads, std::size_t count, bool cpu_time,
          const std::function<std::size_t(std::size_t, std::size_t)>& trace) {
  std::vector<std::size_t> hits(static_cast<std::size_t>(threads));
  std::vector<double> cpu_seconds(static_cast<std::size_t>(threads));
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      const std::size_t begin = count * t / threads, end = count * (t + 1) / threads;
      const auto cpu_start = ThreadCpuClock::now();
      hits[t] = trace(begin, end);
      cpu_seconds[t] = std::chrono::duration<double>(ThreadCpuClock::now() - cpu_start).count();
    });
  for (std::thread& thread : pool) thread.join();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  Timed timed{
      cpu_time ? *std::max_element(cpu_seconds.begin(), cpu_seconds.end()) : elapsed.count(), 0};
  for (const std::size_t h : hits) timed.hits += h;
  return timed;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

// Prints Tessera's tree and the work a ray of each kind does in it.
void count_mesh(const std::string& name, const Mesh& mesh, const Options& options) {
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  std::size_t children = 0, leaves = 0, leaf_positions = 0, gaps = 0;
  for (const BvhWideNode& node : accel.bvh.wide)
    for (int c = 0; c < kWideChildren; ++c) {
      if (node.boxes.bound[0][0][c] <= node.boxes.bound[0][1][c]) ++children;
      if (node.count[c] == 0) continue;
      ++leaves, leaf_positions += node.count[c];
      for (std::uint32_t i = node.child[c]; i < node.child[c] + node.count[c]; ++i)
        gaps += accel.bvh.primitive_order[i] == MeshAccel::kNoTriangle;
    }
  const WideBvhCost cost = wide_bvh_cost(accel.bvh, kMeshLeafTests);
  const auto ratio = [](std::size_t a, std::size_t b) {
    return static_cast<double>(a) / static_cast<double>(std::max<std::size_t>(b, 1));
  };
  std::printf(
      "%s: %zu wide nodes of %.2f children, %zu leaves of %.2f triangles and %.2f gaps; "
      "SAH: %.3f node steps + %.3f leaf tests a ray through the root's box\n\n",
      name.c_str(), accel.bvh.wide.size(), ratio(children, accel.bvh.wide.size()), leaves,
      ratio(leaf_positions - gaps, leaves), ratio(gaps, leaves), cost.node_steps, cost.leaf_tests);
  std::printf("| rays | wide nodes a ray | triangles tested a ray |\n| --- | --- | --- |\n");
  for (const RaySet& set : make_rays(accel, options.width, options.height)) {
    IntersectionCounters counters;
    for (std::size_t i = 0; i < set.rays.size(); ++i) {
      LocalHit hit;
      if (set.kind == RayKind::Shadow)
        occluded_mesh(accel, set.rays[i], set.t_max[i], counters);
      else
        intersect_mesh(accel, false, set.rays[i], set.t_max[i], hit, counters);
    }
    const double n = static_cast<double>(std::max<std::size_t>(set.rays.size(), 1));
    // bvh_nodes counts the root's box once a ray, then eight boxes a wide node.
    std::printf("| %s | %.2f | %.2f |\n", kind_name(set.kind),
                static_cast<double>(counters.bvh_nodes - set.rays.size()) / kWideChildren / n,
                static_cast<double>(counters.triangle_tests) / n);
  }
}

// Traces one mesh; prints its rows; returns false when the engines disagree on the hits.
bool bench_mesh(const std::string& name, const Mesh& mesh, const Options& options) {
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  const EmbreeMesh embree(mesh, options.embree_config);
  const std::vector<RaySet> sets = make_rays(accel, options.width, options.height);
  bool agree = true;
  for (const RaySet& set : sets)
    for (const int threads : {1, 2}) {
      if (options.only && set.kind != *options.only) continue;
      std::vector<double> embree_rate, tessera_rate, ratio;
      Timed e, t;
      for (int r = 0; r < options.repeats; ++r) {
        // Alternate which engine goes first so that a drift in load favours neither.
        const auto time_embree = [&] {
          e = run(threads, set.rays.size(), options.cpu_time,
                  [&](std::size_t b, std::size_t f) { return embree.trace(set, b, f); });
        };
        const auto time_tessera = [&] {
          t = run(threads, set.rays.size(), options.cpu_time,
                  [&](std::size_t b, std::size_t f) { return trace_tessera(accel, set, b, f); });
        };
        if (r % 2 == 0)
          time_embree(), time_tessera();
        else
          time_tessera(), time_embree();
        const double n = static_cast<double>(set.rays.size());
        embree_rate.push_back(n / e.seconds / 1e6);
        tessera_rate.push_back(n / t.seconds / 1e6);
        ratio.push_back(tessera_rate.back() / embree_rate.back());
      }
      // Float (Embree) and double (Tessera) differ only on rays that graze an edge.
      const double n = static_cast<double>(set.rays.size());
      const double disagreement =
          std::fabs(static_cast<double>(e.hits) - static_cast<double>(t.hits)) / std::max(n, 1.0);
      if (disagreement > 0.01) agree = false;
      std::printf("| %s | %zu | %s | %d | %.2f | %.2f | %.2f (%.2f–%.2f) | %.1f %% / %.1f %% |\n",
                  name.c_str(), mesh.triangles.size(), kind_name(set.kind), threads,
                  median(embree_rate), median(tessera_rate), median(ratio),
                  *std::min_element(ratio.begin(), ratio.end()),
                  *std::max_element(ratio.begin(), ratio.end()),
                  100 * static_cast<double>(e.hits) / std::max(n, 1.0),
                  100 * static_cast<double>(t.hits) / std::max(n, 1.0));
      std::fflush(stdout);
    }
  return agree;
}

Mesh read_obj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return load_obj(text.str(), path);
}

int main_impl(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&] {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      return std::stoi(argv[++i]);
    };
    if (arg == "--repeats")
      options.repeats = std::max(1, value());
    else if (arg == "--width")
      options.width = std::max(1, value());
    else if (arg == "--height")
      options.height = std::max(1, value());
    else if (arg == "--cpu-time")
      options.cpu_time = true;
    else if (arg == "--counts")
      options.counts = true;
    else if (arg == "--rays") {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      options.only = parse_kind(argv[++i]);
    } else if (arg == "--embree-config") {
      if (i + 1 >= argc) throw std::runtime_error(arg + " needs a value");
      options.embree_config = argv[++i];
    } else if (arg == "--smoke")
      options.smoke = true;
    else if (arg.starts_with("--"))
      throw std::runtime_error("unknown option " + arg);
    else
      options.meshes.push_back(arg);
  }
  if (options.smoke) options.width = 32, options.height = 24, options.repeats = 1;
  if (options.counts) {
    if (options.meshes.empty()) count_mesh("teapot", teapot_mesh(), options);
    for (const std::string& path : options.meshes)
      count_mesh(path.substr(path.find_last_of('/') + 1), read_obj(path), options);
    return 0;
  }
  std::printf("%d×%d camera rays; Mrays/s (%s) are medians of %d interleaved repeats\n\n",
              options.width, options.height, options.cpu_time ? "CPU time" : "wall clock",
              options.repeats);
  std::printf(
      "| mesh | triangles | rays | threads | Embree Mrays/s | Tessera Mrays/s "
      "| Tessera/Embree (min–max) | hits Embree / Tessera |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  bool agree = true;
  if (options.meshes.empty()) agree = bench_mesh("teapot", teapot_mesh(), options);
  for (const std::string& path : options.meshes) {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    agree = bench_mesh(name, read_obj(path), options) && agree;
  }
  if (!agree) {
    std::fprintf(stderr, "Embree and Tessera disagree on more than 1 %% of the hits\n");
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  try {
    return tessera::main_impl(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera-embree-bench: %s\n", e.what());
    return 2;
  }
}
