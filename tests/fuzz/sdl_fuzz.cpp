// libFuzzer target: SDL text, loaded, prepared and rendered at 3x2 pixels. A scene error is a
// normal outcome; a crash, a sanitizer report or a hang is a bug. Limits are lowered so each
// input stays fast (the defaults are tested in tests/loaders/load_budget_test.cpp).
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_loader.h"
#include "tests/fuzz/fuzz_render.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  MemorySource source;
  source.add("scene.sdl", std::string(reinterpret_cast<const char*>(data), size));
  LoadBudget budget;
  budget.max_objects = 2000;
  budget.max_lights = 100;
  budget.max_tokens = 1u << 20;
  try {
    fuzz::prepare_and_render(load_sdl(source, "scene.sdl", budget));
  } catch (const SceneError&) {
  }
  return 0;
}
