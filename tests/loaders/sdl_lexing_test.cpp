// SDL lexing: comments, case, layout, numbers and the locations of tokens in messages.
#include <gtest/gtest.h>

#include <string>

#include "common/loaders/sdl_lexer.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

TEST(SdlLexer, SplitsWordsBracesAndSkipsComments) {
  const sdl::LexedText lexed = sdl::lex_sdl("def a{sphere}! comment { }\n\t use a!x\r\n", 7);
  ASSERT_EQ(lexed.tokens.size(), 7u);
  const char* texts[] = {"def", "a", "{", "sphere", "}", "use", "a"};
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(lexed.tokens[i].text, texts[i]) << i;
  EXPECT_EQ(lexed.tokens[2].column, 6);
  EXPECT_EQ(lexed.tokens[3].column, 7);
  EXPECT_EQ(lexed.tokens[5].line, 2);
  EXPECT_EQ(lexed.tokens[5].column, 3);  // a tab counts as one column
  EXPECT_EQ(lexed.tokens[6].column, 7);
  EXPECT_EQ(lexed.tokens[0].file, 7u);
  EXPECT_EQ(lexed.end_line, 3);
  EXPECT_EQ(lexed.end_column, 1);
}

TEST(SdlLexer, LinesEndAtLfCrLfOrALoneCr) {
  const sdl::LexedText lexed = sdl::lex_sdl("a\r\nb\rc!x\rd\ne", 0);
  ASSERT_EQ(lexed.tokens.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(lexed.tokens[i].line, i + 1) << lexed.tokens[i].text;
    EXPECT_EQ(lexed.tokens[i].column, 1) << lexed.tokens[i].text;
  }
}

TEST(SdlLexer, EndOfFileIsJustPastTheLastByte) {
  const sdl::LexedText lexed = sdl::lex_sdl("sphere\ncube", 0);
  EXPECT_EQ(lexed.end_line, 2);
  EXPECT_EQ(lexed.end_column, 5);
  const sdl::LexedText empty = sdl::lex_sdl("", 0);
  EXPECT_TRUE(empty.tokens.empty());
  EXPECT_EQ(empty.end_line, 1);
  EXPECT_EQ(empty.end_column, 1);
}

TEST(SdlLexing, CommentsRunToTheEndOfTheLine) {
  const Scene scene = load_text("sphere ! cube cube\n! cube\ncube!sphere\n!");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[0].geometry));
  EXPECT_TRUE(std::holds_alternative<Cube>(scene.objects[1].geometry));
}

TEST(SdlLexing, KeywordsAreCaseInsensitive) {
  const Scene scene = load_text("SPHERE Sphere sPhErE\nTRANSLATE 1 0 0 CUBE DIFFUSE 1 0 0 cube");
  ASSERT_EQ(scene.objects.size(), 5u);
  EXPECT_TRUE(near(scene.objects[3].transform.apply_point({0, 0, 0}), {1, 0, 0}));
  EXPECT_EQ(scene.objects[4].material.diffuse, Rgb(1, 0, 0));
}

TEST(SdlLexing, ParametersMaySpanLinesAndComments) {
  const Scene scene = load_text("translate\n1\n\n  2 ! the y\n\t3 sphere");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({0, 0, 0}), {1, 2, 3}));
}

TEST(SdlLexing, ShapesRecordWhereTheyWereWritten) {
  const Scene scene = load_text("sphere\r\n  ! a comment\r\n\t\tcube");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].where.file, "scene.sdl");
  EXPECT_EQ(scene.objects[0].where.line, 1);
  EXPECT_EQ(scene.objects[0].where.column, 1);
  EXPECT_EQ(scene.objects[1].where.line, 3);
  EXPECT_EQ(scene.objects[1].where.column, 3);
}

TEST(SdlLexing, EmptyAndCommentOnlyFilesGiveAnEmptyScene) {
  EXPECT_TRUE(load_text("").objects.empty());
  EXPECT_TRUE(load_text("! nothing here\n\n   \t\n").objects.empty());
}

