// One budget per load (issue 16 §2): a hostile scene is stopped by what it PRODUCES, not by its
// size in bytes. A 3 KB VRML world of DEF/USE doublings expands to 2^60 nodes, and one small
// Inlined file named a thousand times is a thousand worlds; so every loader counts the nodes,
// replays, instances, objects, lights, triangles and bytes it makes against the one LoadBudget
// of the load, across all of its files, and gives up with LoadBudgetExceeded at the first limit
// it passes. A deadline and a cancel flag stop a load from outside. docs/SERVICE.md has the
// table of limits.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>

#include "common/scene/mesh.h"
#include "common/scene/source_location.h"

namespace tessera {

struct LoadBudget {
  // ---- Totals over every file of the load
  std::uint64_t max_nodes = 4'000'000;  // VRML nodes parsed and made by PROTO expansion
  // Node visits of the VRML scene walk beyond a node's first (USE, and every Inline of a file
  // after the first), and SDL macro uses and includes.
  std::uint64_t max_use_replays = 1'000'000;
  std::uint64_t max_proto_instances = 1'000'000;  // VRML, nested instances counted
  std::uint64_t max_inline_expansions = 10'000;   // VRML Inlines walked
  std::uint64_t max_tokens = 64ull << 20;         // SDL tokens parsed, replays counted
  std::uint64_t max_objects = 1'000'000;          // shapes and boolean objects
  std::uint64_t max_lights = 100'000;
  std::uint64_t max_triangles = 8'000'000;  // in the scene's meshes (each mesh once)
  // Bytes read from the source (scene files, meshes, images) and inflated from gzip.
  std::uint64_t max_bytes_read = 128ull << 20;
  // An estimate of the memory the load and the scene's preparation for tracing take: tokens,
  // nodes, field values, objects, lights, meshes and their BVH, kept images. With the default,
  // a coordinator's peak for one request stays under about 512 MB.
  std::uint64_t max_bytes_produced = 384ull << 20;

  // ---- Sizes and depths of one thing
  std::uint64_t max_file_bytes = 16ull << 20;  // one file as stored
  std::uint64_t max_node_nesting = 256;        // VRML nodes inside nodes
  std::uint64_t max_replay_nesting = 64;       // SDL includes and macro uses, nested
  std::uint64_t max_inline_depth = 16;         // VRML Inlines inside Inlined files
  std::uint64_t max_csg_depth = 256;           // SDL boolean objects awaiting children
  std::uint64_t max_push_depth = 65'536;       // SDL transforms saved by push

  std::uint64_t max_warnings = 100;  // further warnings are dropped, not an error
  // Lenient loading (false) warns about a missing or undecodable texture, a node or field
  // outside VRML97, an unsupported url, and goes on without that part; strict loading
  // (tessera-render --strict, the job setting "strict") makes each an error.
  bool strict = false;

  // ---- Stopping from outside, checked every few thousand counted items
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  const std::atomic<bool>* cancel = nullptr;  // loading stops once it reads true
};

// Each limit of LoadBudget (but max_warnings), and the two ways a load is stopped from outside.
enum class LoadLimit : std::uint8_t {
  Nodes,
  UseReplays,
  ProtoInstances,
  InlineExpansions,
  Tokens,
  Objects,
  Lights,
  Triangles,
  BytesRead,
  BytesProduced,
  FileBytes,
  NodeNesting,
  ReplayNesting,
  InlineDepth,
  CsgDepth,
  PushDepth,
  Deadline,
  Cancel,
};

// A stable short name for messages, logs and clients: "use_replays", "deadline".
std::string_view limit_name(LoadLimit limit);
// The limit's value in `budget` (0 for Deadline and Cancel).
std::uint64_t limit_value(const LoadBudget& budget, LoadLimit limit);

// A load went over its budget or was stopped: what() reads
// "w.wrl:3:20: the scene expands to more than 1000000 USE replays (limit use_replays)".
class LoadBudgetExceeded : public SceneError {
 public:
  LoadBudgetExceeded(SourceLocation where, LoadLimit limit, std::uint64_t value,
                     const std::string& message)
      : SceneError(std::move(where), message), limit_(limit), value_(value) {}
  LoadLimit limit() const { return limit_; }
  std::string_view limit_name() const { return tessera::limit_name(limit_); }
  std::uint64_t limit_value() const { return value_; }

