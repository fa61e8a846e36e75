#include "common/loaders/sdl_square.h"

namespace tessera {

Mesh hill_square_mesh() {
  Mesh mesh;
  mesh.source = "square";
  mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  MeshTriangle lower, upper;
  lower.v = {0, 1, 2};
  upper.v = {0, 2, 3};
  mesh.triangles = {lower, upper};
  return mesh;
}

}  // namespace tessera
