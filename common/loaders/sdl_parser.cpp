#include "common/loaders/sdl_parser.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "common/image/decoded_texture.h"
#include "common/loaders/hill_mesh_loader.h"
#include "common/loaders/lexical.h"
#include "common/loaders/obj_loader.h"
#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"

namespace tessera::sdl {

struct SourceFile {
  std::string path;  // root-relative
  std::string text;
  LexedText lexed;  // tokens point into `text`
};

struct Macro {
  std::string name;  // as written in its def
  std::vector<Token> tokens;
  Token where;  // the name in the def
};

using MeshLoader = Mesh (*)(std::string_view text, const std::string& file);

// ---------------------------------------------------------------------------------------------
// LoadContext: what one load shares across its files

class LoadContext {
 public:
  LoadContext(const SceneSource& source, LoadMeter& meter) : source_(source), meter_(meter) {}

  Scene load(const std::string& path) {
    const SourceLocation start{path, 1, 1};
    const std::optional<std::string> resolved = resolve_scene_path("", path);
    if (!resolved) throw SceneError(start, "scene path " + in_quotes(path) + " is not a file name");
    const SourceFile& file = sdl_file(*resolved, start, "scene file");
    include_chain_.push_back(*resolved);
    FileParser parser(*this, file, /*included=*/false);
    parser.run();
    parser.validate_camera();
    parser.validate_csg();
    return std::move(scene_);
  }

  Scene& scene() { return scene_; }
  LoadMeter& meter() { return meter_; }
  const SceneSource& source() const { return source_; }
  const LoadBudget& budget() const { return meter_.budget(); }
  std::unordered_map<std::string, Macro>& macros() { return macros_; }
  const std::string& path_of(const Token& token) const { return files_[token.file]->path; }
  SourceLocation location(const Token& token) const {
    return {path_of(token), token.line, token.column};
  }
  [[noreturn]] void fail(const Token& at, const std::string& message) const {
    throw SceneError(location(at), message);
  }

  void count_token(const Token& token) {
    meter_.add(LoadLimit::Tokens, 1, [&] { return location(token); });
  }
  // An include or a macro use: a replay, nested in those being read.
  void enter_nesting(const Token& at) {
    meter_.add(LoadLimit::UseReplays, 1, [&] { return location(at); });
    const std::uint64_t limit = budget().max_replay_nesting;
    if (++nesting_ > limit) {
      meter_.fail(
          LoadLimit::ReplayNesting, location(at),
          "include and use are nested too deeply (more than " + std::to_string(limit) + " levels)");
    }
  }
  void leave_nesting() { --nesting_; }

  // ---- Boolean objects being read (§3.2.4), innermost last; shared by included files, so
  // that a child may come from an include or a macro.
  struct OpenCsg {
    CsgOperation operation;
    Token keyword;
    std::optional<std::uint32_t> left;  // the first child, once read
  };
  const std::vector<OpenCsg>& open_csg() const { return open_csg_; }
  void begin_csg(CsgOperation operation, const Token& keyword) {
    if (open_csg_.size() >= budget().max_csg_depth) {
      meter_.fail(LoadLimit::CsgDepth, location(keyword),
                  "boolean objects are nested too deeply (more than " +
                      std::to_string(budget().max_csg_depth) + " levels)");
    }
    open_csg_.push_back({operation, keyword, std::nullopt});
  }
  // Object `index` was just added: it becomes the next child of the innermost open boolean
  // object, which, once it has two, is added as an object itself, and so on outwards.
  void place_object(std::uint32_t index) {
    while (!open_csg_.empty()) {
      OpenCsg& node = open_csg_.back();
      if (!node.left) {
        node.left = index;
        return;
      }
      meter_.add_object(location(node.keyword));
      scene_.objects.push_back({CsgShape{node.operation, *node.left, index}, Affine::identity(),
                                Material{}, location(node.keyword), std::nullopt});
      index = static_cast<std::uint32_t>(scene_.objects.size() - 1);
      open_csg_.pop_back();
    }
  }

  void warn(const std::string& warning) {
    if (!warning_set_.insert(warning).second) return;
    if (scene_.warnings.size() < budget().max_warnings) {
      scene_.warnings.push_back(warning);
    } else if (scene_.warnings.size() == budget().max_warnings) {
      scene_.warnings.push_back("further warnings are omitted");
    }
  }

