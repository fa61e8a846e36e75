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

// If a line break starts at text[i] (LF, CRLF or a lone CR, as old Mac files have), moves `i`
// past it and returns true, so that errors name the lines editors show.
inline bool skip_line_break(std::string_view text, std::size_t& i) {
  if (text[i] != '\n' && text[i] != '\r') return false;
  if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
  ++i;
  return true;
}

// ASCII lower case (SDL keywords and macro names are case-insensitive).
std::string to_lower(std::string_view text);

// `text` in single quotes for a message, shortened and with control characters replaced.
std::string in_quotes(std::string_view text);

}  // namespace tessera
