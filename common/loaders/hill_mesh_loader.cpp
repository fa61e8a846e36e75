#include "common/loaders/hill_mesh_loader.h"

#include <cstdint>
#include <optional>
#include <vector>

#include "common/loaders/lexical.h"
#include "common/scene/source_location.h"

namespace tessera {
namespace {

struct Word {
  std::string_view text;
  int line = 1, column = 1;
};

// Whitespace-separated words with their positions; a line ends at LF, CR or CR LF.
class WordReader {
 public:
  WordReader(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  std::optional<Word> next() {
    skip_space();
    if (pos_ == text_.size()) return std::nullopt;
    Word word{{}, line_, column_};
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) advance();
    word.text = text_.substr(begin, pos_ - begin);
    end_line_ = line_;
    end_column_ = column_;
    return word;
  }

  [[noreturn]] void fail(const Word& at, const std::string& message) const {
    throw SceneError({file_, at.line, at.column}, message);
  }
  // Just past the last word read, where a missing value belongs.
  [[noreturn]] void fail_at_end(const std::string& message) const {
    throw SceneError({file_, end_line_, end_column_}, message);
  }

 private:
  static bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  }

  void advance() {
    const char c = text_[pos_++];
    const bool line_end = c == '\n' || (c == '\r' && (pos_ == text_.size() || text_[pos_] != '\n'));
    if (line_end) {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
  }

  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) advance();
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
  int end_line_ = 1, end_column_ = 1;
};

enum class Format { ThreeVN, ThreeDV, ThreeDM };

class HillMeshParser {
 public:
  HillMeshParser(std::string_view text, const std::string& file, Format format)
      : words_(text, file), format_(format) {
    mesh_.source = file;
  }

  Mesh parse() {
    const std::size_t vertex_count = count("#vertices");
    const std::size_t normal_count = format_ == Format::ThreeVN ? count("#normals") : 0;
    const std::size_t face_count = count("#faces");
    for (std::size_t i = 0; i < vertex_count; ++i) {
      mesh_.positions.push_back(point("vertex", i));
      if (format_ == Format::ThreeDV) mesh_.normals.push_back(point("normal", i));
    }
    for (std::size_t i = 0; i < normal_count; ++i) mesh_.normals.push_back(point("normal", i));
    for (std::size_t i = 0; i < face_count; ++i) face(i);
    if (const std::optional<Word> extra = words_.next()) {
      words_.fail(*extra, "unexpected " + in_quotes(extra->text) + " after the last face");
    }
    if (format_ == Format::ThreeDM) {
      for (Vec3& normal : mesh_.normals) normal = normalize_or(normal, Vec3{});
    }
    return std::move(mesh_);
  }

 private:
  Word expect(const std::string& what) {
    std::optional<Word> word = words_.next();
    if (!word) words_.fail_at_end("unexpected end of file, expected " + what);
    return *word;
  }

  // A non-negative integer: a count or an index.
  std::pair<std::size_t, Word> whole(const std::string& what) {
    const Word word = expect(what);
    const IntegerResult result = parse_integer(word.text);
    if (result.status != DecimalStatus::Ok || result.value < 0) {
      words_.fail(word, "expected " + what + ", found " + in_quotes(word.text));
    }
    return {static_cast<std::size_t>(result.value), word};
  }

  std::size_t count(const char* name) {
    return whole(std::string("a non-negative count for ") + name).first;
  }

  double number(const std::string& what) {
    const Word word = expect(what);
    const DecimalResult result = parse_decimal(word.text);
    if (result.status == DecimalStatus::OutOfRange) {
      words_.fail(word, "number " + in_quotes(word.text) + " is out of range");
    }
    if (result.status != DecimalStatus::Ok) {
      words_.fail(word, "expected " + what + ", found " + in_quotes(word.text));
    }
    return result.value;
  }

  Vec3 point(const char* kind, std::size_t index) {
    const std::string of = std::string(" of ") + kind + " " + std::to_string(index);
    const double x = number("a number for x" + of);
    const double y = number("a number for y" + of);
    const double z = number("a number for z" + of);
    return {x, y, z};
  }

