// The accuracy report (issue 5): what it sweeps, what it measures, and every file it promises.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bench/accuracy/accuracy_report.h"
#include "bench/accuracy/report_writer.h"
#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"

namespace tessera::test {
namespace {

Scene load(const std::string& text) {
  MemorySource source({{"s.sdl", text}});
  return load_sdl(source, "s.sdl");
}

// A large mirror ball over a bright floor: most of its pixels are reflection.
const char* const kMirrorScene =
    "eyePoint 0 1 5 light 3 4 5 1 1 1\n"
    "push scale 1.5 1.5 1.5 diffuse 0 0 0 ambient 0 0 0 reflectivity 0.9 sphere pop\n"
    "push translate 0 -2 0 scale 10 0.5 10 diffuse 0.8 0.6 0.2 cube pop\n";

bool has_knob(const Sweep& sweep, const std::string& knob) {
  return std::any_of(sweep.variants.begin(), sweep.variants.end(),
                     [&](const Variant& v) { return v.knob == knob; });
}

TEST(AccuracySweep, SweepsRecursionDepthOnlyWhenTheSceneRecurses) {
  RenderSettings base;
  const Sweep mirror = make_sweep(load(kMirrorScene), base);
  EXPECT_TRUE(has_knob(mirror, "recursion depth"));
  EXPECT_GT(mirror.reference.max_depth, 5);  // deeper than the scene's own depth
  const Sweep matte = make_sweep(load("light 0 5 5 1 1 1 sphere"), base);
  EXPECT_FALSE(has_knob(matte, "recursion depth"));
  EXPECT_TRUE(std::any_of(matte.not_swept.begin(), matte.not_swept.end(),
                          [](const std::string& s) { return s.rfind("recursion depth", 0) == 0; }));
}

TEST(AccuracySweep, SweepsConeSamplesOnlyForGlossTranslucencyOrSoftShadows) {
  RenderSettings base;
  const std::string cones = "cone samples (gloss, translucency, soft shadows)";
  const Sweep mirror = make_sweep(load(kMirrorScene), base);
  EXPECT_FALSE(has_knob(mirror, cones));
  EXPECT_EQ(mirror.reference.settings.cone_samples, base.cone_samples);
  const Sweep glossy =
      make_sweep(load("light 0 5 5 1 1 1 reflectivity 0.8 glossStrength 0.3 sphere"), base);
  EXPECT_TRUE(has_knob(glossy, cones));
  EXPECT_GT(glossy.reference.settings.cone_samples, 17);  // beyond every swept count
  RenderSettings soft = base;
  soft.shadows = ShadowMode::Soft;
  EXPECT_TRUE(has_knob(make_sweep(load(kMirrorScene), soft), cones));
}

TEST(AccuracySweep, SweepsTheShadowModeOnlyWhenTheSceneHasLights) {
  RenderSettings base;
  const Sweep lit = make_sweep(load(kMirrorScene), base);
  ASSERT_TRUE(has_knob(lit, "shadow mode"));
  std::vector<ShadowMode> modes;
  for (const Variant& v : lit.variants)
    if (v.knob == "shadow mode") modes.push_back(v.settings.shadows);
  EXPECT_EQ(modes, (std::vector<ShadowMode>{ShadowMode::None, ShadowMode::Hard, ShadowMode::Soft}));
  const Sweep dark = make_sweep(load("sphere"), base);
  EXPECT_FALSE(has_knob(dark, "shadow mode"));
  EXPECT_TRUE(std::any_of(dark.not_swept.begin(), dark.not_swept.end(),
                          [](const std::string& s) { return s.rfind("shadow mode", 0) == 0; }));
}

TEST(AccuracySweep, SweepsTimeSamplesOnlyWhenSomethingMoves) {
  RenderSettings base;
  const Sweep moving =
      make_sweep(load("light 0 5 5 1 1 1 mbTranslate 1 0 0 mbEnable sphere"), base);
  EXPECT_TRUE(has_knob(moving, "motion-blur time samples"));
  EXPECT_EQ(moving.reference.settings.time_samples, 16);  // converged in time too
  // More time samples converge towards the reference on a moving ball.
  AccuracyOptions options;
  options.base.width = 24;
  options.base.height = 18;
  options.repeats = 1;
  options.threads = 1;
  const AccuracyReport report =
      measure_accuracy(load("eyePoint 0 0 4 light 0 5 5 1 1 1 mbTranslate 2 0 0 mbEnable sphere"),
                       "ball.sdl", options);
  double one = -1, many = -1;
  for (const Measured& m : report.measured) {
    if (m.variant.label == "1 times") one = m.error.rmse;
    if (m.variant.label == "16 times") many = m.error.rmse;
  }
  ASSERT_GE(one, 0);
  ASSERT_GE(many, 0);
  EXPECT_LT(many, one);
  const Sweep still = make_sweep(load("light 0 5 5 1 1 1 sphere"), base);
  EXPECT_FALSE(has_knob(still, "motion-blur time samples"));
  EXPECT_TRUE(std::any_of(still.not_swept.begin(), still.not_swept.end(), [](const std::string& s) {
    return s.rfind("motion-blur time samples", 0) == 0;
  }));
}

TEST(AccuracySweep, ParetoFrontKeepsOnlyUndominatedSettings) {
  std::vector<Measured> m(4);
  m[0].seconds = 1, m[0].error.rmse = 0.5;  // fastest
  m[1].seconds = 2, m[1].error.rmse = 0.1;  // better error
  m[2].seconds = 3, m[2].error.rmse = 0.2;  // dominated by m[1]
  m[3].seconds = 2, m[3].error.rmse = 0.1;  // ties m[1]: neither dominates
  mark_pareto_front(m);
  EXPECT_TRUE(m[0].pareto);
  EXPECT_TRUE(m[1].pareto);
  EXPECT_FALSE(m[2].pareto);
  EXPECT_TRUE(m[3].pareto);
}

TEST(AccuracyReport, MeasuresEveryKnobAndWritesEveryTableAndPlot) {
  AccuracyOptions options;
  options.base.width = 24;
  options.base.height = 18;
  options.repeats = 1;
  options.threads = 1;
  const AccuracyReport report = measure_accuracy(load(kMirrorScene), "mirror.sdl", options);

  // More samples converge towards the reference: 9 jittered samples beat 1 regular one.
  const auto rmse_of = [&](const std::string& label) {
    for (const Measured& m : report.measured)
      if (m.variant.label == label) return m.error.rmse;
    ADD_FAILURE() << "no variant " << label;
    return 0.0;
  };
  EXPECT_LT(rmse_of("aa 9 jittered"), rmse_of("aa 1"));
  // Depth 0 leaves the mirror black: further from the reference than the scene's depth.
  EXPECT_GT(rmse_of("depth 0"), rmse_of("depth 4"));
  // The reference has hard shadows: leaving them out is further from it than keeping them.
  EXPECT_GT(rmse_of("no shadows"), rmse_of("hard shadows"));
  // One row per level, down to single pixels, each tracing new anchors; the last level's
  // preview is the finished pass 0.
  ASSERT_EQ(report.levels.size(), 5u);  // 24x18: blocks of 16, 8, 4, 2, 1
  EXPECT_EQ(report.levels.back().block, 1);
  long long traced = 0;
  for (const LevelRow& row : report.levels) traced += row.traced;
  EXPECT_EQ(traced, 24 * 18);
  EXPECT_NEAR(report.levels.back().error.rmse, rmse_of("aa 1"), 1e-6);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "tessera_accuracy_test";
  std::filesystem::remove_all(dir);
  const std::vector<std::string> files = write_accuracy_report(report, dir.string());
  ASSERT_EQ(files.size(), 3u);
  for (const std::string& f : files) EXPECT_GT(std::filesystem::file_size(f), 200u) << f;
  std::stringstream md;
  md << std::ifstream(files[0]).rdbuf();
  for (const char* heading :
       {"## anti-aliasing (regular)", "## anti-aliasing (jittered)", "## jitter strength",
        "## sample passes", "## recursion depth", "## Progressive levels", "time_vs_error.svg",
        "progressive_levels.svg", "★", "## shadow mode", "cone samples: nothing"})
    EXPECT_NE(md.str().find(heading), std::string::npos) << heading;
  std::stringstream svg;
  svg << std::ifstream(files[1]).rdbuf();
  EXPECT_NE(svg.str().find("Pareto front"), std::string::npos);
  EXPECT_NE(svg.str().find("<polyline"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera::test
