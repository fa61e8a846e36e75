// multipart/form-data bodies (RFC 7578), the browser's and curl's way to upload a scene with
// its files: `scene`, `settings` (JSON), `main`, `format` fields and `file` parts.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

struct FormPart {
  std::string name;
  std::optional<std::string> filename;
  std::string data;
};

// The boundary parameter of a multipart Content-Type, or nullopt.
std::optional<std::string> multipart_boundary(std::string_view content_type);
// Throws std::runtime_error for a body that does not follow the boundary structure.
std::vector<FormPart> parse_multipart(std::string_view body, const std::string& boundary);

}  // namespace tessera
