// Replays the regression corpus (tests/fuzz/regressions/<target>/: inputs the fuzzers once
// broke, and hand-made edge cases) through the fuzz targets' own checks, in every build: a fix
// that regresses fails here without a fuzzing run.
#include <gtest/gtest.h>

#include "tests/fuzz/fuzz_checks.h"
#include "tests/fuzz/replay.h"

namespace tessera::fuzz {
namespace {

TEST(FuzzRegressions, Sdl) { replay("sdl", check_sdl_input); }
TEST(FuzzRegressions, Mesh) { replay("mesh", check_mesh_input); }
TEST(FuzzRegressions, Vrml) { replay("vrml", check_vrml_input); }

}  // namespace
}  // namespace tessera::fuzz
