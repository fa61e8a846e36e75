// libFuzzer target: bytes from a worker's connection through the frame decoder, and each
// Result frame through the coordinator's result validation for a fixed unit (tests/fuzz/
// service_fuzz_checks.h says what is checked). A ProtocolError is a normal outcome; a crash, a
// sanitizer report, another exception, a broken invariant or an allocation over the limit
// (scripts/fuzz.sh sets -malloc_limit_mb) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/service_fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tessera::fuzz::check_worker_frames_input(
      std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
