// libFuzzer target: a VRML world (plain or gzip), loaded, prepared and rendered at 3x2 pixels.
// A scene error is a normal outcome; a crash, a sanitizer report or a hang is a bug. So that
// each input stays fast, worlds are loaded with a lowered budget (the defaults are tested in
// tests/loaders/load_budget_test.cpp); the world may Inline itself.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_loader.h"
#include "tests/fuzz/fuzz_render.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  MemorySource source;
  source.add("world.wrl", bytes);
  LoadBudget budget;
  budget.max_node_nesting = 64;
  budget.max_nodes = 5000;
  budget.max_bytes_read = 1u << 20;
  try {
    fuzz::prepare_and_render(load_vrml(source, "world.wrl", budget));
  } catch (const SceneError&) {
  }
  return 0;
}
