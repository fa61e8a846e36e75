#include "common/loaders/lexical.h"

#include <charconv>
#include <cmath>
#include <system_error>

namespace tessera {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

DecimalResult parse_decimal(std::string_view text) {
  // Grammar: [+-]? (digits ('.' digits?)? | '.' digits) ([eE] [+-]? digits)?
  std::size_t i = 0;
  bool negative = false;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    negative = text[i] == '-';
    ++i;
  }
  const std::size_t mantissa_begin = i;
  std::size_t int_digits = 0, frac_digits = 0;
  while (i < text.size() && is_digit(text[i])) ++i, ++int_digits;
  if (i < text.size() && text[i] == '.') {
    ++i;
    while (i < text.size() && is_digit(text[i])) ++i, ++frac_digits;
  }
  if (int_digits + frac_digits == 0) return {};
  const std::size_t mantissa_end = i;
  long long exponent = 0;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exp_negative = false;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
      exp_negative = text[i] == '-';
      ++i;
    }
    std::size_t exp_digits = 0;
    while (i < text.size() && is_digit(text[i])) {
      if (exponent < 1'000'000'000) exponent = exponent * 10 + (text[i] - '0');
      ++i, ++exp_digits;
    }
    if (exp_digits == 0) return {};
    if (exp_negative) exponent = -exponent;
  }
  if (i != text.size()) return {};

  // Clinger's fast path, for the numbers scene files are made of (a mesh has hundreds of
  // thousands): with at most 15 digits the mantissa is an exact double, and so is 10^k for
  // k <= 22, so one correctly rounded product or quotient is the correctly rounded value,
  // the one from_chars gives (tests/loaders/lexical_test.cpp compares them bit for bit).
  if (int_digits + frac_digits <= 15) {
    const long long scale = exponent - static_cast<long long>(frac_digits);
    if (scale >= -22 && scale <= 22) {
      static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
      long long digits = 0;
      for (std::size_t k = mantissa_begin; k < mantissa_end; ++k)
        if (text[k] != '.') digits = digits * 10 + (text[k] - '0');
      const auto mantissa = static_cast<double>(digits);
      const double value =
          scale >= 0 ? mantissa * kPowersOfTen[scale] : mantissa / kPowersOfTen[-scale];
      return {DecimalStatus::Ok, negative ? -value : value};
    }
  }

  // from_chars does not take a leading '+'; the sign is applied afterwards.
  const std::string_view unsigned_text = text.substr(mantissa_begin);
  double value = 0;
  const auto [ptr, ec] =
      std::from_chars(unsigned_text.data(), unsigned_text.data() + unsigned_text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Decide between overflow and underflow from the decimal order of magnitude: the position
    // of the first non-zero digit relative to the decimal point, plus the exponent.
    long long order = 0;
    bool found = false;
    long long position = static_cast<long long>(int_digits);  // digits left of the point
    for (std::size_t k = mantissa_begin; k < mantissa_end; ++k) {
      if (text[k] == '.') continue;
      --position;
      if (text[k] != '0') {
        order = position;
        found = true;
        break;
      }
    }
    if (!found || order + exponent < 0) return {DecimalStatus::Ok, negative ? -0.0 : 0.0};
    return {DecimalStatus::OutOfRange, 0};
  }
  if (ec != std::errc() || ptr != unsigned_text.data() + unsigned_text.size() ||
      !std::isfinite(value)) {
    return {DecimalStatus::OutOfRange, 0};
  }
  return {DecimalStatus::Ok, negative ? -value : value};
}

IntegerResult parse_integer(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  if (i == text.size()) return {};
  for (std::size_t k = i; k < text.size(); ++k) {
    if (!is_digit(text[k])) return {};
  }
  // from_chars takes a leading '-' but not a leading '+'.
  const std::size_t begin = text[0] == '+' ? 1 : 0;
  long long value = 0;
  const auto [ptr, ec] = std::from_chars(text.data() + begin, text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) return {DecimalStatus::OutOfRange, 0};
  if (ec != std::errc() || ptr != text.data() + text.size()) return {};
  return {DecimalStatus::Ok, value};
}

std::string to_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

std::string in_quotes(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "'";
  for (const char c : text.substr(0, kMaxShown)) {
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  }
  if (text.size() > kMaxShown) out += "...";
  return out + "'";
}

}  // namespace tessera
