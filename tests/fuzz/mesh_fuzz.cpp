// libFuzzer target: mesh files. The first byte picks the format (OBJ, 3VN, 3DV, 3DM), the rest
// is the file; a loaded mesh is built into a BVH and shot at with rays through its bounds.
// A scene error is a normal outcome; a crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/accel/mesh_accel.h"
#include "common/geometry/shapes.h"
#include "common/loaders/hill_mesh_loader.h"
#include "common/loaders/obj_loader.h"
#include "common/scene/source_location.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    Mesh mesh;
    switch (data[0] % 4) {
      case 0:
        mesh = load_obj(text, "mesh.obj");
        break;
      case 1:
        mesh = load_3vn(text, "mesh.3vn");
        break;
      case 2:
        mesh = load_3dv(text, "mesh.3dv");
        break;
      default:
        mesh = load_3dm(text, "mesh.3dm");
        break;
    }
    const MeshAccel accel = build_mesh_accel(mesh, BvhMode::Sah);
    const Bounds3 bounds = object_bounds(MeshShape{0, true}, &accel);
    if (bounds.empty()) return 0;
    IntersectionCounters counters;
    LocalHit hit;
    const Vec3 centre = bounds.centroid();
    for (const Vec3& d : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}, Vec3{1, 1, 1}})
      intersect_mesh(accel, true, {centre - d * 2 * length(bounds.diagonal()), d}, kInfinity, hit,
                     counters);
  } catch (const SceneError&) {
  }
  return 0;
}
