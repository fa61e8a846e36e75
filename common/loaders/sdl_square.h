// The generic square of Hill's SDL (F.S. Hill, "Computer Graphics Using OpenGL", ch. 14): the
// part of the plane z = 0 with |x| <= 1 and |y| <= 1, facing +z.
#pragma once

#include "common/scene/mesh.h"

namespace tessera {

// Two triangles, counter-clockwise seen from +z, so that the geometric normal is +z.
Mesh hill_square_mesh();

}  // namespace tessera
