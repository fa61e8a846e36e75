// Helpers shared by the VRML loader tests: parse or load VRML text from memory, measure a mesh.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_lexer.h"
#include "common/loaders/vrml_loader.h"
#include "common/loaders/vrml_parser.h"
#include "tests/loaders/loader_test_util.h"

namespace tessera::test {

inline constexpr const char* kVrmlHeader = "#VRML V2.0 utf8\n";

// A 1 x 1 white RGB image (binary PPM) for textures: what OpenImageIO decodes.
inline const std::string kTinyPpm = "P6\n1 1\n255\n\xff\xff\xff";

// A budget that makes what lenient loading warns about an error (--strict).
inline LoadBudget strict_budget() {
  LoadBudget budget;
  budget.strict = true;
  return budget;
}

// Parses `body` (after the header line) as "world.wrl".
inline vrml::ParsedWorld parse_world(const std::string& body, const LoadBudget& budget = {}) {
  return vrml::parse_vrml(vrml::lex_vrml(kVrmlHeader + body, "world.wrl"), budget);
}

// Loads `body` (after the header line) as "world.wrl", next to `files`.
inline Scene load_world(const std::string& body, Files files = {}, const LoadBudget& budget = {}) {
  MemorySource source(std::move(files));
  source.add("world.wrl", kVrmlHeader + body);
  return load_vrml(source, "world.wrl", budget);
}

// The total area of a mesh's triangles.
inline double mesh_area(const Mesh& mesh) {
  double sum = 0;
  for (const MeshTriangle& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t.v[0]], &b = mesh.positions[t.v[1]],
               &c = mesh.positions[t.v[2]];
    sum += length(cross(b - a, c - a)) / 2;
  }
  return sum;
}

// Succeeds when loading `body` throws a SceneError at world.wrl:line:column (lines counted
// with the header as line 1) with exactly `message`.
inline ::testing::AssertionResult world_fails_at(const std::string& body, int line, int column,
                                                 const std::string& message,
                                                 const LoadBudget& budget = {}) {
  try {
    load_world(body, {}, budget);
  } catch (const SceneError& e) {
    const SourceLocation& at = e.where();
    if (at.file == "world.wrl" && at.line == line && at.column == column && e.message() == message)
      return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "got      " << e.what() << "\nexpected world.wrl:" << line << ":" << column << ": "
           << message;
  }
  return ::testing::AssertionFailure() << "no error; expected " << message;
}

}  // namespace tessera::test