TEST(SdlNumbers, AcceptsDecimalAndFloatSyntax) {
  const Scene scene = load_text(
      "translate 1 -2.5 +3 sphere identityAffine\n"
      "translate 1e-3 .5 5. sphere identityAffine\n"
      "translate 1E2 -0 -.25e+1 sphere identityAffine\n"
      "translate 1e-400 0.000 007 sphere");
  ASSERT_EQ(scene.objects.size(), 4u);
  const Vec3 o{0, 0, 0};
  EXPECT_EQ(scene.objects[0].transform.apply_point(o), Vec3(1, -2.5, 3));
  EXPECT_EQ(scene.objects[1].transform.apply_point(o), Vec3(1e-3, 0.5, 5));
  EXPECT_EQ(scene.objects[2].transform.apply_point(o), Vec3(100, 0, -2.5));
  EXPECT_EQ(scene.objects[3].transform.apply_point(o), Vec3(0, 0, 7));  // underflow is 0
}

TEST(SdlNumbers, RejectsAnythingNotFullyANumber) {
  for (const std::string bad :
       {"abc", "nan", "NaN", "inf", "-inf", "infinity", "1e", "1e+", "1.2.3", "0x10", "1,5", "--1",
        "+-1", ".", "-", "e5", "1e5x", "1f", "{"}) {
    EXPECT_TRUE(fails_at("translate 0 " + bad + " 0", 1, 13,
                         "expected a number for <dy> of 'translate', found '" + bad + "'"))
        << bad;
  }
}

TEST(SdlNumbers, RejectsNumbersTooLargeForADouble) {
  EXPECT_TRUE(
      fails_at("scale 1e309 1 1", 1, 7, "number '1e309' for <sx> of 'scale' is out of range"));
  EXPECT_TRUE(
      fails_at("scale 1 -2e400 1", 1, 9, "number '-2e400' for <sy> of 'scale' is out of range"));
}

TEST(SdlErrors, WrongParameterIsLocatedAtTheToken) {
  EXPECT_TRUE(fails_at("sphere\n  translate 1 abc 3", 2, 15,
                       "expected a number for <dy> of 'translate', found 'abc'"));
  // The canonical spelling of the keyword is used whatever the case written.
  EXPECT_TRUE(
      fails_at("TRANSLATE x", 1, 11, "expected a number for <dx> of 'translate', found 'x'"));
}

TEST(SdlErrors, AShapeKeywordIsNotANumber) {
  EXPECT_TRUE(fails_at("translate 1 2 sphere", 1, 15,
                       "expected a number for <dz> of 'translate', found 'sphere'"));
}

TEST(SdlErrors, EndOfFileIsLocatedJustPastTheLastByte) {
  EXPECT_TRUE(fails_at("translate 1 2", 1, 14,
                       "unexpected end of file, expected a number for <dz> of 'translate'"));
  EXPECT_TRUE(fails_at("translate 1 2\n", 2, 1,
                       "unexpected end of file, expected a number for <dz> of 'translate'"));
  EXPECT_TRUE(fails_at("translate 1 2 ! then nothing", 1, 29,
                       "unexpected end of file, expected a number for <dz> of 'translate'"));
}

TEST(SdlErrors, UnknownKeywordIsAnErrorNotSkipped) {
  EXPECT_TRUE(fails_at("sphere\n  foo 1 2\ncube", 2, 3, "unknown keyword 'foo'"));
  EXPECT_TRUE(fails_at("sphere 1", 1, 8, "unknown keyword '1'"));
}

TEST(SdlErrors, ControlCharactersAndLongWordsAreShortenedInMessages) {
  EXPECT_TRUE(fails_at(std::string("a\x01z"), 1, 1, "unknown keyword 'a?z'"));
  EXPECT_TRUE(
      fails_at(std::string(50, 'x'), 1, 1, "unknown keyword '" + std::string(40, 'x') + "...'"));
}

TEST(SdlErrors, StrayBracesAreErrors) {
  EXPECT_TRUE(fails_at("sphere }", 1, 8, "unexpected '}' (braces belong to 'def <name> { }')"));
  EXPECT_TRUE(fails_at("{ sphere }", 1, 1, "unexpected '{' (braces belong to 'def <name> { }')"));
}

}  // namespace
}  // namespace tessera::test