  void include(const std::string& path, const Token& name, const Token& keyword) {
    const auto cycle_start = std::find(include_chain_.begin(), include_chain_.end(), path);
    if (cycle_start != include_chain_.end()) {
      std::string cycle;
      for (auto it = cycle_start; it != include_chain_.end(); ++it) cycle += *it + " -> ";
      fail(name, "include cycle: " + cycle + path);
    }
    enter_nesting(keyword);
    const SourceFile& file = sdl_file(path, location(name), "included file");
    include_chain_.push_back(path);
    FileParser parser(*this, file, /*included=*/true);
    parser.run();
    include_chain_.pop_back();
    leave_nesting();
  }

  std::size_t mesh(const std::string& path, const Token& name, MeshLoader loader) {
    const auto known = mesh_ids_.find(path);
    if (known != mesh_ids_.end()) return known->second;
    const std::string bytes = read(path, location(name), "mesh file");
    Mesh mesh = loader(bytes, path);
    if (mesh.triangles.empty()) fail(name, "mesh " + in_quotes(path) + " has no triangles");
    meter_.add_mesh(mesh, location(name));
    scene_.meshes.push_back(std::move(mesh));
    mesh_ids_.emplace(path, scene_.meshes.size() - 1);
    return scene_.meshes.size() - 1;
  }

  void image(const std::string& path, const Token& name) {
    if (!image_paths_.insert(path).second) return;
    std::string bytes = read(path, location(name), "image file");
    std::size_t pixels = 0;
    try {
      pixels = texture_pixels(bytes, path);
    } catch (const std::runtime_error&) {
      // Undecodable: the scene's preparation refuses it, placed here, with the reason.
    }
    meter_.add_texture(bytes.size(), pixels, location(name));  // kept in the scene
    scene_.images.push_back({path, std::move(bytes), location(name)});
  }

  std::size_t built_in_mesh(const std::string& name, Mesh (*make)(), const SourceLocation& at) {
    const auto known = built_in_mesh_ids_.find(name);
    if (known != built_in_mesh_ids_.end()) return known->second;
    scene_.meshes.push_back(make());
    meter_.add_mesh(scene_.meshes.back(), at);
    built_in_mesh_ids_.emplace(name, scene_.meshes.size() - 1);
    return scene_.meshes.size() - 1;
  }

 private:
  std::string read(const std::string& path, const SourceLocation& at, const std::string& kind) {
    std::optional<std::string> bytes = source_.read(path);
    if (!bytes) throw SceneError(at, kind + " " + in_quotes(path) + " not found");
    const std::uint64_t limit = budget().max_file_bytes;
    if (bytes->size() > limit) {
      const std::string size = limit % (1u << 20) == 0 ? std::to_string(limit >> 20) + " MiB"
                                                       : std::to_string(limit) + " bytes";
      meter_.fail(LoadLimit::FileBytes, at,
                  kind + " " + in_quotes(path) + " is larger than " + size);
    }
    meter_.add(LoadLimit::BytesRead, bytes->size(), at);
    return std::move(*bytes);
  }

  // An SDL file, read and lexed once however often it is included.
  const SourceFile& sdl_file(const std::string& path, const SourceLocation& at,
                             const std::string& kind) {
    const auto known = file_ids_.find(path);
    if (known != file_ids_.end()) return *files_[known->second];
    auto file = std::make_unique<SourceFile>();
    file->path = path;
    file->text = read(path, at, kind);
    const auto id = static_cast<std::uint32_t>(files_.size());
    file->lexed = lex_sdl(file->text, id);
    meter_.add(LoadLimit::BytesProduced,
               file->text.size() + file->lexed.tokens.size() * sizeof(Token), at);
    files_.push_back(std::move(file));
    file_ids_.emplace(path, id);
    return *files_.back();
  }

