// Triangle meshes as loaded from OBJ, 3VN, 3DV and 3DM files or built by the loader
// (polyhedra, teapot).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "common/math/vec3.h"
#include "common/scene/rgb.h"
#include "common/scene/tex_coord.h"

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
  // Optional attributes of the triangles' corners (VRML's Color and TextureCoordinate): empty,
  // or three per triangle, corner k of triangle i at 3 i + k in the order of MeshTriangle::v,
  // so that only meshes that have them pay for them. Colours replace the material's diffuse
  // colour (common/texture/surface_texture.h); texture coordinates replace shrink wrapping.
  std::vector<Rgb> corner_colours;
  std::vector<TexCoord> corner_tex_coords;
};

}  // namespace tessera