 private:
  LoadLimit limit_;
  std::uint64_t value_;
};

// Approximate bytes a scene's parts take once loaded and prepared for tracing.
std::uint64_t estimated_bytes(const Mesh& mesh);     // with its BVH
inline constexpr std::uint64_t kObjectBytes = 1024;  // SceneObject, its instance, BVH leaf
inline constexpr std::uint64_t kLightBytes = 256;
// A texture decoded for tracing: 3 floats a pixel (Image), kept with the prepared scene.
inline constexpr std::uint64_t kTexturePixelBytes = 3 * sizeof(float);

// What one load has counted so far, shared by all of its files. Counting is cheap: a `where`
// callable makes the location only when a limit is passed.
class LoadMeter {
 public:
  explicit LoadMeter(const LoadBudget& budget) : budget_(budget) {}
  LoadMeter(const LoadMeter&) = delete;
  LoadMeter& operator=(const LoadMeter&) = delete;

  const LoadBudget& budget() const { return budget_; }
  std::uint64_t total(LoadLimit limit) const { return totals_[index(limit)]; }

  // Adds `amount` to the total of `limit` (one of the totals, Nodes ... BytesProduced); throws
  // LoadBudgetExceeded at where() once it passes the limit, or when time is up.
  template <std::invocable Where>
  void add(LoadLimit limit, std::uint64_t amount, Where&& where) {
    std::uint64_t& total = totals_[index(limit)];
    total += amount;
    if (total > limit_value(budget_, limit)) [[unlikely]]
      exceeded(limit, where());
    if (++calls_ % kCheckEvery == 0 && out_of_time()) [[unlikely]]
      stopped(where());
  }
  void add(LoadLimit limit, std::uint64_t amount, const SourceLocation& at) {
    add(limit, amount, [&] { return at; });
  }
  // Throws as add would, without adding: for what is about to be made all at once.
  void ensure_room(LoadLimit limit, std::uint64_t amount, const SourceLocation& at) const {
    if (amount > limit_value(budget_, limit) - std::min(total(limit), limit_value(budget_, limit)))
      exceeded(limit, at);
  }

  // An object, a light, a mesh: the count and the bytes together.
  void add_object(const SourceLocation& at);
  void add_light(const SourceLocation& at);
  void add_mesh(const Mesh& mesh, const SourceLocation& at);
  // An image file kept in the scene, `file_bytes` as read, and what decoding its `pixels`
  // makes: a PNG of a few kilobytes can decode to 200 MB of floats.
  void add_texture(std::uint64_t file_bytes, std::uint64_t pixels, const SourceLocation& at);

  // Throws as add does when time is up or the load was cancelled: for work that counts
  // nothing against the budget but grows with what was counted (the camera framing a world
  // measures every object, its mesh's vertices each time).
  void check_time(const SourceLocation& at) const {
    if (out_of_time()) [[unlikely]]
      stopped(at);
  }

  // A depth or size (FileBytes ... PushDepth) beyond its limit: `what` says what went too far,
  // " (limit name)" is appended.
  [[noreturn]] void fail(LoadLimit limit, const SourceLocation& at, const std::string& what) const;

 private:
  static constexpr std::uint64_t kCheckEvery = 4096;
  static constexpr std::size_t index(LoadLimit limit) { return static_cast<std::size_t>(limit); }
  bool out_of_time() const;
  [[noreturn]] void exceeded(LoadLimit limit, const SourceLocation& at) const;
  [[noreturn]] void stopped(const SourceLocation& at) const;

  LoadBudget budget_;
  std::array<std::uint64_t, static_cast<std::size_t>(LoadLimit::BytesProduced) + 1> totals_{};
  std::uint64_t calls_ = 0;
};

}  // namespace tessera
