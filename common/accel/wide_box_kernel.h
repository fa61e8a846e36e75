// Which kernel the mesh BVH traversal tests a wide node's boxes with (float_child_boxes.h):
// chosen once, at the first traversal, from what the CPU supports, so that one binary runs
// everywhere. The kernels give bit-identical results; forcing one (the environment variable
// TESSERA_BOX_KERNEL=sse2, scalar or avx2, or force_wide_box_kernel) is for tests that check
// exactly that, and for measuring one against another.
#pragma once

#include <optional>
#include <string_view>
#include <type_traits>

namespace tessera {

enum class WideBoxKernel { Scalar, Sse2, Avx2 };

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
// "scalar", "sse2", "avx2"; parse_wide_box_kernel is its inverse (std::nullopt otherwise).
std::string_view wide_box_kernel_name(WideBoxKernel kernel);
std::optional<WideBoxKernel> parse_wide_box_kernel(std::string_view name);

}  // namespace tessera
