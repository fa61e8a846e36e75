// libFuzzer target: a POST /api/jobs body (JSON, multipart or tar, picked by the first byte)
// through the coordinator's parse_job_request with lowered limits (tests/fuzz/
// service_fuzz_checks.h says what is checked). A refusal with an ApiError is a normal outcome;
// a crash, a sanitizer report, another exception, a broken invariant or a hang is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tests/fuzz/service_fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tessera::fuzz::check_job_request_input(
      std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
