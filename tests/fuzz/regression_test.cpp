// Replays the regression corpus (tests/fuzz/regressions/<target>/: inputs the fuzzers once
// broke, and hand-made edge cases) through the fuzz targets' own checks, in every build: a fix
// that regresses fails here without a fuzzing run.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_checks.h"

namespace tessera::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> corpus(const std::string& target) {
  const fs::path folder = fs::path(TESSERA_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / target;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Inputs whose name starts with "refused" must be refused with a scene error; every other
// one must load and keep the invariants, so that the corpus keeps exercising the checks.
void replay(const std::string& target, const std::function<bool(std::string_view)>& check) {
  const std::vector<fs::path> files = corpus(target);
  EXPECT_FALSE(files.empty()) << "no regression inputs for " << target;
  for (const fs::path& file : files) {
    const bool refusal = file.filename().string().starts_with("refused");
    try {
      EXPECT_EQ(check(bytes_of(file)), !refusal)
          << file.filename() << (refusal ? " loaded" : " was refused");
    } catch (const std::exception& e) {
      ADD_FAILURE() << file.filename() << ": " << e.what();
    }
  }
}

TEST(FuzzRegressions, Sdl) { replay("sdl", check_sdl_input); }
TEST(FuzzRegressions, Mesh) { replay("mesh", check_mesh_input); }
TEST(FuzzRegressions, Vrml) { replay("vrml", check_vrml_input); }

}  // namespace
}  // namespace tessera::fuzz
