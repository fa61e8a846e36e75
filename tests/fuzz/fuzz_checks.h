// What the fuzz targets check on every input, shared with the replay of the regression corpus
// (tests/fuzz/regression_test.cpp) so that a saved input is checked exactly as the fuzzer
// checked it. A scene error is a normal outcome. Past survival, an input that loads must keep
// the invariants the tracer relies on:
//   - a mesh's bounds contain every vertex of its triangles, and an instance's world bounds
//     every vertex it places in the world;
//   - the BVH's nearest hit on the fuzzed mesh is brute force's, at the same t, within the
//     ray's range (0, t_max), and nothing is hit before it;
//   - rendered pixels are finite.
// A broken invariant throws InvariantViolation: it escapes the fuzz target, so libFuzzer
// reports a crash and saves the input, and it fails the replay test with its message.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/accel/mesh_accel.h"
#include "common/geometry/shapes.h"
#include "common/geometry/triangle.h"
#include "common/loaders/hill_mesh_loader.h"
#include "common/loaders/obj_loader.h"
#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"
#include "common/loaders/vrml_loader.h"
#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/scene/source_location.h"

namespace tessera::fuzz {

class InvariantViolation : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

inline void require(bool holds, const std::string& invariant) {
  if (!holds) throw InvariantViolation(invariant);
}

inline bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// `p`, give or take `slack` per component, lies in `b`.
inline bool inside(const Bounds3& b, const Vec3& p, const Vec3& slack = {}) {
  for (int a = 0; a < 3; ++a)
    if (p[a] + slack[a] < b.lo[a] || p[a] - slack[a] > b.hi[a]) return false;
  return true;
}

inline void check_mesh_bounds(const MeshAccel& accel) {
  for (const MeshTriangle& tri : accel.mesh->triangles)
    for (const std::uint32_t v : tri.v)
      require(inside(accel.bounds, accel.mesh->positions.at(v)),
              "a mesh vertex lies outside the mesh's bounds");
}

// The nearest hit with t in (0, t_max) by testing every triangle.
inline bool brute_force_hit(const Mesh& mesh, const Ray& ray, double t_max, double& t) {
  bool found = false;
  t = t_max;
  for (const MeshTriangle& tri : mesh.triangles) {
    TriangleHit h;
    if (intersect_triangle(mesh.positions[tri.v[0]], mesh.positions[tri.v[1]],
                           mesh.positions[tri.v[2]], ray, t, h)) {
      t = h.t;
      found = true;
    }
  }
  return found;
}

inline void check_ray(const MeshAccel& accel, const Ray& ray) {
  double nearest = 0;
  const bool expected = brute_force_hit(*accel.mesh, ray, kInfinity, nearest);
  IntersectionCounters counters;
  LocalHit hit;
  const bool found = intersect_mesh(accel, false, ray, kInfinity, hit, counters);
  require(found == expected, found ? "the BVH hits a mesh that brute force misses"
                                   : "the BVH misses a hit that brute force finds");
  if (!found) return;
  require(hit.t > 0 && hit.t < kInfinity, "a mesh hit lies outside the ray's range");
  require(hit.t == nearest, "the BVH's nearest hit is not brute force's");
  require(hit.part < accel.mesh->triangles.size(), "a mesh hit names no triangle");
  LocalHit nearer;
  require(!intersect_mesh(accel, false, ray, nearest, nearer, counters),
          "the BVH hits before the nearest hit (t_max not respected)");
}

// Rays from outside the bounds along a few fixed directions through their centre, and at the
// centres of up to 32 triangles, where most of them hit.
inline void check_mesh_hits(const MeshAccel& accel) {
  const Bounds3& b = accel.bounds;
  if (b.empty() || !finite(b.lo) || !finite(b.hi) || !std::isfinite(length(b.diagonal()))) return;
  const Mesh& mesh = *accel.mesh;
  const double reach = 2 * std::max(1.0, length(b.diagonal()));
  for (const Vec3& d :
       {Vec3{1, 0, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}, Vec3{1, 1, 1}, Vec3{-0.3, 0.7, 0.2}})
    check_ray(accel, {b.centroid() - d * reach, d});
  const std::size_t step = mesh.triangles.size() / 32 + 1;
  const Vec3 skew{0.31, -0.57, 0.76};
  for (std::size_t i = 0; i < mesh.triangles.size(); i += step) {
    const auto& v = mesh.triangles[i].v;
    const Vec3 centre = (mesh.positions[v[0]] + mesh.positions[v[1]] + mesh.positions[v[2]]) / 3;
    if (finite(centre)) check_ray(accel, {centre - skew * reach, skew});
  }
}

inline void check_mesh(const Mesh& mesh) {
  const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
  check_mesh_bounds(accel);
  check_mesh_hits(accel);
}

// Prepares the scene, checks the world bounds of its meshes, and renders a few pixels.
inline void check_scene(const Scene& scene) {
  const PreparedScene prepared(scene, BvhMode::Sah);
  for (const Instance& instance : prepared.instances()) {
    if (!instance.mesh || instance.motion) continue;
    check_mesh_bounds(*instance.mesh);
    for (const MeshTriangle& tri : instance.mesh->mesh->triangles)
      for (const std::uint32_t v : tri.v) {
        const Vec3& p = instance.mesh->mesh->positions[v];
        require(inside(instance.world_bounds, instance.to_world.apply_point(p),
                       instance.to_world.point_error(p, {})),
                "a mesh vertex placed in the world lies outside its instance's world bounds");
      }
  }
  RenderSettings settings;
  settings.width = 4;
  settings.height = 3;
  RenderStats stats;
  const Image image = render_image(prepared, settings, 1, stats);
  for (const float value : image.rgb)
    require(std::isfinite(value), "a rendered pixel is not finite");
}

// The inputs of the three targets. Each returns true when the input loaded and kept every
// invariant, false when it was refused with a SceneError.

inline bool check_sdl_input(std::string_view bytes) {
  MemorySource source;
  source.add("scene.sdl", std::string(bytes));
  // A lowered budget keeps each input fast (the defaults are tested in
  // tests/loaders/load_budget_test.cpp).
  LoadBudget budget;
  budget.max_objects = 2000;
  budget.max_lights = 100;
  budget.max_tokens = 1u << 20;
  try {
    check_scene(load_sdl(source, "scene.sdl", budget));
  } catch (const SceneError&) {
    return false;
  }
  return true;
}

// The first byte picks the format (OBJ, 3VN, 3DV, 3DM), the rest is the file.
inline bool check_mesh_input(std::string_view bytes) {
  if (bytes.empty()) return false;
  const std::string_view text = bytes.substr(1);
  try {
    switch (static_cast<unsigned char>(bytes[0]) % 4) {
      case 0:
        check_mesh(load_obj(text, "mesh.obj"));
        break;
      case 1:
        check_mesh(load_3vn(text, "mesh.3vn"));
        break;
      case 2:
        check_mesh(load_3dv(text, "mesh.3dv"));
        break;
      default:
        check_mesh(load_3dm(text, "mesh.3dm"));
        break;
    }
  } catch (const SceneError&) {
    return false;
  }
  return true;
}

// A world, plain or gzip, loaded with a lowered budget so that each input stays fast (the
// defaults are tested in tests/loaders/load_budget_test.cpp); the world may Inline itself.
inline bool check_vrml_input(std::string_view bytes) {
  const std::string world(bytes);
  MemorySource source;
  source.add("world.wrl", world);
  LoadBudget budget;
  budget.max_node_nesting = 64;
  budget.max_nodes = 5000;
  budget.max_bytes_read = 1u << 20;
  try {
    check_scene(load_vrml(source, "world.wrl", budget));
  } catch (const SceneError&) {
    return false;
  }
  return true;
}

}  // namespace tessera::fuzz
