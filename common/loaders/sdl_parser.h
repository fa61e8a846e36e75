// Internal to the SDL loader: the parser of one file (its token stream, current transform and
// material) and the operations the keyword handlers of sdl_keywords.cpp are written with.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/loaders/load_budget.h"
#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_lexer.h"
#include "common/scene/scene.h"

namespace tessera::sdl {

class LoadContext;  // what one load shares across files (sdl_parser.cpp)
struct SourceFile;
struct Macro;

// What a number parameter must satisfy; the message names the interval.
enum class Range {
  Any,
  NonNegative,   // >= 0
  Positive,      // > 0
  UnitInterval,  // [0, 1]
  OpenAngle,     // (0, 180), degrees
  Cutoff,        // (0, 180], degrees
};

struct Number {
  double value = 0;
  Token token;  // where it was written, for errors found later
};

class FileParser {
 public:
  FileParser(LoadContext& context, const SourceFile& file, bool included);
  FileParser(const FileParser&) = delete;
  FileParser& operator=(const FileParser&) = delete;

  // Parses every statement of the file.
  void run();
  // At the end of the top-level file: the camera must have a view direction and an up vector
  // that is not parallel to it.
  void validate_camera() const;
  // At the end of the top-level file: every boolean object must have both children.
  void validate_csg() const;

  // ---- The statement being parsed
  const Token& keyword() const { return keyword_; }
  std::string_view keyword_name() const { return keyword_name_; }  // canonical spelling
  Scene& scene();
  SourceLocation location(const Token& token) const;
  [[noreturn]] void fail(const Token& at, const std::string& message) const;

  // ---- Parameters of the current keyword. `param` is the manual's name ("<dx>"), used in
  // messages such as "expected a number for <dx> of 'translate', found 'abc'".
  Token word(const std::string& what);  // any token but a brace: a file or macro name
  Number read_number(const char* param, Range range = Range::Any);
  double number(const char* param, Range range = Range::Any) {
    return read_number(param, range).value;
  }
  int integer(const char* param, int min, int max);
  bool flag(const char* param);  // any number; non-zero is true
  // Whether the next token is a number. Hill's SDL leaves out the trailing parameters that the
  // manual adds to some shapes (`cone` for `cone 0`); since a statement never starts with a
  // number, a number after such a shape is its parameter and anything else starts the next
  // statement. It reads nothing, so a parameter may still follow the end of a macro replay.
  bool number_follows();
  Vec3 vec3(const char* x, const char* y, const char* z);
  Rgb color(const char* r, const char* g, const char* b);  // non-negative components

  // ---- Effects of statements
  Affine& ct() { return ct_; }
  void push_ct();
  void pop_ct();
  Material& material() { return material_; }
  // The motion-blur state of §3.2.6: the next shape's motion, and whether mbEnable was given.
  struct PendingMotion {
    ObjectMotion motion;
    bool enabled = false;
  };
  PendingMotion& motion() { return motion_; }
  // Adds a shape with the CT, material and motion; inside a boolean object, as its next child.
  void add_object(const ShapeGeometry& geometry);
  // Starts a boolean object (§3.2.4): the next two objects (shapes or boolean objects, each
  // with whatever transforms and materials are set before it) are its children.
  void begin_csg(CsgOperation operation);
  void add_light(const Light& light);
  // The index in Scene::meshes of the mesh file `name` (loaded once per resolved path).
  std::size_t mesh(const Token& name);
  // The index in Scene::meshes of the mesh `make` builds for the current keyword (a polyhedron,
  // the teapot): made once per scene and shared by every instance.
  std::size_t built_in_mesh(Mesh (*make)());
  // Reads the image file at resolved `path` (written as `name`) into Scene::images, once per
  // path; an error at `name` when it is missing or too large.
  void image(const std::string& path, const Token& name);
  // `name` resolved relative to the file it is written in; an error when it leaves the root.
  std::string resolve(const Token& name);
  void include(const Token& name);
  void define();
  void use();
  // Global attributes apply only in the top-level file: in an included file this adds a
  // warning and returns false.
  bool accept_global();
  // A warning placed at the current keyword, shown once however often it is repeated.
  void warn(const std::string& message);
  void note_camera_position() { last_camera_position_ = keyword_; }
  void note_up_direction() { up_direction_ = keyword_; }

 private:
  struct Frame {
    const std::vector<Token>* tokens = nullptr;
    std::size_t next = 0;
    const Macro* macro = nullptr;  // the macro being replayed, null for the file itself
  };

  std::optional<Token> next();
  const Token* peek();  // the token next() returns, or null at the end; reads nothing
  Token expect(const std::string& what);  // the next token, or "unexpected end of file"
  [[noreturn]] void fail_at_end(const std::string& what) const;
  std::string of_keyword(const char* param) const;  // "<dx> of 'translate'"
  // An error when a boolean object awaits a child: the current keyword is not one.
  void refuse_in_csg() const;

  LoadContext& context_;
  const SourceFile& file_;
  bool included_;
  std::vector<Frame> frames_;
  Token keyword_;
  std::string_view keyword_name_;
  Affine ct_;
  std::vector<Affine> ct_stack_;
  Material material_;
  PendingMotion motion_;
  std::optional<Token> last_camera_position_;  // the last eyePoint or viewPoint
  std::optional<Token> up_direction_;
};

// ---- The keyword table (sdl_keywords.cpp)

using KeywordHandler = void (*)(FileParser&);

struct Keyword {
  std::string_view name;  // canonical spelling; matching is case-insensitive
  KeywordHandler handler;
};

// The keyword spelled `name` in any case, or null.
const Keyword* find_keyword(std::string_view name);

}  // namespace tessera::sdl
