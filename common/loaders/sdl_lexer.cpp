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
  LineCursor at;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (at.skip_line_break(text, i)) continue;
    if (is_space(c)) {
      ++i;
    } else if (c == '!') {
      skip_to_line_end(text, i);
    } else if (is_brace(c)) {
      out.tokens.push_back({text.substr(i, 1), file, at.line, at.column(i)});
      ++i;
    } else {
      const std::size_t begin = i;
      while (i < text.size() && !is_space(text[i]) && text[i] != '!' && !is_brace(text[i])) ++i;
      out.tokens.push_back({text.substr(begin, i - begin), file, at.line, at.column(begin)});
    }
  }
  out.end_line = at.line;
  out.end_column = at.column(text.size());
  return out;
}

}  // namespace tessera::sdl