  const SceneSource& source_;
  LoadMeter& meter_;
  Scene scene_;
  std::vector<std::unique_ptr<SourceFile>> files_;  // indexed by Token::file
  std::unordered_map<std::string, std::uint32_t> file_ids_;
  std::unordered_map<std::string, std::size_t> mesh_ids_;           // into Scene::meshes, by path
  std::unordered_map<std::string, std::size_t> built_in_mesh_ids_;  // by keyword
  std::unordered_set<std::string> image_paths_;                     // in Scene::images
  std::unordered_map<std::string, Macro> macros_;                   // by lower-case name
  std::vector<std::string> include_chain_;  // files being parsed, outermost first
  std::vector<OpenCsg> open_csg_;
  std::unordered_set<std::string> warning_set_;
  std::uint64_t nesting_ = 0;
};

// ---------------------------------------------------------------------------------------------
// FileParser: the token stream

FileParser::FileParser(LoadContext& context, const SourceFile& file, bool included)
    : context_(context), file_(file), included_(included) {
  frames_.push_back({&file.lexed.tokens, 0, nullptr});
}

Scene& FileParser::scene() { return context_.scene(); }

SourceLocation FileParser::location(const Token& token) const { return context_.location(token); }

void FileParser::fail(const Token& at, const std::string& message) const {
  context_.fail(at, message);
}

void FileParser::fail_at_end(const std::string& what) const {
  throw SceneError({file_.path, file_.lexed.end_line, file_.lexed.end_column},
                   "unexpected end of file, expected " + what);
}

const Token* FileParser::peek() {
  // A replay is left only when the token after its last one is asked for: while its last
  // token is being handled it is still on the stack, so a macro that uses itself in tail
  // position is caught as recursion.
  while (frames_.back().next == frames_.back().tokens->size()) {
    if (frames_.size() == 1) return nullptr;
    frames_.pop_back();
    context_.leave_nesting();
  }
  const Frame& frame = frames_.back();
  return &(*frame.tokens)[frame.next];
}

std::optional<Token> FileParser::next() {
  const Token* token = peek();
  if (token == nullptr) return std::nullopt;
  ++frames_.back().next;
  context_.count_token(*token);
  return *token;
}

Token FileParser::expect(const std::string& what) {
  const std::optional<Token> token = next();
  if (!token) fail_at_end(what);
  return *token;
}

void FileParser::run() {
  while (const std::optional<Token> token = next()) {
    keyword_ = *token;
    keyword_name_ = {};
    if (token->text == "{" || token->text == "}") {
      fail(*token, "unexpected " + in_quotes(token->text) + " (braces belong to 'def <name> { }')");
    }
    const Keyword* entry = find_keyword(token->text);
    if (entry == nullptr) fail(*token, "unknown keyword " + in_quotes(token->text));
    keyword_name_ = entry->name;
    entry->handler(*this);
  }
}

// ---------------------------------------------------------------------------------------------
// FileParser: parameters

namespace {

bool in_range(double v, Range range) {
  switch (range) {
    case Range::Any:
      return true;
    case Range::NonNegative:
      return v >= 0;
    case Range::Positive:
      return v > 0;
    case Range::UnitInterval:
      return v >= 0 && v <= 1;
    case Range::OpenAngle:
      return v > 0 && v < 180;
    case Range::Cutoff:
      return v > 0 && v <= 180;
  }
  return false;
}

const char* describe(Range range) {
  switch (range) {
    case Range::Any:
      return "a number";
    case Range::NonNegative:
      return "non-negative";
    case Range::Positive:
      return "positive";
    case Range::UnitInterval:
      return "in [0, 1]";
    case Range::OpenAngle:
      return "strictly between 0 and 180 degrees";
    case Range::Cutoff:
      return "in (0, 180] degrees";
  }
  return "";
}

}  // namespace

std::string FileParser::of_keyword(const char* param) const {
  return std::string(param) + " of '" + std::string(keyword_name_) + "'";
}

Token FileParser::word(const std::string& what) {
  const Token token = expect(what);
  if (token.text == "{" || token.text == "}") {
    fail(token, "expected " + what + ", found " + in_quotes(token.text));
  }
  return token;
}

// Messages are built only on the error paths: numbers are most of a large scene's tokens.
Number FileParser::read_number(const char* param, Range range) {
  const std::optional<Token> token = next();
  if (!token) fail_at_end("a number for " + of_keyword(param));
  const DecimalResult result = parse_decimal(token->text);
  if (result.status == DecimalStatus::OutOfRange) {
    fail(*token,
         "number " + in_quotes(token->text) + " for " + of_keyword(param) + " is out of range");
  }
  if (result.status != DecimalStatus::Ok) {
    fail(*token,
         "expected a number for " + of_keyword(param) + ", found " + in_quotes(token->text));
  }
  if (!in_range(result.value, range)) {
    fail(*token,
         of_keyword(param) + " must be " + describe(range) + ", found " + in_quotes(token->text));
  }
  return {result.value, *token};
}

int FileParser::integer(const char* param, int min, int max) {
  const std::optional<Token> token = next();
  if (!token) fail_at_end("an integer for " + of_keyword(param));
  const DecimalResult result = parse_decimal(token->text);
  if (result.status != DecimalStatus::Ok || result.value != std::floor(result.value)) {
    fail(*token,
         "expected an integer for " + of_keyword(param) + ", found " + in_quotes(token->text));
  }
  if (result.value < min || result.value > max) {
    const std::string interval =
        max != INT_MAX       ? "between " + std::to_string(min) + " and " + std::to_string(max)
        : result.value < min ? "at least " + std::to_string(min)
                             : "at most " + std::to_string(max);
    fail(*token, of_keyword(param) + " must be " + interval + ", found " + in_quotes(token->text));
  }
  return static_cast<int>(result.value);
}

bool FileParser::flag(const char* param) { return number(param) != 0; }

bool FileParser::number_follows() {
  const Token* token = peek();
  return token != nullptr && parse_decimal(token->text).status != DecimalStatus::NotANumber;
}

Vec3 FileParser::vec3(const char* x, const char* y, const char* z) {
  const double vx = number(x);
  const double vy = number(y);
  const double vz = number(z);
  return {vx, vy, vz};
}

Rgb FileParser::color(const char* r, const char* g, const char* b) {
  const double red = number(r, Range::NonNegative);
  const double green = number(g, Range::NonNegative);
  const double blue = number(b, Range::NonNegative);
  return {red, green, blue};
}

// ---------------------------------------------------------------------------------------------
// FileParser: effects of statements

void FileParser::push_ct() {
  const std::uint64_t limit = context_.budget().max_push_depth;
  if (ct_stack_.size() >= limit) {
    context_.meter().fail(LoadLimit::PushDepth, location(keyword_),
                          "too many nested 'push' (more than " + std::to_string(limit) + ")");
  }
  ct_stack_.push_back(ct_);
}

void FileParser::pop_ct() {
  if (ct_stack_.empty()) fail(keyword_, "'pop' without a matching 'push'");
  ct_ = ct_stack_.back();
  ct_stack_.pop_back();
}

namespace {

// "'union' at scene.sdl:3:1": the boolean object a message is about.
std::string csg_at(const LoadContext& context, const Token& keyword) {
  return in_quotes(keyword.text) + " at " + context.location(keyword).to_string();
}

}  // namespace

void FileParser::add_object(const ShapeGeometry& geometry) {
  const std::string name = "'" + std::string(keyword_name_) + "'";
  if (!ct_.is_finite()) fail(keyword_, name + " has a transform that is not finite (too large?)");
  if (!ct_.inverse()) fail(keyword_, name + " has a singular transform (zero scale?)");
  const auto& open = context_.open_csg();
  if (!open.empty() && std::holds_alternative<AlgebraicSurface>(geometry)) {
    fail(keyword_, name + " cannot be a child of " + csg_at(context_, open.back().keyword) +
                       ": an algebraic surface is clipped to a box in world space, not a solid");
  }
  Scene& s = scene();
  context_.meter().add_object(location(keyword_));
  std::optional<ObjectMotion> motion;
  if (motion_.enabled) {
    if (std::holds_alternative<AlgebraicSurface>(geometry))
      fail(keyword_, name + " cannot move: algebraic surfaces do not take motion blur");
    motion = motion_.motion;
  }
  motion_ = {};  // every shape clears the motion (§3.2.6)
  s.objects.push_back({geometry, ct_, material_, location(keyword_), motion});
  context_.place_object(static_cast<std::uint32_t>(s.objects.size() - 1));
}

void FileParser::begin_csg(CsgOperation operation) { context_.begin_csg(operation, keyword_); }

void FileParser::refuse_in_csg() const {
  const auto& open = context_.open_csg();
  if (open.empty()) return;
  fail(keyword_, "expected a shape or a boolean object as the next child of " +
                     csg_at(context_, open.back().keyword) + ", found '" +
                     std::string(keyword_name_) + "'");
}

void FileParser::add_light(const Light& light) {
  refuse_in_csg();
  context_.meter().add_light(location(keyword_));
  scene().lights.push_back(light);
}

std::string FileParser::resolve(const Token& name) {
  const std::optional<std::string> path =
      resolve_scene_path(context_.path_of(name), std::string(name.text));
  if (!path || !context_.source().admits(*path)) {
    fail(name,
         std::string(keyword_name_) + " " + in_quotes(name.text) + " leaves the scene's folder");
  }
  return *path;
}

std::size_t FileParser::mesh(const Token& name) {
  const std::string path = resolve(name);
  const std::size_t slash = path.rfind('/');
  const std::size_t dot = path.rfind('.');
  const std::string extension =
      dot == std::string::npos || (slash != std::string::npos && dot < slash)
          ? std::string()
          : to_lower(std::string_view(path).substr(dot + 1));
  // The extensions the manual names give the format; any other name is read as Hill's
  // programs read it, as a 3VN (or 3DV, 3DM) mesh told by its content.
  MeshLoader loader = load_hill_mesh;
  if (extension == "obj") loader = load_obj;
  if (extension == "3vn") loader = load_3vn;
  if (extension == "3dv") loader = load_3dv;
  if (extension == "3dm") loader = load_3dm;
  return context_.mesh(path, name, loader);
}

void FileParser::image(const std::string& path, const Token& name) { context_.image(path, name); }

std::size_t FileParser::built_in_mesh(Mesh (*make)()) {
  return context_.built_in_mesh(std::string(keyword_name_), make, location(keyword_));
}

void FileParser::include(const Token& name) { context_.include(resolve(name), name, keyword_); }

void FileParser::define() {
  const Token name = word("a macro name after 'def'");
  const std::string opening = "'{' after 'def " + std::string(name.text) + "'";
  const Token open = expect(opening);
  if (open.text != "{") fail(open, "expected " + opening + ", found " + in_quotes(open.text));
  Macro macro{std::string(name.text), {}, name};
  int depth = 1;
  while (true) {
    const std::optional<Token> token = next();
    if (!token) {
      fail_at_end("'}' to close 'def " + std::string(name.text) + "' opened at " +
                  std::to_string(open.line) + ":" + std::to_string(open.column));
    }
    if (token->text == "{") ++depth;
    if (token->text == "}" && --depth == 0) break;
    macro.tokens.push_back(*token);
  }
  auto& macros = context_.macros();
  const std::string key = to_lower(name.text);
  const auto existing = macros.find(key);
  if (existing != macros.end()) {
    fail(name, "macro " + in_quotes(name.text) + " is already defined at " +
                   location(existing->second.where).to_string());
  }
  macros.emplace(key, std::move(macro));
}

void FileParser::use() {
  const Token name = word("a macro name after 'use'");
  const auto& macros = context_.macros();
  const auto found = macros.find(to_lower(name.text));
  if (found == macros.end()) fail(name, "macro " + in_quotes(name.text) + " is not defined");
  const Macro& macro = found->second;
  for (const Frame& frame : frames_) {
    if (frame.macro == &macro) {
      fail(name,
           "macro " + in_quotes(macro.name) + " uses itself (directly or through other macros)");
    }
  }
  context_.enter_nesting(keyword_);
  frames_.push_back({&macro.tokens, 0, &macro});
}

void FileParser::warn(const std::string& message) {
  context_.warn(location(keyword_).to_string() + ": " + message);
}

bool FileParser::accept_global() {
  refuse_in_csg();
  if (!included_) return true;
  context_.warn(location(keyword_).to_string() + ": '" + std::string(keyword_name_) +
                "' in an included file is ignored");
  return false;
}

void FileParser::validate_camera() const {
  const Camera& camera = context_.scene().camera;
  const SourceLocation position_at =
      last_camera_position_ ? location(*last_camera_position_) : SourceLocation{file_.path, 1, 1};
  const Vec3 view = view_direction(camera);
  if (view == Vec3{}) {
    throw SceneError(position_at, "eyePoint and viewPoint are the same point");
  }
  if (camera_right(camera, view) == Vec3{}) {
    throw SceneError(up_direction_ ? location(*up_direction_) : position_at,
                     "upDirection is zero or parallel to the view direction");
  }
}

void FileParser::validate_csg() const {
  const auto& open = context_.open_csg();
  if (open.empty()) return;
  fail_at_end(std::string(open.back().left ? "the second" : "a first") + " child of " +
              csg_at(context_, open.back().keyword));
}

}  // namespace tessera::sdl

// ---------------------------------------------------------------------------------------------
// Entry points

namespace tessera {

Scene load_sdl(const SceneSource& source, const std::string& path, const LoadBudget& budget) {
  LoadMeter meter(budget);
  return sdl::LoadContext(source, meter).load(path);
}

Scene load_sdl_file(const std::filesystem::path& file, const LoadBudget& budget) {
  return load_sdl(folder_of(file), file.filename().string(), budget);
}

}  // namespace tessera
