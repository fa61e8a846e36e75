// The 8-bit value a PNG stores for an intensity.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

// Clamped to [0, 1] and rounded, exactly as OpenImageIO converts float to 8 bits, so that the
// PNG written here (png/write_png.h), OpenImageIO's and the page's tile deltas agree bit for bit.
inline std::uint8_t to_8bit(float v) {
  float s = v * 255.0f;
  s += s < 0 ? -0.5f : 0.5f;
  if (!(s >= 0.0f)) s = 0.0f;  // NaN too
  if (s > 255.0f) s = 255.0f;
  return static_cast<std::uint8_t>(s);
}

// to_8bit of n values into out, four at a time with SSE2 (in every x86-64 CPU): the
// same IEEE operations, the comparisons as masks (the coordinator converts every pixel pass
// it merges for the tile records).
inline void to_8bit_run(const float* values, std::size_t n, std::uint8_t* out) {
  std::size_t i = 0;
#if defined(__SSE2__)
  const __m128 scale = _mm_set1_ps(255.0f), half = _mm_set1_ps(0.5f),
               minus_half = _mm_set1_ps(-0.5f), zero = _mm_setzero_ps(), most = _mm_set1_ps(255.0f);
  for (; i + 4 <= n; i += 4) {
    __m128 s = _mm_mul_ps(_mm_loadu_ps(values + i), scale);
    const __m128 negative = _mm_cmplt_ps(s, zero);
    s = _mm_add_ps(s, _mm_or_ps(_mm_and_ps(negative, minus_half), _mm_andnot_ps(negative, half)));
    s = _mm_and_ps(_mm_cmpge_ps(s, zero), s);  // !(s >= 0): 0, NaN too
    s = _mm_min_ps(s, most);                   // s > 255: 255
    alignas(16) std::int32_t truncated[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(truncated), _mm_cvttps_epi32(s));
    for (int k = 0; k < 4; ++k) out[i + k] = static_cast<std::uint8_t>(truncated[k]);
  }
#endif
  for (; i < n; ++i) out[i] = to_8bit(values[i]);
}

}  // namespace tessera
