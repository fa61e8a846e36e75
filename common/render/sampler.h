// Counter-based random numbers (docs/ARCHITECTURE.md, "Determinism"): every number is a hash of
// (seed, pixel x, pixel y, sample index, dimension), so a pixel's value does not depend on
// which thread, tile, worker or host computes it, nor on the order of pixels.
#pragma once

#include <cstdint>

namespace tessera {

// SplitMix64's finalizer: a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A uniform double in [0, 1) for one (seed, x, y, sample, dimension).
constexpr double sample_uniform(std::uint64_t seed, std::uint32_t x, std::uint32_t y,
                                std::uint32_t sample, std::uint32_t dimension) {
  std::uint64_t h = mix64(seed + 0x9e3779b97f4a7c15ULL);
  h = mix64(h ^ ((static_cast<std::uint64_t>(x) << 32) | y));
  h = mix64(h ^ ((static_cast<std::uint64_t>(sample) << 32) | dimension));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// The random numbers of one camera sample, drawn in a fixed order: dimension k is the k-th
// number the tracer asks for while following that sample, which is deterministic.
class SampleStream {
 public:
  SampleStream(std::uint64_t seed, std::uint32_t x, std::uint32_t y, std::uint32_t sample)
      : seed_(seed), x_(x), y_(y), sample_(sample) {}
  double next() { return sample_uniform(seed_, x_, y_, sample_, dimension_++); }

 private:
  std::uint64_t seed_;
  std::uint32_t x_, y_, sample_;
  std::uint32_t dimension_ = 0;
};

}  // namespace tessera
