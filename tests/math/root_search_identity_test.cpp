// The root search (visit_real_roots, common/math/polynomial.h) answers bit for bit as it did when
// its results were recorded: every root's bits, every touching flag, the visit order, where a
// visitor or bracket test ends the search, and every bracket it offers. The quartic proofs
// (math/quartic_*_proof.h) and the images depend on its exact behaviour, so a change made for
// speed must leave all of it alone. The search's events over a fixed set of polynomials (random,
// touching, grazing, far from the origin, torus rays, and the logged quartics and cubics of
// bench/polish_brackets_sample.txt) are folded into one 64-bit digest, recorded from main at
// f1df9b3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "common/math/polynomial.h"

namespace tessera {
namespace {

// FNV-1a over 64-bit words.
struct Digest {
  std::uint64_t value = 14695981039346656037ull;
  void add(std::uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      value ^= (word >> (8 * i)) & 0xff;
      value *= 1099511628211ull;
    }
  }
  void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    add(bits);
  }
};

// Uniform doubles from the generator's bits alone (the standard distributions' results are the
// library's choice, and the digest must not depend on it; nor on libm's pow, sin or cos, so the
// polynomials below are built from exact scalings and rational points of the circle).
class Numbers {
 public:
  explicit Numbers(std::uint64_t seed) : rng_(seed) {}
  double unit() { return static_cast<double>(rng_() >> 11) * 0x1p-53; }  // [0, 1)
  double between(double lo, double hi) { return lo + (hi - lo) * unit(); }
  int below(int n) { return static_cast<int>(rng_() % static_cast<std::uint64_t>(n)); }

 private:
  std::mt19937_64 rng_;
};

Polynomial linear(double a, double b) {  // a + b x
  Polynomial p;
  p.degree = 1;
  p.c[0] = a;
  p.c[1] = b;
  return p;
}

// Every event of the searches of p on (lo, hi): all roots; the search ended by the visitor at
// each root in turn; the brackets offered to a test that never ends it, and the search ended by
// the test at each bracket in turn.
void record_searches(const Polynomial& p, double lo, double hi, Digest& digest) {
  std::vector<PolynomialRoot> all;
  const auto keep = [&](const PolynomialRoot& root) {
    all.push_back(root);
    return true;
  };
  digest.add(std::uint64_t{visit_real_roots(p, lo, hi, keep)});
  digest.add(std::uint64_t{all.size()});
  for (const PolynomialRoot& root : all) {
    digest.add(root.x);
    digest.add(std::uint64_t{root.touching});
  }
  for (std::size_t wanted = 1; wanted <= all.size(); ++wanted) {
    std::size_t seen = 0;
    const auto until = [&](const PolynomialRoot& root) {
      digest.add(root.x);
      return ++seen < wanted;
    };
    digest.add(std::uint64_t{visit_real_roots(p, lo, hi, until)});
  }
  std::size_t brackets = 0;
  const auto count = [&](const PolynomialRoot& root) {
    digest.add(root.x);
    digest.add(std::uint64_t{root.touching});
    return true;
  };
  const auto offered = [&](double a, double b) {
    digest.add(a);
    digest.add(b);
    ++brackets;
    return false;
  };
  digest.add(std::uint64_t{visit_real_roots(p, lo, hi, count, offered)});
  for (std::size_t ending = 1; ending <= brackets; ++ending) {
    std::size_t asked = 0;
    const auto ends_at = [&](double, double) { return ++asked == ending; };
    digest.add(std::uint64_t{visit_real_roots(p, lo, hi, count, ends_at)});
  }
}

// A product of factors: real roots (some repeated, some a few ulps apart) and complex pairs
// (some with tiny imaginary parts: grazing), scaled, about a centre that may lie far out.
Polynomial random_product(Numbers& numbers, int degree) {
  const double centre = numbers.below(4) == 0 ? numbers.between(-1e6, 1e6) : 0;
  const double spread = std::ldexp(numbers.between(1, 2), numbers.below(17) - 10);
  Polynomial p;
  p.c[0] = std::ldexp(numbers.between(-2, 2), numbers.below(27) - 13);
  double previous = centre;
  int left = degree;
  while (left > 0) {
    const int kind = numbers.below(5);
    const double r = centre + spread * numbers.between(-1, 1);
    if (kind == 0 && left >= 2) {  // a complex pair r +- i w, w from tiny to wide
      const double w = spread * std::ldexp(numbers.between(1, 2), -numbers.below(41));
      Polynomial pair;
      pair.degree = 2;
      pair.c[0] = r * r + w * w;
      pair.c[1] = -2 * r;
      pair.c[2] = 1;
      p = p * pair;
      left -= 2;
      continue;
    }
    double root = r;
    if (kind == 1) root = previous;  // repeated
    if (kind == 2) root = previous + std::ldexp(std::fabs(previous) + 1, -52 + numbers.below(30));
    p = p * linear(-root, 1);
    previous = root;
    --left;
  }
  return p;
}

