#include "common/loaders/teapot.h"

#include "common/loaders/obj_loader.h"

namespace tessera {
namespace {

constexpr unsigned char kTeapotObj[] = {
#include "teapot_obj.inc"  // generated from scenes/meshes/teapot.obj (common/CMakeLists.txt)
};

}  // namespace

std::string_view teapot_obj() {
  return {reinterpret_cast<const char*>(kTeapotObj), sizeof kTeapotObj};
}

Mesh teapot_mesh() { return load_obj(teapot_obj(), "teapot"); }

}  // namespace tessera
