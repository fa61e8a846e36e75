// include (§3.2.10): relative paths, fresh state, cycles, ignored globals; and the limits.
#include <gtest/gtest.h>

#include <string>

#include "common/loaders/sdl_parser.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlInclude, PathsAreRelativeToTheIncludingFile) {
  const Scene scene = load_text("include sub/a.sdl\ninclude c.sdl",
                                {{"sub/a.sdl", "include b.sdl\ninclude deeper/../../c.sdl"},
                                 {"sub/b.sdl", "sphere"},
                                 {"c.sdl", "cube"}});
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[0].geometry));
  EXPECT_EQ(scene.objects[0].where.file, "sub/b.sdl");
  EXPECT_EQ(scene.objects[1].where.file, "c.sdl");
  EXPECT_EQ(scene.objects[2].where.file, "c.sdl");
}

TEST(SdlInclude, PathsOutsideTheRootAreRefused) {
  EXPECT_TRUE(fails_at("include ../x.sdl", 1, 9, "include '../x.sdl' leaves the scene's folder",
                       {{"x.sdl", "sphere"}}));
  EXPECT_TRUE(
      fails_at("include /etc/passwd", 1, 9, "include '/etc/passwd' leaves the scene's folder"));
  EXPECT_TRUE(fails_with("include sub/a.sdl", "sub/a.sdl", 2, 11,
                         "include '../../x.sdl' leaves the scene's folder",
                         {{"sub/a.sdl", "sphere\n  include ../../x.sdl"}}));
}

TEST(SdlInclude, MissingFileIsAnError) {
  EXPECT_TRUE(
      fails_at("sphere\ninclude  sub/nope.sdl", 2, 10, "included file 'sub/nope.sdl' not found"));
  EXPECT_TRUE(
      fails_at("include", 1, 8, "unexpected end of file, expected a file name after 'include'"));
}

TEST(SdlInclude, CyclesAreErrors) {
  EXPECT_TRUE(fails_with("include a.sdl", "b.sdl", 1, 16, "include cycle: a.sdl -> b.sdl -> a.sdl",
                         {{"a.sdl", "include b.sdl"}, {"b.sdl", "sphere include a.sdl"}}));
  EXPECT_TRUE(fails_at("include scene.sdl", 1, 9, "include cycle: scene.sdl -> scene.sdl"));
}

TEST(SdlInclude, IncludingOneFileTwiceIsNotACycle) {
  const Scene scene = load_text("include a.sdl translate 1 0 0 include a.sdl", {{"a.sdl", "cube"}});
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[1].transform, Affine::identity());
}

TEST(SdlInclude, IncludedFilesStartFreshAndTheirStateDoesNotFlowBack) {
  const Scene scene = load_text(
      "translate 5 0 0 diffuse 1 0 0 push\n"
      "include part.sdl\n"
      "sphere pop",
      {{"part.sdl", "sphere translate 0 7 0 diffuse 0 1 0 push push cube"}});
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].transform, Affine::identity());
  EXPECT_EQ(scene.objects[0].material, Material{});
  EXPECT_EQ(scene.objects[1].material.diffuse, Rgb(0, 1, 0));
  EXPECT_TRUE(near(scene.objects[2].transform.apply_point({0, 0, 0}), {5, 0, 0}));
  EXPECT_EQ(scene.objects[2].material.diffuse, Rgb(1, 0, 0));
}

TEST(SdlInclude, AnIncludedFileCannotPopTheIncludersPush) {
  EXPECT_TRUE(fails_with("push include a.sdl", "a.sdl", 1, 1, "'pop' without a matching 'push'",
                         {{"a.sdl", "pop"}}));
}

TEST(SdlInclude, DefsAndLightsAreShared) {
  const Scene scene = load_text("def red { diffuse 1 0 0 }\ninclude lib.sdl\nuse blue sphere",
                                {{"lib.sdl",
                                  "def blue { diffuse 0 0 1 } light 1 2 3 1 1 1\n"
                                  "use red cube"}});
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].material.diffuse, Rgb(1, 0, 0));
  EXPECT_EQ(scene.objects[1].material.diffuse, Rgb(0, 0, 1));
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].position, Vec3(1, 2, 3));
}

TEST(SdlInclude, GlobalsInIncludedFilesAreIgnoredWithAWarning) {
  const Scene scene =
      load_text("include sub/env.sdl include sub/env.sdl",
                {{"sub/env.sdl", "background 1 1 1\n  eyePoint 9 9 9 maxRecursionDepth 3 sphere"}});
  EXPECT_EQ(scene.globals, SceneGlobals{});
  EXPECT_EQ(scene.camera, Camera{});
  EXPECT_EQ(scene.objects.size(), 2u);
  // One warning per attribute written; the second include repeats the same ones.
  ASSERT_EQ(scene.warnings.size(), 3u);
  EXPECT_EQ(scene.warnings[0], "sub/env.sdl:1:1: 'background' in an included file is ignored");
  EXPECT_EQ(scene.warnings[1], "sub/env.sdl:2:3: 'eyePoint' in an included file is ignored");
  EXPECT_EQ(scene.warnings[2],
            "sub/env.sdl:2:18: 'maxRecursionDepth' in an included file is ignored");
}

TEST(SdlInclude, GlobalsInIncludedFilesAreStillChecked) {
  EXPECT_TRUE(fails_with("include env.sdl", "env.sdl", 1, 12,
                         "<value> of 'viewAngle' must be strictly between 0 and 180 degrees, "
                         "found '0'",
                         {{"env.sdl", "viewAngle  0"}}));
}

