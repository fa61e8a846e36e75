// The replay of one target's regression corpus (tests/fuzz/regressions/<target>/) through its
// check, shared by the replay tests of the loaders' and the coordinator's targets.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::fuzz {

namespace fs = std::filesystem;

inline std::vector<fs::path> corpus(const std::string& target) {
  const fs::path folder = fs::path(TESSERA_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / target;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

inline std::string bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Inputs whose name starts with "refused" must be refused (a scene error, an ApiError, a
// ProtocolError: the check returns false); every other one must be accepted and keep the
// invariants, so that the corpus keeps exercising the checks.
inline void replay(const std::string& target, const std::function<bool(std::string_view)>& check) {
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

}  // namespace tessera::fuzz
