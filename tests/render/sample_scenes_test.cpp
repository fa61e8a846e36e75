// Every sample scene in scenes/ (SDL and VRML) loads and renders at a small size with every pixel
// finite.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/loaders/scene_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

bool is_scene(const std::filesystem::path& path) {
  const std::filesystem::path extension = path.extension();
  if (extension == ".gz") return path.stem().extension() == ".wrl";
  return extension == ".sdl" || extension == ".dat" || extension == ".wrl";  // .dat: Hill's SDL
}

std::vector<std::filesystem::path> sample_scenes() {
  std::vector<std::filesystem::path> out;
  const std::filesystem::path root = std::filesystem::path(TESSERA_SOURCE_DIR) / "scenes";
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root))
    if (is_scene(entry.path()) && entry.path().parent_path().filename() != "parts")
      out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(SampleScenes, ThereAreSampleScenes) { EXPECT_GE(sample_scenes().size(), 8u); }

TEST(SampleScenes, EveryOneRendersWithoutNaN) {
  for (const auto& path : sample_scenes()) {
    SCOPED_TRACE(path.string());
    const Scene scene = load_scene_file(path);
    const PreparedScene prepared(scene, BvhMode::Sah);
    EXPECT_TRUE(prepared.unsupported().empty()) << prepared.unsupported().front();
    RenderSettings s = settings(64, 48);
    s.aa_samples = 5;
    RenderStats stats;
    const Image image = render_image(prepared, s, 0, stats);
    EXPECT_EQ(stats.nan_samples, 0u);
    int lit = 0;
    for (float v : image.rgb) {
      ASSERT_TRUE(std::isfinite(v));
      lit += v > 0.02f ? 1 : 0;
    }
    EXPECT_GT(lit, 64 * 48 / 10) << "the scene renders mostly black";
  }
}

}  // namespace
}  // namespace tessera::test