TEST(SdlInclude, AMacroFromAnIncludedFileAppliesGlobalsWhereItIsUsed) {
  const Scene scene =
      load_text("include lib.sdl use sky", {{"lib.sdl", "def sky { background 0 0 1 }"}});
  EXPECT_EQ(scene.globals.background, Rgb(0, 0, 1));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(SdlInclude, ErrorsAreLocatedInTheIncludedFile) {
  EXPECT_TRUE(fails_with("sphere\ninclude a/b.sdl", "a/b.sdl", 3, 4, "unknown keyword 'sphre'",
                         {{"a/b.sdl", "\n\n   sphre"}}));
  EXPECT_TRUE(fails_with("include a.sdl", "a.sdl", 1, 14,
                         "unexpected end of file, expected a number for <dz> of 'translate'",
                         {{"a.sdl", "translate 1 2"}}));
}

TEST(SdlInclude, NestingIsLimitedTo64) {
  Files files;
  for (int i = 1; i <= 70; ++i) {
    files["f" + std::to_string(i) + ".sdl"] = "include f" + std::to_string(i + 1) + ".sdl";
  }
  files["f64.sdl"] = "sphere";
  EXPECT_EQ(load_text("include f1.sdl", files).objects.size(), 1u);
  files["f64.sdl"] = "include f65.sdl";
  files["f65.sdl"] = "sphere";
  EXPECT_TRUE(fails_with("include f1.sdl", "f64.sdl", 1, 1,
                         "include and use are nested too deeply (more than 64 levels) (limit "
                         "replay_nesting)",
                         files));
}

TEST(SdlLimits, FilesLargerThan16MiBAreRefused) {
  const std::string big(16u * 1024 * 1024 + 1, ' ');
  EXPECT_TRUE(fails_at("sphere\ninclude big.sdl", 2, 9,
                       "included file 'big.sdl' is larger than 16 MiB (limit file_bytes)",
                       {{"big.sdl", big}}));
  EXPECT_TRUE(fails_at("mesh big.obj 1", 1, 6,
                       "mesh file 'big.obj' is larger than 16 MiB (limit file_bytes)",
                       {{"big.obj", big}}));
  EXPECT_TRUE(
      fails_at(big, 1, 1, "scene file 'scene.sdl' is larger than 16 MiB (limit file_bytes)"));
  // Exactly 16 MiB is allowed.
  EXPECT_NO_THROW(load_text("include ok.sdl", {{"ok.sdl", std::string(16u << 20, '\n')}}));
}

TEST(SdlLimits, MissingTopLevelFile) {
  MemorySource source;
  try {
    load_sdl(source, "none.sdl");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.where().file, "none.sdl");
    EXPECT_EQ(e.message(), "scene file 'none.sdl' not found");
    EXPECT_STREQ(e.what(), "none.sdl:1:1: scene file 'none.sdl' not found");
  }
}

// The other limits, lowered so that tests reach them cheaply.
::testing::AssertionResult fails_with_limits(const std::string& text, const LoadBudget& limits,
                                             int line, int column, const std::string& message) {
  MemorySource source;
  source.add("scene.sdl", text);
  try {
    load_sdl(source, "scene.sdl", limits);
  } catch (const SceneError& e) {
    if (e.where().line == line && e.where().column == column && e.message() == message) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got " << e.what();
  }
  return ::testing::AssertionFailure() << "no error";
}

TEST(SdlLimits, ObjectsLightsPushesAndTokens) {
  LoadBudget limits;
  limits.max_objects = 3;
  EXPECT_TRUE(fails_with_limits("sphere sphere\nsphere cube", limits, 2, 8,
                                "the scene expands to more than 3 objects (limit objects)"));
  limits.max_lights = 1;
  EXPECT_TRUE(fails_with_limits("light 0 0 0 1 1 1 light 0 0 0 1 1 1", limits, 1, 19,
                                "the scene expands to more than 1 lights (limit lights)"));
  limits.max_push_depth = 2;
  EXPECT_TRUE(fails_with_limits("push pop push push push", limits, 1, 20,
                                "too many nested 'push' (more than 2) (limit push_depth)"));
  // Macros that double at every level would replay 2^30 tokens: the token budget stops them.
  std::string doubling = "def m0 { push pop }\n";
  for (int i = 1; i <= 30; ++i) {
    const std::string prev = "m" + std::to_string(i - 1);
    doubling += "def m" + std::to_string(i) + " { use " + prev + " use " + prev + " }\n";
  }
  doubling += "use m30";
  limits = LoadBudget{};
  limits.max_tokens = 1000;
  MemorySource source;
  source.add("scene.sdl", doubling);
  try {
    load_sdl(source, "scene.sdl", limits);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.message(),
              "the scene expands to more than 1000 tokens to parse, counting includes and "
              "macro uses (limit tokens)");
  }
}

TEST(SdlLimits, WarningsAreCapped) {
  LoadBudget limits;
  limits.max_warnings = 2;
  MemorySource source;
  source.add("scene.sdl", "include a.sdl");
  source.add("a.sdl", "background 0 0 0 background 0 0 0 showExtents 1 showExtents 0");
  const Scene scene = load_sdl(source, "scene.sdl", limits);
  ASSERT_EQ(scene.warnings.size(), 3u);
  EXPECT_EQ(scene.warnings[2], "further warnings are omitted");
}

}  // namespace
}  // namespace tessera::test
