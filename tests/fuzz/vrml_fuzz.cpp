// libFuzzer target: a VRML world (plain or gzip), loaded, prepared and rendered at 3x2 pixels.
// A scene error is a normal outcome; a crash, a sanitizer report or a hang is a bug. So that
// each input stays fast, worlds are first parsed with lowered limits and only small ones go on
// (the defaults are tested in tests/loaders/vrml_parser_test.cpp); the world may Inline itself.
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_lexer.h"
#include "common/loaders/vrml_loader.h"
#include "common/loaders/vrml_parser.h"
#include "tests/fuzz/fuzz_render.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tessera;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  MemorySource source;
  source.add("world.wrl", bytes);
  vrml::ParseLimits limits;
  limits.max_nesting = 64;
  limits.max_nodes = 5000;
  try {
    vrml::parse_vrml(vrml::lex_vrml(vrml::vrml_text(bytes, "world.wrl", 1u << 20), "world.wrl"),
                     limits);
    fuzz::prepare_and_render(load_vrml(source, "world.wrl"));
  } catch (const SceneError&) {
  }
  return 0;
}
