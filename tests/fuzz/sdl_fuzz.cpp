// libFuzzer target: SDL text, loaded, prepared and rendered (tests/fuzz/fuzz_checks.h says what
// is checked). A scene error is a normal outcome; a crash, a sanitizer report, a broken
// invariant or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tessera::fuzz::check_sdl_input(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
