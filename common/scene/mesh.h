// Triangle meshes as loaded from OBJ, 3VN, 3DV and 3DM files or built by the loader
// (polyhedra, teapot).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/math/vec3.h"

namespace tessera {

struct MeshTriangle {
  std::array<std::uint32_t, 3> v{};  // indices into Mesh::positions
  // Indices into Mesh::normals, or kNoNormal where the file gave none for that corner.
  std::array<std::uint32_t, 3> n{kNoNormal, kNoNormal, kNoNormal};
  static constexpr std::uint32_t kNoNormal = 0xffffffffu;
  friend bool operator==(const MeshTriangle&, const MeshTriangle&) = default;
};

struct Mesh {
  std::string source;  // the file it came from, for messages
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<MeshTriangle> triangles;  // polygons are fan-triangulated on load
};

}  // namespace tessera
