// The Utah teapot of SDL §3.3.3: scenes/meshes/teapot.obj (made by scripts/make_teapot.py from
// Newell's Bezier patches), compiled into the program. Like every OBJ it is unitized on load:
// centred on its bounding box, the spout-to-handle length spanning x in [-1, 1]; y is up, the
// spout points along +x.
#pragma once

#include <string_view>

#include "common/scene/mesh.h"

namespace tessera {

// The OBJ text as shipped.
std::string_view teapot_obj();

// The teapot mesh, with vertex normals for Phong shading; its source is "teapot".
Mesh teapot_mesh();

}  // namespace tessera
