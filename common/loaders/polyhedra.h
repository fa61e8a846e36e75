// The polyhedra of SDL §3.3.1 as triangle meshes, so that they share the watertight triangle
// test and the mesh BVH. The manual gives no sizes: each is centred on the origin and fits the
// unit sphere (docs/SDL.md lists the shapes and orientations).
#pragma once

#include "common/scene/mesh.h"

namespace tessera {

enum class Polyhedron {
  Buckyball,
  Diamond,
  Dodecahedron,
  Icosahedron,
  Octahedron,
  Pyramid,
  Tetrahedron
};

// The polyhedron's faces, convex polygons fan-triangulated and wound counter-clockwise seen
// from outside (so that the geometric normals point out), without vertex normals: it is meant
// to be flat shaded.
Mesh polyhedron_mesh(Polyhedron which);

}  // namespace tessera
