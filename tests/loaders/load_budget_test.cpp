// The load budget (issue 16 §2): hostile scenes, each a small generated string, stop at the
// limit they go over, named; a deadline or a cancel flag stops a bomb at once; an Inlined file
// is read and parsed once however many Inlines name it.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <map>
#include <string>

#include "common/image/decoded_texture.h"
#include "common/loaders/load_budget.h"
#include "common/loaders/scene_loader.h"
#include "common/loaders/vrml_parser.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {
namespace {

constexpr const char* kHeader = "#VRML V2.0 utf8\n";

// The name of the limit that loading `path` of `files` within `budget` goes over, "loaded" when
// it loads, or the message of another error.
std::string limit_passed(const Files& files, const std::string& path,
                         const LoadBudget& budget = {}) {
  MemorySource source(files);
  try {
    load_scene(source, path, scene_format_of(path), budget);
  } catch (const LoadBudgetExceeded& e) {
    return std::string(e.limit_name());
  } catch (const SceneError& e) {
    return std::string("other error: ") + e.what();
  }
  return "loaded";
}

std::string world_limit(const std::string& body, const LoadBudget& budget = {}) {
  return limit_passed({{"w.wrl", kHeader + body}}, "w.wrl", budget);
}

std::string sdl_limit(const std::string& text, const LoadBudget& budget = {}, Files files = {}) {
  files["s.sdl"] = text;
  return limit_passed(files, "s.sdl", budget);
}

// DEF A0 <leaf>, DEF A1 Transform { children [USE A0 USE A0] }, ... up to A<levels>, each a
// root: walking A<k> visits 2^(k+1) - 2 nodes beyond their first visit.
std::string doubling_world(int levels, const std::string& leaf) {
  std::string body = "DEF A0 " + leaf + "\n";
  for (int k = 1; k <= levels; ++k) {
    const std::string prev = "A" + std::to_string(k - 1);
    body += "DEF A" + std::to_string(k) + " Transform { children [USE " + prev + " USE " + prev +
            "] }\n";
  }
  return body;
}

LoadBudget with(std::uint64_t LoadBudget::*limit, std::uint64_t value) {
  LoadBudget budget;
  budget.*limit = value;
  return budget;
}

TEST(LoadBudget, UseReplaysOfShapelessNodesAreCountedExactly) {
  // Replays: A1 2, A2 6, A3 14: 22 in all.
  const std::string world = doubling_world(3, "Transform {}");
  EXPECT_EQ(world_limit(world, with(&LoadBudget::max_use_replays, 22)), "loaded");
  EXPECT_EQ(world_limit(world, with(&LoadBudget::max_use_replays, 21)), "use_replays");
}

// (Without the limit the walk would take 2^60 steps: the test would never end. How fast the
// limit is reached is a benchmark's question, not a test's: docs/SERVICE.md has the figures.)
TEST(LoadBudget, ADoublingChainStopsAtTheDefaultReplayLimit) {
  MemorySource source({{"w.wrl", kHeader + doubling_world(60, "Transform {}")}});
  try {
    load_scene(source, "w.wrl", SceneFormat::Vrml);
    FAIL() << "loaded";
  } catch (const LoadBudgetExceeded& e) {
    EXPECT_EQ(e.limit(), LoadLimit::UseReplays);
    EXPECT_EQ(e.limit_value(), 1'000'000u);
    EXPECT_EQ(e.message(),
              "the scene expands to more than 1000000 USE replays (limit use_replays)");
  }
  // The error names the replayed node: the first replay is of A0, a Transform at 2:8.
  source.add("w.wrl", kHeader + doubling_world(1, "Transform {}"));
  try {
    load_scene(source, "w.wrl", SceneFormat::Vrml, with(&LoadBudget::max_use_replays, 0));
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "w.wrl:2:8: the scene expands to more than 0 USE replays (limit use_replays)");
  }
}

TEST(LoadBudget, ADoublingChainOfShapesStops) {
  const std::string world = doubling_world(60, "Shape { geometry Sphere {} }");
  // With the defaults the shapes' memory is the first limit passed; with fewer replays allowed,
  // the replays are.
  EXPECT_EQ(world_limit(world), "bytes_produced");
  EXPECT_EQ(world_limit(world, with(&LoadBudget::max_use_replays, 1000)), "use_replays");
  EXPECT_EQ(world_limit(world, with(&LoadBudget::max_objects, 1000)), "objects");
}

