#include "common/loaders/load_budget.h"

namespace tessera {
namespace {

struct LimitInfo {
  std::string_view name;
  std::string_view noun;  // what a total counts, in "more than N <noun>"
};

constexpr std::array<LimitInfo, static_cast<std::size_t>(LoadLimit::Cancel) + 1> kLimits{{
    {"nodes", "nodes"},
    {"use_replays", "USE replays"},
    {"proto_instances", "PROTO instances"},
    {"inline_expansions", "Inline expansions"},
    {"tokens", "tokens to parse, counting includes and macro uses"},
    {"objects", "objects"},
    {"lights", "lights"},
    {"triangles", "mesh triangles"},
    {"bytes_read", "bytes read and inflated"},
    {"bytes_produced", "bytes of memory (estimated)"},
    {"file_bytes", ""},
    {"node_nesting", ""},
    {"replay_nesting", ""},
    {"inline_depth", ""},
    {"csg_depth", ""},
    {"push_depth", ""},
    {"deadline", ""},
    {"cancel", ""},
}};

// Memory of a BVH over `n` primitives: about two nodes each, with their bounds, and an index.
std::uint64_t bvh_bytes(std::uint64_t n) { return n * (2 * 32 + 4); }

}  // namespace

std::string_view limit_name(LoadLimit limit) {
  return kLimits[static_cast<std::size_t>(limit)].name;
}

std::uint64_t limit_value(const LoadBudget& b, LoadLimit limit) {
  switch (limit) {
    case LoadLimit::Nodes:
      return b.max_nodes;
    case LoadLimit::UseReplays:
      return b.max_use_replays;
    case LoadLimit::ProtoInstances:
      return b.max_proto_instances;
    case LoadLimit::InlineExpansions:
      return b.max_inline_expansions;
    case LoadLimit::Tokens:
      return b.max_tokens;
    case LoadLimit::Objects:
      return b.max_objects;
    case LoadLimit::Lights:
      return b.max_lights;
    case LoadLimit::Triangles:
      return b.max_triangles;
    case LoadLimit::BytesRead:
      return b.max_bytes_read;
    case LoadLimit::BytesProduced:
      return b.max_bytes_produced;
    case LoadLimit::FileBytes:
      return b.max_file_bytes;
    case LoadLimit::NodeNesting:
      return b.max_node_nesting;
    case LoadLimit::ReplayNesting:
      return b.max_replay_nesting;
    case LoadLimit::InlineDepth:
      return b.max_inline_depth;
    case LoadLimit::CsgDepth:
      return b.max_csg_depth;
    case LoadLimit::PushDepth:
      return b.max_push_depth;
    case LoadLimit::Deadline:
    case LoadLimit::Cancel:
      return 0;
  }
  return 0;
}

std::uint64_t estimated_bytes(const Mesh& mesh) {
  return mesh.positions.size() * sizeof(Vec3) + mesh.normals.size() * sizeof(Vec3) +
         mesh.triangles.size() * sizeof(MeshTriangle) + mesh.corner_colours.size() * sizeof(Rgb) +
         mesh.corner_tex_coords.size() * sizeof(TexCoord) + bvh_bytes(mesh.triangles.size());
}

void LoadMeter::add_object(const SourceLocation& at) {
  add(LoadLimit::Objects, 1, at);
  add(LoadLimit::BytesProduced, kObjectBytes, at);
}

void LoadMeter::add_light(const SourceLocation& at) {
  add(LoadLimit::Lights, 1, at);
  add(LoadLimit::BytesProduced, kLightBytes, at);
}

void LoadMeter::add_texture(std::uint64_t file_bytes, std::uint64_t pixels,
                            const SourceLocation& at) {
  add(LoadLimit::BytesProduced, file_bytes + pixels * kTexturePixelBytes, at);
}

void LoadMeter::add_mesh(const Mesh& mesh, const SourceLocation& at) {
  add(LoadLimit::Triangles, mesh.triangles.size(), at);
  add(LoadLimit::BytesProduced, estimated_bytes(mesh), at);
}

void LoadMeter::fail(LoadLimit limit, const SourceLocation& at, const std::string& what) const {
  throw LoadBudgetExceeded(at, limit, limit_value(budget_, limit),
                           what + " (limit " + std::string(limit_name(limit)) + ")");
}

bool LoadMeter::out_of_time() const {
  return (budget_.cancel && budget_.cancel->load(std::memory_order_relaxed)) ||
         (budget_.deadline != std::chrono::steady_clock::time_point::max() &&
          std::chrono::steady_clock::now() >= budget_.deadline);
}

void LoadMeter::exceeded(LoadLimit limit, const SourceLocation& at) const {
  const std::uint64_t value = limit_value(budget_, limit);
  fail(limit, at,
       "the scene expands to more than " + std::to_string(value) + " " +
           std::string(kLimits[index(limit)].noun));
}

void LoadMeter::stopped(const SourceLocation& at) const {
  if (budget_.cancel && budget_.cancel->load(std::memory_order_relaxed))
    throw LoadBudgetExceeded(at, LoadLimit::Cancel, 0, "loading was cancelled");
  throw LoadBudgetExceeded(at, LoadLimit::Deadline, 0, "loading took longer than its time budget");
}

}  // namespace tessera
