// Quadratic factors with roots close together, touching or just apart, for the tests of the
// quartic proofs against the root search (a grazing ray's quartic has such factors).
#pragma once

#include <cmath>
#include <random>

#include "common/math/polynomial.h"

namespace tessera::testing {

// x^2 - 2 a x + a^2 + e: roots a +- sqrt(-e), a double root at e = 0, none above.
inline Polynomial quadratic_about(double a, double e) {
  Polynomial q;
  q.degree = 2;
  q.c[0] = a * a + e;
  q.c[1] = -2 * a;
  q.c[2] = 1;
  return q;
}

// +-10^-16 to +-1: a quadratic factor's offset from a double root.
inline double random_gap(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double sign = unit(rng) < 0.5 ? -1 : 1;
  return sign * std::pow(10.0, -16 * unit(rng));
}

// The product of two quadratic factors about the points place() gives, each with a random gap,
// scaled by 10^-3 to 10^3: roots close together, touching, just apart or none.
template <class Place>
Polynomial random_pair_of_quadratics(std::mt19937_64& rng, const Place& place) {
  std::uniform_real_distribution<double> unit(0, 1);
  const double scale = std::pow(10.0, 6 * unit(rng) - 3);
  return scale *
         (quadratic_about(place(), random_gap(rng)) * quadratic_about(place(), random_gap(rng)));
}

}  // namespace tessera::testing
