// Tokens of SDL (`002_…` §3.1-3.2.1): words separated by whitespace, `{` and `}` as tokens of
// their own, and comments from `!` to the end of the line.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace tessera::sdl {

struct Token {
  std::string_view text;   // points into the file's text, which outlives the load
  std::uint32_t file = 0;  // index into the loader's table of file names
  int line = 0;            // 1-based
  int column = 0;          // 1-based, in bytes
};

struct LexedText {
  std::vector<Token> tokens;
  int end_line = 1, end_column = 1;  // just past the last byte, for "unexpected end of file"
};

LexedText lex_sdl(std::string_view text, std::uint32_t file);

}  // namespace tessera::sdl