  std::uint32_t index(const char* kind, std::size_t face, std::size_t defined) {
    const std::string what = std::string("a ") + kind + " index of face " + std::to_string(face);
    const auto [value, word] = whole(what);
    if (value >= defined) {
      words_.fail(word, std::string(kind) + " index " + std::string(word.text) +
                            " is out of range (" + std::to_string(defined) +
                            " defined, indices start at 0)");
    }
    return static_cast<std::uint32_t>(value);
  }

  void face(std::size_t f) {
    const auto [corners, at] = whole("the number of vertices of face " + std::to_string(f));
    if (corners < 3) {
      words_.fail(at, "face " + std::to_string(f) + " needs at least 3 vertices, found " +
                          std::to_string(corners));
    }
    // Read corner by corner so that a huge count fails at the end of the file, not in an
    // allocation.
    std::vector<std::uint32_t> v, n;
    for (std::size_t i = 0; i < corners; ++i) {
      v.push_back(index("vertex", f, mesh_.positions.size()));
    }
    if (format_ == Format::ThreeVN) {
      for (std::size_t i = 0; i < corners; ++i) {
        n.push_back(index("normal", f, mesh_.normals.size()));
      }
    } else {
      n = v;  // 3DV: the vertex's own normal; 3DM: the one computed from its polygons
    }
    if (format_ == Format::ThreeDM) add_to_vertex_normals(v);
    for (std::size_t i = 1; i + 1 < corners; ++i) {
      MeshTriangle t;
      t.v = {v[0], v[i], v[i + 1]};
      t.n = {n[0], n[i], n[i + 1]};
      mesh_.triangles.push_back(t);
    }
  }

  // 3DM: each vertex's normal is the sum of its polygons' area vectors (twice the area along
  // the normal), that is the mean of their normals weighted by area. A vertex whose polygons
  // cancel out keeps a zero normal, and interpolation falls back to the geometric normal there
  // (triangle.h).
  void add_to_vertex_normals(const std::vector<std::uint32_t>& polygon) {
    if (mesh_.normals.size() != mesh_.positions.size()) {
      mesh_.normals.assign(mesh_.positions.size(), Vec3{});
    }
    const Vec3& p0 = mesh_.positions[polygon[0]];
    Vec3 area;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      area += cross(mesh_.positions[polygon[i]] - p0, mesh_.positions[polygon[i + 1]] - p0);
    }
    for (std::uint32_t k : polygon) mesh_.normals[k] += area;
  }

  WordReader words_;
  Format format_;
  Mesh mesh_;
};

bool reads_further(const SourceLocation& a, const SourceLocation& b) {
  return a.line != b.line ? a.line > b.line : a.column > b.column;
}

}  // namespace

Mesh load_3vn(std::string_view text, const std::string& file) {
  return HillMeshParser(text, file, Format::ThreeVN).parse();
}

Mesh load_3dv(std::string_view text, const std::string& file) {
  return HillMeshParser(text, file, Format::ThreeDV).parse();
}

Mesh load_3dm(std::string_view text, const std::string& file) {
  return HillMeshParser(text, file, Format::ThreeDM).parse();
}

Mesh load_hill_mesh(std::string_view text, const std::string& file) {
  const std::optional<Word> first = WordReader(text, file).next();
  const IntegerResult count = first ? parse_integer(first->text) : IntegerResult{};
  if (count.status != DecimalStatus::Ok || count.value < 0) {
    throw SceneError({file, first ? first->line : 1, first ? first->column : 1},
                     "the format of the mesh is unknown: OBJ files are named .obj, and 3VN, 3DV "
                     "and 3DM files start with a count of vertices");
  }
  std::optional<SceneError> furthest;
  std::optional<Mesh> faceless;  // a layout can fit with no faces: another may find them
  for (const Format format : {Format::ThreeVN, Format::ThreeDV, Format::ThreeDM}) {
    try {
      Mesh mesh = HillMeshParser(text, file, format).parse();
      if (!mesh.triangles.empty()) return mesh;
      if (!faceless) faceless = std::move(mesh);
    } catch (const SceneError& error) {
      if (!furthest || reads_further(error.where(), furthest->where())) furthest = error;
    }
  }
  if (faceless) return std::move(*faceless);
  throw *furthest;
}

}  // namespace tessera