// PROTO P0 [] { Group {} }, PROTO P<k> [] { Group { children [P<k-1> {} P<k-1> {}] } }, and one
// instance of P<levels>.
std::string proto_fan_out(int levels) {
  std::string body = "PROTO P0 [] { Group {} }\n";
  for (int k = 1; k <= levels; ++k) {
    const std::string prev = "P" + std::to_string(k - 1);
    body += "PROTO P" + std::to_string(k) + " [] { Group { children [" + prev + " {} " + prev +
            " {}] } }\n";
  }
  return body + "P" + std::to_string(levels) + " {}\n";
}

TEST(LoadBudget, ProtoInstancesCountTheInstancesInsideTheirBodies) {
  // P1's body: 2; P2's body: 2 x (1 + 2) = 6; the instance of P2: 1 + 6.
  EXPECT_EQ(world_limit(proto_fan_out(2), with(&LoadBudget::max_proto_instances, 15)), "loaded");
  EXPECT_EQ(world_limit(proto_fan_out(2), with(&LoadBudget::max_proto_instances, 14)),
            "proto_instances");
  EXPECT_EQ(world_limit(proto_fan_out(40), with(&LoadBudget::max_proto_instances, 10'000)),
            "proto_instances");
  // Each instance copies its body's nodes.
  LoadBudget more_instances = with(&LoadBudget::max_proto_instances, 1u << 30);
  more_instances.max_nodes = 1000;
  EXPECT_EQ(world_limit(proto_fan_out(40), more_instances), "nodes");
}

// A counting source: how often each file was read.
class CountingSource : public SceneSource {
 public:
  explicit CountingSource(Files files) : files_(std::move(files)) {}
  std::optional<std::string> read(const std::string& path) const override {
    ++reads[path];
    return files_.read(path);
  }
  mutable std::map<std::string, int> reads;

 private:
  MemorySource files_;
};

TEST(LoadBudget, AnInlinedFileIsReadOnceAndCountedAtEveryInline) {
  std::string world = kHeader;
  for (int i = 0; i < 16; ++i)
    world += "Transform { translation " + std::to_string(i) + " 0 0 children Inline { url \"" +
             (i % 2 ? "./" : "") + "part.wrl\" } }\n";
  const Files files{{"w.wrl", world},
                    {"part.wrl", std::string(kHeader) + "Shape { geometry Box {} }\n" +
                                     "Transform { children Shape { geometry Sphere {} } }\n"}};
  CountingSource source(files);
  const Scene scene = load_scene(source, "w.wrl", SceneFormat::Vrml);
  EXPECT_EQ(source.reads["part.wrl"], 1);
  EXPECT_EQ(scene.objects.size(), 32u);
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_inline_expansions, 16)), "loaded");
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_inline_expansions, 15)),
            "inline_expansions");
  // The 15 Inlines after the first walk its 3 nodes again.
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_use_replays, 45)), "loaded");
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_use_replays, 44)), "use_replays");
}

TEST(LoadBudget, InlinesOfItselfStop) {
  const std::string world = "Inline { url \"w.wrl\" } Inline { url \"w.wrl\" }";
  EXPECT_EQ(world_limit(world), "inline_depth");
  LoadBudget deeper = with(&LoadBudget::max_inline_depth, 64);
  deeper.max_inline_expansions = 20;
  EXPECT_EQ(world_limit(world, deeper), "inline_expansions");
}

TEST(LoadBudget, BytesReadAreCountedAcrossFiles) {
  // Three files of 100 bytes: each within any per-file limit, together over 250.
  const std::string part = std::string(kHeader) + "Group {}" + std::string(76, ' ');
  ASSERT_EQ(part.size(), 100u);
  Files files{{"a.wrl", part}, {"b.wrl", part}};
  files["w.wrl"] = std::string(kHeader) + "Inline { url \"a.wrl\" } Inline { url \"b.wrl\" }";
  files["w.wrl"].resize(100, ' ');
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_bytes_read, 300)), "loaded");
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_bytes_read, 250)), "bytes_read");
  EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_file_bytes, 99)), "file_bytes");
}

