#include "common/loaders/vrml_lexer.h"

#include <zlib.h>

#include "common/loaders/lexical.h"

namespace tessera::vrml {
namespace {

constexpr std::string_view kHeader = "#VRML V2.0 utf8";

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f' || c == ',';
}
bool is_punct(char c) { return c == '{' || c == '}' || c == '[' || c == ']'; }

}  // namespace

std::string vrml_text(const std::string& bytes, const std::string& path, LoadMeter& meter) {
  if (bytes.size() < 2 || static_cast<unsigned char>(bytes[0]) != 0x1f ||
      static_cast<unsigned char>(bytes[1]) != 0x8b)
    return bytes;
  const SourceLocation at{path, 1, 1};
  z_stream stream{};
  if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK)
    throw SceneError(at, "cannot start inflating the gzip stream");
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  std::string out;
  char buffer[1 << 16];
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof buffer;
    status = inflate(&stream, Z_NO_FLUSH);
    const std::size_t made = sizeof buffer - stream.avail_out;
    try {
      meter.add(LoadLimit::BytesRead, made, at);
    } catch (...) {
      inflateEnd(&stream);
      throw;
    }
    out.append(buffer, made);
  }
  inflateEnd(&stream);
  if (status != Z_STREAM_END) throw SceneError(at, "the gzip stream is corrupt or truncated");
  return out;
}

LexedFile lex_vrml(std::string_view text, const std::string& path) {
  LoadMeter meter{LoadBudget{}};
  return lex_vrml(text, path, meter);
}

LexedFile lex_vrml(std::string_view text, const std::string& path, LoadMeter& meter) {
  if (!text.starts_with(kHeader)) {
    const std::string found = text.starts_with("#VRML V1.0") ? " (VRML 1.0 is not supported)" : "";
    throw SceneError({path, 1, 1}, "expected the header '#VRML V2.0 utf8'" + found);
  }
  LexedFile out;
  out.path = path;
  LineCursor at;
  std::size_t i = 0;
  // A token and its share of the vector's spare capacity, and its text beyond the string's
  // own buffer.
  const auto keep = [&](Token&& token) {
    const std::size_t heap = token.text.size() > 15 ? token.text.size() + 1 : 0;
    meter.add(LoadLimit::BytesProduced, 2 * sizeof(Token) + heap, [&] {
      return SourceLocation{path, token.line, token.column};
    });
    out.tokens.push_back(std::move(token));
  };
  while (i < text.size()) {
    const char c = text[i];
    if (at.skip_line_break(text, i)) continue;
    if (is_space(c)) {
      ++i;
    } else if (c == '#') {  // the header is a comment too
      skip_to_line_end(text, i);
    } else if (is_punct(c)) {
      keep({Token::Kind::Punct, std::string(1, c), at.line, at.column(i)});
      ++i;
    } else if (c == '"') {
      Token token{Token::Kind::String, "", at.line, at.column(i)};
      ++i;
      for (;;) {
        if (i == text.size())
          throw SceneError({path, token.line, token.column}, "unterminated string");
        if (text[i] == '"') break;
        if (text[i] == '\\' && i + 1 < text.size()) ++i;  // \" and \\ (§5.3.13)
        if (text[i] == '\n') ++at.line, at.line_start = i + 1;
        token.text += text[i++];
      }
      ++i;
      keep(std::move(token));
    } else {
      const std::size_t begin = i;
      while (i < text.size() && !is_space(text[i]) && !is_punct(text[i]) && text[i] != '#' &&
             text[i] != '"')
        ++i;
      keep({Token::Kind::Word, std::string(text.substr(begin, i - begin)), at.line,
            at.column(begin)});
    }
  }
  out.end_line = at.line;
  out.end_column = at.column(text.size());
  return out;
}

}  // namespace tessera::vrml