// The quartic of the ray o + t d against the torus (|x|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2),
// the ray aimed at a point near the tube's surface (grazing, tangent and crossing rays).
Polynomial torus_ray(Numbers& numbers, double& hi) {
  const double R = numbers.between(0.2, 2), r = R * numbers.between(0.05, 1.5);
  const double near = r * (1 + std::ldexp(numbers.between(-1, 1), -numbers.below(44) - 3));
  // Points of the unit circle, (1 - t^2, 2 t) / (1 + t^2), and the reflection of the half
  // circle they cover.
  const auto circle = [&](double& cosine, double& sine) {
    const double t = numbers.between(-1, 1), scale = 1 + t * t;
    cosine = (1 - t * t) / scale * (numbers.below(2) ? 1 : -1);
    sine = 2 * t / scale;
  };
  double cos_angle, sin_angle, cos_around, sin_around;
  circle(cos_angle, sin_angle);
  circle(cos_around, sin_around);
  const double target[3] = {(R + near * cos_around) * cos_angle,
                            (R + near * cos_around) * sin_angle, near * sin_around};
  double o[3], d[3], norm = 0;
  for (int i = 0; i < 3; ++i) o[i] = numbers.between(-6, 6);
  for (int i = 0; i < 3; ++i) {
    d[i] = target[i] - o[i];
    norm += d[i] * d[i];
  }
  norm = std::sqrt(norm);
  for (double& v : d) v /= norm;
  Polynomial squared_distance, planar;
  for (int i = 0; i < 3; ++i) {
    const Polynomial coordinate = linear(o[i], d[i]);
    squared_distance = squared_distance + coordinate * coordinate;
    if (i < 2) planar = planar + coordinate * coordinate;
  }
  const Polynomial shifted = squared_distance + linear(R * R - r * r, 0);
  hi = 2 * norm + 2 * (R + r);
  return shifted * shifted + (-4 * R * R) * planar;
}

std::vector<Polynomial> logged_polynomials() {
  std::vector<Polynomial> polynomials;
  const std::string path = std::string(TESSERA_SOURCE_DIR) + "/bench/polish_brackets_sample.txt";
  FILE* file = std::fopen(path.c_str(), "r");
  if (!file) return polynomials;
  int tag;
  while (std::fscanf(file, "%d", &tag) == 1) {
    Polynomial p;
    p.degree = tag % 10;
    for (int i = 0; i <= p.degree; ++i)
      if (std::fscanf(file, "%la", &p.c[i]) != 1) break;
    double a, b;
    if (std::fscanf(file, "%la %la", &a, &b) != 2) break;
    polynomials.push_back(p);
  }
  std::fclose(file);
  return polynomials;
}

// The digest of main's search (f1df9b3) over the polynomials below. It changes when any root,
// flag, order, or bracket does: a change meant to leave the search's results alone must not
// change it.
constexpr std::uint64_t kRecordedDigest = 0x48aacbe1eddb59f9;

TEST(RootSearchIdentity, ResultsBitForBitAsRecorded) {
  Digest digest;
  Numbers numbers(20261128);
  int searched = 0;
  for (int i = 0; i < 12000; ++i) {
    const Polynomial p = random_product(numbers, 3 + i % 2);
    const double width = std::ldexp(numbers.between(1, 2), numbers.below(24) - 4);
    const double lo = numbers.below(3) == 0 ? 0 : numbers.between(-width, 0);
    record_searches(p, lo, lo + width * numbers.between(0.01, 2), digest);
    ++searched;
  }
  for (int i = 0; i < 12000; ++i) {
    double hi;
    const Polynomial p = torus_ray(numbers, hi);
    record_searches(p, numbers.below(2) ? 0 : -hi, hi, digest);
    ++searched;
  }
  const std::vector<Polynomial> logged = logged_polynomials();
  ASSERT_EQ(logged.size(), 200u);
  for (const Polynomial& p : logged) {
    record_searches(p, -1, 4, digest);
    record_searches(p, 0, 1e3, digest);
    searched += 2;
  }
  EXPECT_EQ(searched, 24400);
  EXPECT_EQ(digest.value, kRecordedDigest) << std::hex << digest.value;
}

}  // namespace
}  // namespace tessera