TEST(LoadBudget, MeshTriangles) {
  const std::string two_triangles =
      "Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }"
      " coordIndex [0 1 2 -1 0 2 3 -1] } }";
  EXPECT_EQ(world_limit(two_triangles, with(&LoadBudget::max_triangles, 2)), "loaded");
  EXPECT_EQ(world_limit(two_triangles, with(&LoadBudget::max_triangles, 1)), "triangles");
  // 3000 spine points by 3000 cross-section points: about 18 million triangles, refused
  // before they are made.
  std::string spine, section;
  for (int i = 0; i < 3000; ++i) {
    spine += "0 " + std::to_string(i) + " 0, ";
    section += std::to_string(i) + " 0, ";
  }
  EXPECT_EQ(world_limit("Shape { geometry Extrusion { spine [" + spine + "] crossSection [" +
                        section + "] } }"),
            "triangles");
  EXPECT_EQ(world_limit(
                "Shape { geometry ElevationGrid { xDimension 1000000000 zDimension 1000000000 } }"),
            "triangles");
  // SDL: meshes from files and built in.
  const Files obj{{"m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"}};
  EXPECT_EQ(sdl_limit("mesh m.obj 1", with(&LoadBudget::max_triangles, 2), obj), "loaded");
  EXPECT_EQ(sdl_limit("mesh m.obj 1", with(&LoadBudget::max_triangles, 1), obj), "triangles");
  EXPECT_EQ(sdl_limit("teapot", with(&LoadBudget::max_triangles, 100)), "triangles");
}

TEST(LoadBudget, CsgDepthObjectsAndLights) {
  EXPECT_EQ(sdl_limit("union union sphere sphere sphere", with(&LoadBudget::max_csg_depth, 2)),
            "loaded");
  EXPECT_EQ(sdl_limit("union union union sphere sphere sphere sphere",
                      with(&LoadBudget::max_csg_depth, 2)),
            "csg_depth");
  // A boolean object is an object too: 3 shapes and 2 boolean objects.
  EXPECT_EQ(sdl_limit("union union sphere sphere sphere", with(&LoadBudget::max_objects, 5)),
            "loaded");
  EXPECT_EQ(sdl_limit("union union sphere sphere sphere", with(&LoadBudget::max_objects, 4)),
            "objects");
  const std::string lights = "PointLight {} DirectionalLight {} SpotLight {}";
  EXPECT_EQ(world_limit(lights, with(&LoadBudget::max_lights, 3)), "loaded");
  EXPECT_EQ(world_limit(lights, with(&LoadBudget::max_lights, 2)), "lights");
  EXPECT_EQ(sdl_limit("light 0 0 0 1 1 1 light 0 0 0 1 1 1", with(&LoadBudget::max_lights, 1)),
            "lights");
}

TEST(LoadBudget, SdlMacroUsesAndIncludesAreReplays) {
  // Macros that double at every level: 2^40 uses.
  std::string doubling = "def m0 { push pop }\n";
  for (int i = 1; i <= 40; ++i) {
    const std::string prev = "m" + std::to_string(i - 1);
    doubling += "def m" + std::to_string(i) + " { use " + prev + " use " + prev + " }\n";
  }
  EXPECT_EQ(sdl_limit(doubling + "use m40"), "use_replays");
  const Files part{{"p.sdl", "sphere"}};
  EXPECT_EQ(sdl_limit("include p.sdl include p.sdl include p.sdl",
                      with(&LoadBudget::max_use_replays, 3), part),
            "loaded");
  EXPECT_EQ(sdl_limit("include p.sdl include p.sdl include p.sdl",
                      with(&LoadBudget::max_use_replays, 2), part),
            "use_replays");
}

