#include "common/accel/wide_box_kernel.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace tessera {
namespace {

WideBoxKernel widest_supported() {
  if (wide_box_kernel_supported(WideBoxKernel::Avx512Vl)) return WideBoxKernel::Avx512Vl;
  if (wide_box_kernel_supported(WideBoxKernel::Avx2)) return WideBoxKernel::Avx2;
  if (wide_box_kernel_supported(WideBoxKernel::Sse2)) return WideBoxKernel::Sse2;
  return WideBoxKernel::Scalar;
}

WideBoxKernel automatic_choice() {
#if defined(__SSE2__)
  __builtin_cpu_init();  // run from a static initializer: __builtin_cpu_supports needs it there
#endif
  if (const char* name = std::getenv("TESSERA_BOX_KERNEL")) {
    const auto kernel = parse_wide_box_kernel(name);
    if (kernel && wide_box_kernel_supported(*kernel)) return *kernel;
  }
  return widest_supported();
}

// The automatic choice, made once when the program starts (the environment and the CPU do not
// change), and the kernel in use, which force_wide_box_kernel changes: wide_box_kernel() reads it
// for every mesh ray, and as function-local statics the choice cost a guard's load and test and
// the forced kernel's another, seven instructions and two branches a ray (docs/PERFORMANCE.md
// "An incoherent ray's set-up"). A traversal run by another file's static initializer, before
// these are made, would read the zero-initialized Scalar: the same results, only slower.
const WideBoxKernel automatic = automatic_choice();
WideBoxKernel in_use = automatic;

}  // namespace

bool wide_box_kernel_supported(WideBoxKernel kernel) {
  switch (kernel) {
    case WideBoxKernel::Scalar:
      return true;
    case WideBoxKernel::Sse2:
#if defined(__SSE2__)
      return true;
#else
      return false;
#endif
    case WideBoxKernel::Avx2:
#if defined(__SSE2__)
      return __builtin_cpu_supports("avx2") != 0;
#else
      return false;
#endif
    case WideBoxKernel::Avx512Vl:
#if defined(__SSE2__)
      return __builtin_cpu_supports("avx2") != 0 && __builtin_cpu_supports("avx512f") != 0 &&
             __builtin_cpu_supports("avx512vl") != 0 && __builtin_cpu_supports("avx512dq") != 0 &&
             __builtin_cpu_supports("avx512bw") != 0;
#else
      return false;
#endif
  }
  return false;
}

WideBoxKernel wide_box_kernel() { return in_use; }

void force_wide_box_kernel(std::optional<WideBoxKernel> kernel) {
  if (kernel && !wide_box_kernel_supported(*kernel))
    throw std::invalid_argument("box kernel " + std::string(wide_box_kernel_name(*kernel)) +
                                " is not supported here");
  in_use = kernel.value_or(automatic);
}

std::string_view wide_box_kernel_name(WideBoxKernel kernel) {
  switch (kernel) {
    case WideBoxKernel::Scalar:
      return "scalar";
    case WideBoxKernel::Sse2:
      return "sse2";
    case WideBoxKernel::Avx2:
      return "avx2";
    case WideBoxKernel::Avx512Vl:
      return "avx512vl";
  }
  return "?";
}

std::optional<WideBoxKernel> parse_wide_box_kernel(std::string_view name) {
  for (const auto kernel : kWideBoxKernels)
    if (name == wide_box_kernel_name(kernel)) return kernel;
  return std::nullopt;
}

}  // namespace tessera
