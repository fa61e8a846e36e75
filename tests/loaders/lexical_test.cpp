// The number syntax shared by the SDL and OBJ loaders.
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "common/loaders/lexical.h"

namespace tessera {
namespace {

TEST(ParseDecimal, Accepts) {
  const std::pair<const char*, double> cases[] = {
      {"0", 0},
      {"1", 1},
      {"-2.5", -2.5},
      {"+3", 3},
      {"1e-3", 1e-3},
      {".5", 0.5},
      {"5.", 5},
      {"-.25", -0.25},
      {"1E+2", 100},
      {"007", 7},
      {"1e-400", 0},
      {"-1e-400", -0.0},
      {"123456789012345678901234567890", 1.2345678901234568e29},
      {"0.000000000000000000000000000001e-300", 0}};
  for (const auto& [text, value] : cases) {
    const DecimalResult r = parse_decimal(text);
    EXPECT_EQ(r.status, DecimalStatus::Ok) << text;
    EXPECT_EQ(r.value, value) << text;
  }
  EXPECT_TRUE(std::signbit(parse_decimal("-0").value));
}

// The short decimals a scene is made of, parsed by the fast path, against from_chars (the
// correctly rounded value) bit for bit: every digit count up to 17 (past the fast path's 15),
// every position of the point, exponents around the fast path's limit of 22.
TEST(ParseDecimal, ShortDecimalsAreCorrectlyRounded) {
  std::mt19937_64 random(11);
  for (int n = 0; n < 200000; ++n) {
    const int digits = 1 + static_cast<int>(random() % 17);
    std::string text = random() % 2 ? "-" : "";
    std::string unsigned_text;
    const int point = static_cast<int>(random() % static_cast<unsigned>(digits + 1));
    for (int d = 0; d < digits; ++d) {
      if (d == point) unsigned_text += '.';
      unsigned_text += static_cast<char>('0' + random() % 10);
    }
    if (random() % 3 == 0)
      unsigned_text += "e" + std::to_string(static_cast<int>(random() % 61) - 30);
    text += unsigned_text;
    double expected = 0;
    std::from_chars(unsigned_text.data(), unsigned_text.data() + unsigned_text.size(), expected);
    if (text[0] == '-') expected = -expected;
    const DecimalResult r = parse_decimal(text);
    ASSERT_EQ(r.status, DecimalStatus::Ok) << text;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(r.value), std::bit_cast<std::uint64_t>(expected))
        << text;
  }
}

TEST(ParseDecimal, Refuses) {
  for (const char* text :
       {"",     "+",        "-",     ".",  "e1", "1e",    "1e+", "1.2.3", "1..2", "nan", "inf",
        "-inf", "Infinity", "0x1p3", "1 ", " 1", "1_000", "1,5", "++1",   "1d",   "١"}) {
    EXPECT_EQ(parse_decimal(text).status, DecimalStatus::NotANumber) << text;
  }
  EXPECT_EQ(parse_decimal("1e309").status, DecimalStatus::OutOfRange);
  EXPECT_EQ(parse_decimal("-1e99999999999999999999").status, DecimalStatus::OutOfRange);
  EXPECT_EQ(parse_decimal("1e-99999999999999999999").status, DecimalStatus::Ok);
}

TEST(ParseInteger, AcceptsAndRefuses) {
  EXPECT_EQ(parse_integer("12").value, 12);
  EXPECT_EQ(parse_integer("-3").value, -3);
  EXPECT_EQ(parse_integer("+4").value, 4);
  for (const char* text : {"", "+", "-", "1.0", "1e2", "--1", "+-1", "a", "1 "}) {
    EXPECT_EQ(parse_integer(text).status, DecimalStatus::NotANumber) << text;
  }
  EXPECT_EQ(parse_integer("99999999999999999999").status, DecimalStatus::OutOfRange);
}

TEST(Lexical, ToLowerAndQuotes) {
  EXPECT_EQ(to_lower("TaperedCylinder"), "taperedcylinder");
  EXPECT_EQ(in_quotes("abc"), "'abc'");
  EXPECT_EQ(in_quotes("a\tb\n"), "'a?b?'");
}

}  // namespace
}  // namespace tessera
