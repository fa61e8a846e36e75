// libFuzzer target: mesh files. The first byte picks the format (OBJ, 3VN, 3DV, 3DM), the rest
// is the file; a loaded mesh is built into a BVH whose bounds and nearest hits are checked
// against its vertices and brute force (tests/fuzz/fuzz_checks.h). A scene error is a normal
// outcome; a crash, a sanitizer report or a broken invariant is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tessera::fuzz::check_mesh_input(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
