// Wavefront OBJ meshes: vertices, normals, polygonal faces (fan-triangulated). As the manual
// says (§3.3.4), OBJ models are unitized on load: centred on their bounding box and scaled so
// that the largest extent spans [-1, 1].
#pragma once

#include <string>
#include <string_view>

#include "common/scene/mesh.h"

namespace tessera {

// Throws SceneError naming `file`, line and column on malformed input.
Mesh load_obj(std::string_view text, const std::string& file);

}  // namespace tessera
