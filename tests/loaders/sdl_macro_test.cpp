// Macros (§3.2.9): def records tokens, use replays them as if written there.
#include <gtest/gtest.h>

#include <string>

#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlMacros, DefRecordsAndUseReplays) {
  const Scene scene = load_text(
      "def red { diffuse 1 0 0 }\n"
      "def ball { push translate 0 1 0 sphere pop }\n"
      "sphere use red use ball cube");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].material.diffuse, Material{}.diffuse);  // def does not execute
  EXPECT_EQ(scene.objects[1].material.diffuse, Rgb(1, 0, 0));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({0, 0, 0}), {0, 1, 0}));
  EXPECT_EQ(scene.objects[2].transform, Affine::identity());
  EXPECT_EQ(scene.objects[2].material.diffuse, Rgb(1, 0, 0));
}

TEST(SdlMacros, NamesAreCaseInsensitive) {
  const Scene scene = load_text("DEF Red { diffuse 1 0 0 } USE RED sphere");
  EXPECT_EQ(scene.objects[0].material.diffuse, Rgb(1, 0, 0));
}

TEST(SdlMacros, BracesNeedNoSpaces) {
  EXPECT_EQ(load_text("def a{sphere}use a use a").objects.size(), 2u);
}

TEST(SdlMacros, NestedUsesAndNestedDefs) {
  const Scene scene = load_text(
      "def a { sphere }\n"
      "def b { use a translate 1 0 0 use a }\n"
      "def outer { def inner { cube } use inner }\n"
      "use b use outer use inner");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({0, 0, 0}), {1, 0, 0}));
  EXPECT_TRUE(std::holds_alternative<Cube>(scene.objects[2].geometry));
  EXPECT_TRUE(std::holds_alternative<Cube>(scene.objects[3].geometry));
}

TEST(SdlMacros, AMacroMayUseOneDefinedAfterIt) {
  EXPECT_EQ(load_text("def a { use b } def b { sphere } use a").objects.size(), 1u);
}

TEST(SdlMacros, ReplayIsAsIfWrittenThere) {
  // A macro's tokens join the surrounding stream: a statement may continue after it.
  const Scene scene = load_text("def t { translate 1 } use t 2 3 sphere");
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({0, 0, 0}), {1, 2, 3}));
}

TEST(SdlMacros, EmptyMacro) { EXPECT_EQ(load_text("def e { } use e sphere").objects.size(), 1u); }

TEST(SdlMacros, ErrorsInsideAReplayPointIntoTheDef) {
  EXPECT_TRUE(fails_at("def bad {\n  translate 1 x 0 }\nsphere use bad", 2, 15,
                       "expected a number for <dy> of 'translate', found 'x'"));
  EXPECT_TRUE(fails_at("def s { scale 0 0 0 sphere }\nuse s", 1, 21,
                       "'sphere' has a singular transform (zero scale?)"));
}

TEST(SdlMacros, RedefinitionIsAnError) {
  EXPECT_TRUE(fails_at("def a { sphere }\ndef A { cube }", 2, 5,
                       "macro 'A' is already defined at scene.sdl:1:5"));
}

TEST(SdlMacros, UseOfAnUndefinedMacroIsAnError) {
  EXPECT_TRUE(fails_at("sphere use nothing", 1, 12, "macro 'nothing' is not defined"));
}

TEST(SdlMacros, RecursionIsAnErrorNotAStackOverflow) {
  EXPECT_TRUE(fails_at("def a { sphere use a cube }\nuse a", 1, 20,
                       "macro 'a' uses itself (directly or through other macros)"));
  // In tail position too.
  EXPECT_TRUE(fails_at("def a { sphere use a }\nuse a", 1, 20,
                       "macro 'a' uses itself (directly or through other macros)"));
  // Indirectly.
  EXPECT_TRUE(fails_at("def a { use b }\ndef b { use c }\ndef c { use A }\nuse a", 3, 13,
                       "macro 'a' uses itself (directly or through other macros)"));
  // A def that would recurse is harmless until used.
  EXPECT_NO_THROW(load_text("def a { use a }"));
}

TEST(SdlMacros, SyntaxErrors) {
  EXPECT_TRUE(fails_at("def a sphere }", 1, 7, "expected '{' after 'def a', found 'sphere'"));
  EXPECT_TRUE(fails_at("def { sphere }", 1, 5, "expected a macro name after 'def', found '{'"));
  EXPECT_TRUE(fails_at("def a {\n sphere\n", 3, 1,
                       "unexpected end of file, expected '}' to close 'def a' opened at 1:7"));
  EXPECT_TRUE(fails_at("def a { def b { sphere }", 1, 25,
                       "unexpected end of file, expected '}' to close 'def a' opened at 1:7"));
  EXPECT_TRUE(fails_at("def", 1, 4, "unexpected end of file, expected a macro name after 'def'"));
  EXPECT_TRUE(fails_at("use", 1, 4, "unexpected end of file, expected a macro name after 'use'"));
}

TEST(SdlMacros, NestingIsLimitedTo64Replays) {
  // m1 uses m0, m2 uses m1, ...; `use mN` nests N + 1 replays.
  const auto chain = [](int n) {
    std::string text = "def m0 { sphere }\n";
    for (int i = 1; i <= n; ++i) {
      text += "def m" + std::to_string(i) + " { use m" + std::to_string(i - 1) + " sphere }\n";
    }
    return text + "use m" + std::to_string(n);
  };
  EXPECT_EQ(load_text(chain(63)).objects.size(), 64u);
  // The 65th nested `use` is the one in m0's user, m1, at line 2, column 10.
  EXPECT_TRUE(fails_at(
      chain(64), 2, 10,
      "include and use are nested too deeply (more than 64 levels) (limit replay_nesting)"));
}

}  // namespace
}  // namespace tessera::test
