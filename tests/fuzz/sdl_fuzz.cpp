// libFuzzer target: SDL text, loaded, prepared and rendered at 3x2 pixels. A scene error is a
// normal outcome; a crash, a sanitizer report or a hang is a bug. Limits are lowered so each
// input stays fast (the defaults are tested in tests/loaders/sdl_include_test.cpp).
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/sdl_parser.h"
#include "tests/fuzz/fuzz_render.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  MemorySource source;
  source.add("scene.sdl", std::string(reinterpret_cast<const char*>(data), size));
  sdl::Limits limits;
  limits.max_objects = 2000;
  limits.max_lights = 100;
  limits.max_tokens = 1u << 20;
  try {
    fuzz::prepare_and_render(sdl::load_sdl_with_limits(source, "scene.sdl", limits));
  } catch (const SceneError&) {
  }
  return 0;
}
