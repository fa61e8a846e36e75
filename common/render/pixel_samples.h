// Where in a pixel the camera samples go (§4.4): 1 sample at the centre; 5 at the centre and
// the four corners; 9 on the 3x3 grid of corners, edge midpoints and centre. Stochastic
// sampling jitters each position by up to ±jitter/2 pixels in x and y (eq. 4.52, block 1).
#pragma once

#include <array>
#include <span>

namespace tessera {

struct SampleOffset {
  double dx = 0.5, dy = 0.5;
};

inline std::span<const SampleOffset> regular_sample_offsets(int samples) {
  static constexpr std::array<SampleOffset, 1> one{{{0.5, 0.5}}};
  static constexpr std::array<SampleOffset, 5> five{{{0.5, 0.5}, {0, 0}, {1, 0}, {0, 1}, {1, 1}}};
  static constexpr std::array<SampleOffset, 9> nine{
      {{0.5, 0.5}, {0, 0}, {0.5, 0}, {1, 0}, {0, 0.5}, {1, 0.5}, {0, 1}, {0.5, 1}, {1, 1}}};
  if (samples == 9) return nine;
  if (samples == 5) return five;
  return one;
}

}  // namespace tessera
