// Helpers shared by the loader tests: load SDL text from memory and check located errors.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"
#include "common/scene/scene.h"

namespace tessera::test {

using Files = std::map<std::string, std::string>;

// Loads `text` as "scene.sdl", next to `files`.
inline Scene load_text(const std::string& text, Files files = {}) {
  MemorySource source(std::move(files));
  source.add("scene.sdl", text);
  return load_sdl(source, "scene.sdl");
}

// Succeeds when loading `text` (as "scene.sdl" next to `files`) throws a SceneError at
// file:line:column with exactly `message`.
inline ::testing::AssertionResult fails_with(const std::string& text, const std::string& file,
                                             int line, int column, const std::string& message,
                                             Files files = {}) {
  try {
    load_text(text, std::move(files));
  } catch (const SceneError& e) {
    const SourceLocation& at = e.where();
    if (at.file == file && at.line == line && at.column == column && e.message() == message) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "got      " << e.what() << "\nexpected " << file << ":"
                                         << line << ":" << column << ": " << message;
  }
  return ::testing::AssertionFailure() << "no error; expected " << message;
}

// The same for errors in "scene.sdl" itself.
inline ::testing::AssertionResult fails_at(const std::string& text, int line, int column,
                                           const std::string& message, Files files = {}) {
  return fails_with(text, "scene.sdl", line, column, message, std::move(files));
}

inline ::testing::AssertionResult near(const Vec3& a, const Vec3& b, double tolerance = 1e-12) {
  if (std::fabs(a.x - b.x) <= tolerance && std::fabs(a.y - b.y) <= tolerance &&
      std::fabs(a.z - b.z) <= tolerance) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") vs ("
                                       << b.x << ", " << b.y << ", " << b.z << ")";
}

// A valid OBJ mesh: one triangle.
inline constexpr const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

}  // namespace tessera::test
