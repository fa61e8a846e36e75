#include "common/loaders/obj_loader.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/loaders/lexical.h"
#include "common/scene/source_location.h"

namespace tessera {
namespace {

struct Word {
  std::string_view text;
  int column = 0;  // 1-based
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// The whitespace-separated words of one line, up to a '#' comment, into `words` (reused from
// line to line, so that a file of a million lines does not allocate a million vectors).
void split_words(std::string_view line, std::vector<Word>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    if (is_space(line[i])) {
      ++i;
      continue;
    }
    if (line[i] == '#') break;
    const std::size_t begin = i;
    while (i < line.size() && !is_space(line[i]) && line[i] != '#') ++i;
    words.push_back({line.substr(begin, i - begin), static_cast<int>(begin) + 1});
  }
}

class ObjParser {
 public:
  ObjParser(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  Mesh parse() {
    mesh_.source = file_;
    std::size_t begin = 0;
    while (begin <= text_.size()) {
      std::size_t end = text_.find('\n', begin);
      if (end == std::string_view::npos) end = text_.size();
      ++line_;
      parse_line(text_.substr(begin, end - begin));
      begin = end + 1;
    }
    unitize();
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(int column, const std::string& message) const {
    throw SceneError({file_, line_, column}, message);
  }

  void parse_line(std::string_view line) {
    split_words(line, words_);
    if (words_.empty()) return;
    const std::string_view keyword = words_[0].text;
    if (keyword == "v") {
      parse_vertex();
    } else if (keyword == "vn") {
      parse_normal();
    } else if (keyword == "vt") {
      ++texcoord_count_;  // texture coordinates are not used yet; counted to check indices
    } else if (keyword == "f") {
      parse_face();
    } else if (keyword == "o" || keyword == "g" || keyword == "s" || keyword == "usemtl" ||
               keyword == "mtllib" || keyword == "l" || keyword == "p") {
      // Objects, groups, smoothing groups, materials, lines and points: ignored.
    } else {
      fail(words_[0].column, "unknown OBJ statement " + in_quotes(keyword));
    }
  }

  // The column just past the last word of the line, where a missing value belongs.
  int end_column() const {
    const Word& last = words_.back();
    return last.column + static_cast<int>(last.text.size());
  }

  double number(std::size_t index, const char* param) const {
    const auto what = [&] {
      return std::string("a number for ") + param + " of '" + std::string(words_[0].text) + "'";
    };
    if (index >= words_.size()) fail(end_column(), "unexpected end of line, expected " + what());
    const DecimalResult result = parse_decimal(words_[index].text);
    if (result.status == DecimalStatus::OutOfRange) {
      fail(words_[index].column, "number " + in_quotes(words_[index].text) + " is out of range");
    }
    if (result.status != DecimalStatus::Ok) {
      fail(words_[index].column, "expected " + what() + ", found " + in_quotes(words_[index].text));
    }
    return result.value;
  }

  void parse_vertex() {
    // v x y z [w], or the common colour extension v x y z r g b. w and colours are unused.
    const Vec3 p{number(1, "<x>"), number(2, "<y>"), number(3, "<z>")};
    const std::size_t count = words_.size() - 1;
    if (count == 4) {
      number(4, "<w>");
    } else if (count == 6) {
      number(4, "<r>");
      number(5, "<g>");
      number(6, "<b>");
    } else if (count != 3) {
      const std::size_t extra = count == 5 ? 5 : 7;
      fail(words_[extra].column, "too many values for 'v' (expected x y z [w] or x y z r g b)");
    }
    mesh_.positions.push_back(p);
  }

  void parse_normal() {
    const Vec3 n{number(1, "<x>"), number(2, "<y>"), number(3, "<z>")};
    if (words_.size() > 4) fail(words_[4].column, "too many values for 'vn' (expected x y z)");
    mesh_.normals.push_back(n);
  }

  // Resolves a 1-based (or negative, relative) index among `count` elements defined so far.
  std::uint32_t index(std::string_view text, int column, std::size_t count,
                      const char* kind) const {
    const IntegerResult result = parse_integer(text);
    if (result.status != DecimalStatus::Ok) {
      fail(column, std::string("expected a ") + kind + " index, found " + in_quotes(text));
    }
    const long long value = result.value;
    const long long n = static_cast<long long>(count);
    long long zero_based = -1;
    if (value > 0 && value <= n) zero_based = value - 1;
    if (value < 0 && -value <= n) zero_based = n + value;
    if (value == 0) fail(column, std::string(kind) + " index 0 is not valid (indices start at 1)");
    if (zero_based < 0) {
      fail(column, std::string(kind) + " index " + std::string(text) + " is out of range (" +
                       std::to_string(count) + " defined so far)");
    }
    return static_cast<std::uint32_t>(zero_based);
  }

  struct Corner {
    std::uint32_t v = 0;
    std::uint32_t n = MeshTriangle::kNoNormal;
  };

  Corner corner(const Word& word) const {
    // v, v/vt, v//vn or v/vt/vn.
    std::array<std::string_view, 3> parts{};
    std::array<int, 3> columns{};
    std::size_t count = 0;
    std::size_t begin = 0;
    bool malformed = false;
    while (true) {
      const std::size_t slash = word.text.find('/', begin);
      const std::size_t end = slash == std::string_view::npos ? word.text.size() : slash;
      if (count == parts.size()) {
        malformed = true;
        break;
      }
      parts[count] = word.text.substr(begin, end - begin);
      columns[count] = word.column + static_cast<int>(begin);
      ++count;
      if (slash == std::string_view::npos) break;
      begin = slash + 1;
    }
    // Only the texture coordinate of v//vn may be empty.
    if (!malformed) {
      malformed =
          parts[0].empty() || (count == 2 && parts[1].empty()) || (count == 3 && parts[2].empty());
    }
    if (malformed) {
      fail(word.column, "malformed face corner " + in_quotes(word.text) +
                            " (expected v, v/vt, v//vn or v/vt/vn)");
    }
    Corner c;
    c.v = index(parts[0], columns[0], mesh_.positions.size(), "vertex");
    if (count >= 2 && !parts[1].empty()) {
      index(parts[1], columns[1], texcoord_count_, "texture coordinate");
    }
    if (count == 3) c.n = index(parts[2], columns[2], mesh_.normals.size(), "normal");
    return c;
  }

  void parse_face() {
    if (words_.size() < 4) {
      fail(words_[0].column,
           "a face needs at least 3 corners, found " + std::to_string(words_.size() - 1));
    }
    std::vector<Corner>& corners = corners_;
    corners.clear();
    for (std::size_t i = 1; i < words_.size(); ++i) corners.push_back(corner(words_[i]));
    // Fan triangulation around the first corner.
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
      MeshTriangle t;
      t.v = {corners[0].v, corners[i].v, corners[i + 1].v};
      t.n = {corners[0].n, corners[i].n, corners[i + 1].n};
      mesh_.triangles.push_back(t);
    }
  }

  // Centres the vertices on their bounding box and scales them uniformly so that the largest
  // extent spans [-1, 1]. Normals are unchanged by a uniform scale.
  void unitize() {
    if (mesh_.positions.empty()) return;
    Vec3 lo = mesh_.positions.front(), hi = lo;
    for (const Vec3& p : mesh_.positions) {
      lo = min(lo, p);
      hi = max(hi, p);
    }
    // Halves first, so that coordinates near the limits of double do not overflow; a division
    // rather than a product with the reciprocal, which may be subnormal or inexact.
    const Vec3 centre = lo * 0.5 + hi * 0.5;
    const double half_extent = max_component(hi * 0.5 - lo * 0.5);
    for (Vec3& p : mesh_.positions) {
      p = p - centre;
      if (half_extent > 0) p = p / half_extent;
    }
  }

  std::string_view text_;
  const std::string& file_;
  int line_ = 0;
  std::vector<Word> words_;      // the line's, reused
  std::vector<Corner> corners_;  // the face's, reused
  std::size_t texcoord_count_ = 0;
  Mesh mesh_;
};

}  // namespace

Mesh load_obj(std::string_view text, const std::string& file) {
  return ObjParser(text, file).parse();
}

}  // namespace tessera
