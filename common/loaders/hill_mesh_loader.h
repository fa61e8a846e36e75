// The mesh files of Hill's SDL (§3.3.4): 3VN (vertices, normals, faces with a vertex and a
// normal index per corner), 3DV (a normal stored with every vertex) and 3DM (vertices only:
// each vertex gets the area-weighted mean of its faces' normals). All three are
// whitespace-separated numbers with 0-based indices, as Hill's Mesh::readFile reads them;
// polygons are fan-triangulated. Unlike OBJ they are not unitized: the manual says so of OBJ
// only.
#pragma once

#include <string>
#include <string_view>

#include "common/scene/mesh.h"

namespace tessera {

// Each throws SceneError naming `file`, line and column on malformed input.
Mesh load_3vn(std::string_view text, const std::string& file);
Mesh load_3dv(std::string_view text, const std::string& file);
Mesh load_3dm(std::string_view text, const std::string& file);

}  // namespace tessera
