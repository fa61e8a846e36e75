// Which kernel the mesh BVH traversal tests a wide node's boxes with (float_child_boxes.h):
// chosen once, at the first traversal, from what the CPU supports, so that one binary runs
// everywhere. The kernels give bit-identical results; forcing one (the environment variable
// TESSERA_BOX_KERNEL=scalar, sse2, avx2 or avx512vl, or force_wide_box_kernel) is for tests that
// check exactly that, and for measuring one against another.
#pragma once

#include <optional>
#include <string_view>
#include <type_traits>

namespace tessera {

// Avx512Vl runs Avx2's code (the same intrinsics, the same IEEE operations) compiled for a CPU
// with AVX-512F, VL, DQ and BW: the compiler then has 32 vector registers (ymm16-31, through EVEX
// encodings) and need not spill the node step's values around the leaf's quad test, which takes
// all of AVX2's 16; no 512-bit vector and no FMA (docs/PERFORMANCE.md "The AVX2 traversal as a
// kernel of its own with AVX-512VL's 32 registers").
enum class WideBoxKernel { Scalar, Sse2, Avx2, Avx512Vl };

// Every kernel, narrowest first (whether this build and CPU can run it: wide_box_kernel_supported).
inline constexpr WideBoxKernel kWideBoxKernels[] = {WideBoxKernel::Scalar, WideBoxKernel::Sse2,
                                                    WideBoxKernel::Avx2, WideBoxKernel::Avx512Vl};

// Whether `kernel` runs the AVX2 code: the box test, the leaf's quad test, the packet walks.
// The kernels are declared narrowest first, and every one from Avx2 on runs it: one compare, as
// long as the test for Avx2 alone was (the packet walks' dispatch kept its size, and the code
// after it its alignment).
constexpr bool has_avx2(WideBoxKernel kernel) { return kernel >= WideBoxKernel::Avx2; }
static_assert(!has_avx2(WideBoxKernel::Sse2) && has_avx2(WideBoxKernel::Avx512Vl));

// The target of the functions compiled for WideBoxKernel::Avx512Vl (a macro: gnu::target takes a
// string literal). Without "fma", and with -ffp-contract=off, a*b+c stays two roundings.
#define TESSERA_AVX512VL_TARGET "avx2,avx512f,avx512vl,avx512dq,avx512bw"

// The kernel a traversal was compiled for, as a type: its leaf visitor may use that instruction
// set too (the mesh's four-triangle test, intersect_triangle_pair.h, under AVX2).
template <WideBoxKernel kKernel>
using WideBoxKernelTag = std::integral_constant<WideBoxKernel, kKernel>;

// The kernel in use: the forced one if any, else TESSERA_BOX_KERNEL's if the CPU supports it,
// else the widest the CPU supports.
WideBoxKernel wide_box_kernel();
// Whether this build and CPU can run `kernel`.
bool wide_box_kernel_supported(WideBoxKernel kernel);
// Uses `kernel` from now on (it must be supported); std::nullopt returns to the automatic
// choice. Not for use while other threads trace.
void force_wide_box_kernel(std::optional<WideBoxKernel> kernel);
// "scalar", "sse2", "avx2", "avx512vl"; parse_wide_box_kernel is its inverse (std::nullopt
// otherwise).
std::string_view wide_box_kernel_name(WideBoxKernel kernel);
std::optional<WideBoxKernel> parse_wide_box_kernel(std::string_view name);

}  // namespace tessera