TEST(LoadBudget, NodesNestingAndMemory) {
  EXPECT_EQ(world_limit("Group {} Group {} Group {}", with(&LoadBudget::max_nodes, 3)), "loaded");
  EXPECT_EQ(world_limit("Group {} Group {} Group {}", with(&LoadBudget::max_nodes, 2)), "nodes");
  EXPECT_EQ(world_limit("Group { children Group { children Group {} } }",
                        with(&LoadBudget::max_node_nesting, 2)),
            "node_nesting");
  // 99,999 numbers in a field: their tokens and values take megabytes.
  std::string numbers;
  for (int i = 0; i < 99'999; ++i) numbers += "1 ";
  const std::string big = "Shape { geometry PointSet { coord Coordinate { point [" + numbers +
                          "] } } } Background { skyAngle [" + numbers + "] }";
  EXPECT_EQ(world_limit(big), "loaded");
  EXPECT_EQ(world_limit(big, with(&LoadBudget::max_bytes_produced, 4u << 20)), "bytes_produced");
  // The parsed values count on top of their tokens, at least 8 bytes a number.
  LoadMeter meter{LoadBudget{}};
  const vrml::LexedFile lexed = vrml::lex_vrml(kHeader + big, "w.wrl", meter);
  const std::uint64_t tokens = meter.total(LoadLimit::BytesProduced);
  vrml::parse_vrml(lexed, meter);
  EXPECT_GE(meter.total(LoadLimit::BytesProduced) - tokens, 99'999 * sizeof(double));
}

TEST(LoadBudget, TexturesCountWhatTheyDecodeTo) {
  // 200x100 black pixels compress to a few hundred bytes and decode to 240,000 (12 a pixel).
  const Files texture = {{"t.tex", encode_decoded_texture(Image(200, 100), 3)}};
  ASSERT_LT(texture.at("t.tex").size(), 2000u);
  const std::string sdl = "imageTexture t.tex 1 1 1\nsphere\n";
  const std::string world =
      "Shape { appearance Appearance { texture ImageTexture { url \"t.tex\" } }"
      " geometry Sphere {} }";
  for (const std::uint64_t budget : {200'000u, 1'000'000u}) {
    const std::string expected = budget < 240'000 ? "bytes_produced" : "loaded";
    EXPECT_EQ(sdl_limit(sdl, with(&LoadBudget::max_bytes_produced, budget), texture), expected);
    Files files = texture;
    files["w.wrl"] = kHeader + world;
    EXPECT_EQ(limit_passed(files, "w.wrl", with(&LoadBudget::max_bytes_produced, budget)),
              expected);
  }
  // A file that is no image costs its bytes; preparing the scene refuses it later.
  EXPECT_EQ(sdl_limit(sdl, {}, {{"t.tex", "no image"}}), "loaded");
}

TEST(LoadBudget, ADeadlineStopsABombPromptly) {
  LoadBudget budget = with(&LoadBudget::max_use_replays, ~std::uint64_t{0});
  const auto start = std::chrono::steady_clock::now();
  budget.deadline = start + std::chrono::milliseconds(50);
  MemorySource source({{"w.wrl", kHeader + doubling_world(60, "Transform {}")}});
  try {
    load_scene(source, "w.wrl", SceneFormat::Vrml, budget);
    FAIL() << "loaded";
  } catch (const LoadBudgetExceeded& e) {
    EXPECT_EQ(e.limit(), LoadLimit::Deadline);
    EXPECT_EQ(e.message(), "loading took longer than its time budget");
  }
  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_GE(elapsed, std::chrono::milliseconds(50));
  EXPECT_LT(elapsed, std::chrono::seconds(1));
}

TEST(LoadBudget, ACancelFlagStopsALoad) {
  std::atomic<bool> cancel{true};
  LoadBudget budget;
  budget.cancel = &cancel;
  MemorySource source({{"w.wrl", kHeader + doubling_world(60, "Transform {}")}});
  try {
    load_scene(source, "w.wrl", SceneFormat::Vrml, budget);
    FAIL() << "loaded";
  } catch (const LoadBudgetExceeded& e) {
    EXPECT_EQ(e.limit_name(), "cancel");
    EXPECT_EQ(e.message(), "loading was cancelled");
  }
  cancel = false;
  EXPECT_EQ(world_limit(doubling_world(3, "Transform {}"), budget), "loaded");
}

}  // namespace
}  // namespace tessera::test
