// Lexical helpers shared by the SDL, VRML and OBJ loaders, so that both accept the same numbers and
// quote user text in messages the same way.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace tessera {

enum class DecimalStatus {
  Ok,
  NotANumber,  // not fully a decimal number
  OutOfRange,  // a number, but too large for a double (underflow quietly becomes 0)
};

struct DecimalResult {
  DecimalStatus status = DecimalStatus::NotANumber;
  double value = 0;
};

// Decimal numbers as scene files write them: "1", "-2.5", "+3", "1e-3", ".5", "5.".
// Independent of the C locale; "nan", "inf", hexadecimal and anything with trailing
// characters are refused.
DecimalResult parse_decimal(std::string_view text);

// A signed decimal integer without fraction or exponent ("12", "-3", "+4"); NotANumber for
// anything else, OutOfRange beyond the range of long long.
struct IntegerResult {
  DecimalStatus status = DecimalStatus::NotANumber;
  long long value = 0;
};

IntegerResult parse_integer(std::string_view text);

// Where a lexer is in its text: the line, and the offset where that line starts, for the
// line and column of each token. Lines end at LF, CRLF or a lone CR (old Mac files), so that
// errors name the lines editors show.
struct LineCursor {
  int line = 1;
  std::size_t line_start = 0;
  int column(std::size_t offset) const { return static_cast<int>(offset - line_start) + 1; }
  // If a line break starts at text[i], moves `i` past it onto the next line and returns true.
  bool skip_line_break(std::string_view text, std::size_t& i) {
    if (text[i] != '\n' && text[i] != '\r') return false;
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    ++line;
    line_start = ++i;
    return true;
  }
};

// Moves `i` to the line break (or the end of the text) that ends its line: past a comment.
inline void skip_to_line_end(std::string_view text, std::size_t& i) {
  while (i < text.size() && text[i] != '\n' && text[i] != '\r') ++i;
}

// ASCII lower case (SDL keywords and macro names are case-insensitive).
std::string to_lower(std::string_view text);

// `text` in single quotes for a message, shortened and with control characters replaced.
std::string in_quotes(std::string_view text);

}  // namespace tessera
