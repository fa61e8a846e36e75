#include "common/loaders/sdl_lexer.h"

#include "common/loaders/lexical.h"

namespace tessera::sdl {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
bool is_brace(char c) { return c == '{' || c == '}'; }

}  // namespace

LexedText lex_sdl(std::string_view text, std::uint32_t file) {
  LexedText out;
  int line = 1;
  std::size_t line_start = 0;  // offset of the current line's first byte
  const auto column = [&](std::size_t offset) { return static_cast<int>(offset - line_start) + 1; };
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (skip_line_break(text, i)) {
      ++line;
      line_start = i;
    } else if (is_space(c)) {
      ++i;
    } else if (c == '!') {
      while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
    } else if (is_brace(c)) {
      out.tokens.push_back({text.substr(i, 1), file, line, column(i)});
      ++i;
    } else {
      const std::size_t begin = i;
      while (i < text.size() && !is_space(text[i]) && text[i] != '!' && !is_brace(text[i])) ++i;
      out.tokens.push_back({text.substr(begin, i - begin), file, line, column(begin)});
    }
  }
  out.end_line = line;
  out.end_column = column(text.size());
  return out;
}

}  // namespace tessera::sdl
