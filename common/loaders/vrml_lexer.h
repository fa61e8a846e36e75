// Tokens of the VRML97 UTF-8 encoding (ISO/IEC 14772-1 §5.1): words (names and numbers),
// quoted strings, and `{ } [ ]` as tokens of their own; commas are whitespace and `#` starts a
// comment that runs to the end of the line. gzip-compressed files are inflated first.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/loaders/load_budget.h"
#include "common/scene/source_location.h"

namespace tessera::vrml {

struct Token {
  enum class Kind { Word, String, Punct };
  Kind kind = Kind::Word;
  std::string text;  // a string's contents with its escapes resolved
  int line = 0;      // 1-based
  int column = 0;    // 1-based, in bytes
};

struct LexedFile {
  std::string path;  // root-relative, for messages
  std::vector<Token> tokens;
  int end_line = 1, end_column = 1;  // just past the last byte, for "unexpected end of file"
};

// The bytes of a .wrl file as text: inflated when they start with the gzip magic 1f 8b, the
// inflated bytes counted as read by `meter` as they come. Throws SceneError at `path`:1:1 for a
// corrupt stream, LoadBudgetExceeded for one that inflates beyond the budget.
std::string vrml_text(const std::string& bytes, const std::string& path, LoadMeter& meter);

// Checks the `#VRML V2.0 utf8` header and splits the rest into tokens, their memory counted by
// `meter`. Throws SceneError with the location of a missing header or an unterminated string.
LexedFile lex_vrml(std::string_view text, const std::string& path, LoadMeter& meter);
// With the default budget.
LexedFile lex_vrml(std::string_view text, const std::string& path);

}  // namespace tessera::vrml
