#include "coordinator/http/multipart.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace tessera {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// The value of `key="value"` (or key=value) in a header line, or nullopt.
std::optional<std::string> parameter(std::string_view line, std::string_view key) {
  const std::string lowered = lower(line);
  std::size_t at = 0;
  while ((at = lowered.find(std::string(key) + "=", at)) != std::string::npos) {
    if (at == 0 || lowered[at - 1] == ' ' || lowered[at - 1] == ';') break;
    ++at;
  }
  if (at == std::string::npos) return std::nullopt;
  std::size_t start = at + key.size() + 1;
  if (start < line.size() && line[start] == '"') {
    const std::size_t end = line.find('"', start + 1);
    if (end == std::string_view::npos) return std::nullopt;
    return std::string(line.substr(start + 1, end - start - 1));
  }
  const std::size_t end = line.find(';', start);
  return std::string(line.substr(start, end == std::string_view::npos ? end : end - start));
}

}  // namespace

std::optional<std::string> multipart_boundary(std::string_view content_type) {
  if (!lower(content_type).starts_with("multipart/form-data")) return std::nullopt;
  auto b = parameter(content_type, "boundary");
  if (!b || b->empty() || b->size() > 200) return std::nullopt;
  return b;
}

std::vector<FormPart> parse_multipart(std::string_view body, const std::string& boundary) {
  const std::string delimiter = "--" + boundary;
  std::vector<FormPart> parts;
  std::size_t pos = body.find(delimiter);
  if (pos == std::string_view::npos) throw std::runtime_error("multipart: no boundary in body");
  for (;;) {
    pos += delimiter.size();
    if (body.substr(pos, 2) == "--") return parts;  // the closing delimiter
    if (body.substr(pos, 2) != "\r\n") throw std::runtime_error("multipart: bad delimiter line");
    pos += 2;
    const std::size_t headers_end = body.find("\r\n\r\n", pos);
    if (headers_end == std::string_view::npos)
      throw std::runtime_error("multipart: bad part headers");
    FormPart part;
    for (std::size_t line_start = pos; line_start < headers_end;) {
      std::size_t line_end = body.find("\r\n", line_start);
      if (line_end > headers_end) line_end = headers_end;
      const std::string_view line = body.substr(line_start, line_end - line_start);
      if (lower(line).starts_with("content-disposition:")) {
        part.name = parameter(line, "name").value_or("");
        part.filename = parameter(line, "filename");
      }
      line_start = line_end + 2;
    }
    const std::size_t data_start = headers_end + 4;
    const std::size_t next = body.find("\r\n" + delimiter, data_start);
    if (next == std::string_view::npos) throw std::runtime_error("multipart: unterminated part");
    part.data = std::string(body.substr(data_start, next - data_start));
    parts.push_back(std::move(part));
    pos = next + 2;
  }
}

}  // namespace tessera
