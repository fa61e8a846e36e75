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

// A mesh whose file name does not tell its format (Hill's programs read 3VN from any name, often
// `.txt`): the first of 3VN, 3DV and 3DM whose layout the numbers fit exactly, with at least one
// face. The counts at the start decide, since each layout must then use up the file to its last
// word (a small 3DM file can also read as a 3VN file with no faces). When none fits, the error
// is the one of the layout that read furthest; a file that does not start with a count is no
// Hill mesh at all.
Mesh load_hill_mesh(std::string_view text, const std::string& file);

}  // namespace tessera
