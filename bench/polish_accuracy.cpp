// How accurate polished_root is (docs/PERFORMANCE.md, "Tori and quartics", branch `polish`):
// for logged (polynomial, a, b) inputs, and for random narrower brackets around the same roots,
// the root polished in double against the exact root of the same double coefficients found by
// bisection in __float128; prints the fraction correctly rounded, the mean and largest error in
// ulps, and the time a root. --errors FILE writes each root's error, --compare FILE counts the
// roots that got worse or better against such a file from another build.
//
// Input: one bracket a line, "tag c0 ... cN a b", tag % 10 the degree N (3 or 4), numbers in C's
// %a form, as a temporary fprintf in polished_root / bracketed_root writes them.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "common/math/polynomial.h"

namespace {

using tessera::Polynomial;
__extension__ using Quad = __float128;

struct Bracket {
  Polynomial p;
  double a, b;
};

Quad evaluate_exactly(const Polynomial& p, Quad x) {
  Quad v = p.c[p.degree];
  for (int i = p.degree - 1; i >= 0; --i) v = v * x + p.c[i];
  return v;
}

// The root in (a, b) of p's double coefficients by bisection in quadruple precision (113 bits:
// far below a double's ulp for every root whose condition number is below about 2^50).
Quad exact_root(const Bracket& bracket) {
  Quad a = bracket.a, b = bracket.b;
  const bool positive_at_a = evaluate_exactly(bracket.p, a) > 0;
  for (int i = 0; i < 240; ++i) {
    const Quad m = (a + b) / 2;
    if (m == a || m == b) break;
    const Quad v = evaluate_exactly(bracket.p, m);
    if (v == 0) return m;
    (v > 0) == positive_at_a ? a = m : b = m;
  }
  return (a + b) / 2;
}

std::vector<Bracket> read_brackets(const char* path) {
  std::vector<Bracket> brackets;
  FILE* file = std::fopen(path, "r");
  if (!file) {
    std::perror(path);
    std::exit(2);
  }
  int tag;
  while (std::fscanf(file, "%d", &tag) == 1) {
    Bracket bracket;
    bracket.p.degree = tag % 10;
    bool ok = bracket.p.degree == 3 || bracket.p.degree == 4;
    for (int i = 0; i <= bracket.p.degree; ++i)
      ok &= std::fscanf(file, "%la", &bracket.p.c[i]) == 1;
    ok &= std::fscanf(file, "%la %la", &bracket.a, &bracket.b) == 2;
    if (!ok) {
      std::fprintf(stderr, "%s: malformed line %zu\n", path, brackets.size() + 1);
      std::exit(2);
    }
    brackets.push_back(bracket);
  }
  std::fclose(file);
  return brackets;
}

// A bracket inside [a, b] around the root, its ends 2^-40..1 of the way from the root to a and
// to b, kept only when the values at its ends still have opposite signs.
bool random_narrower_bracket(const Bracket& bracket, Quad root, std::mt19937_64& rng,
                             Bracket& narrower) {
  std::uniform_real_distribution<double> exponent(-40, 0);
  const double r = static_cast<double>(root);
  narrower = bracket;
  narrower.a = r - (r - bracket.a) * std::exp2(exponent(rng));
  narrower.b = r + (bracket.b - r) * std::exp2(exponent(rng));
  narrower.a = std::clamp(narrower.a, bracket.a, bracket.b);
  narrower.b = std::clamp(narrower.b, bracket.a, bracket.b);
  const double fa = tessera::evaluate(narrower.p, narrower.a),
               fb = tessera::evaluate(narrower.p, narrower.b);
  return narrower.a < narrower.b && fa != 0 && fb != 0 && (fa > 0) != (fb > 0);
}

double ulps_off(double x, Quad root) {
  const double r = std::fabs(static_cast<double>(root));
  const double ulp = std::nextafter(r, INFINITY) - r;
  const Quad off = x > root ? Quad(x) - root : root - Quad(x);
  return static_cast<double>(off / ulp);
}

void report(const char* name, const std::vector<Bracket>& brackets, const std::vector<Quad>& roots,
            std::vector<double>& errors) {
  int rounded = 0;
  double sum = 0, largest = 0;
  volatile double sink = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const Bracket& bracket : brackets)
    sink = sink + tessera::polished_root(bracket.p, bracket.a, bracket.b);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (std::size_t i = 0; i < brackets.size(); ++i) {
    const double x = tessera::polished_root(brackets[i].p, brackets[i].a, brackets[i].b);
    const double error = ulps_off(x, roots[i]);
    errors.push_back(error);
    rounded += x == static_cast<double>(roots[i]);
    sum += error;
    largest = std::max(largest, error);
  }
  const double n = static_cast<double>(brackets.size());
  std::printf(
      "%-28s %7zu roots  correctly rounded %.4f  ulps mean %.4f max %8.3f  %.1f ns a root\n", name,
      brackets.size(), rounded / n, sum / n, largest, seconds / n * 1e9);
}

}  // namespace

int main(int argc, char** argv) {
  const char* errors_path = nullptr;
  const char* compare_path = nullptr;
  std::vector<const char*> inputs;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--errors") && i + 1 < argc)
      errors_path = argv[++i];
    else if (!std::strcmp(argv[i], "--compare") && i + 1 < argc)
      compare_path = argv[++i];
    else
      inputs.push_back(argv[i]);
  }
  if (inputs.empty()) {
    std::fprintf(stderr,
                 "usage: tessera-polish-accuracy [--errors FILE] [--compare FILE] BRACKETS...\n");
    return 2;
  }
  std::mt19937_64 rng(18);
  std::vector<double> errors;
  for (const char* input : inputs) {
    const std::vector<Bracket> logged = read_brackets(input);
    for (int degree = 3; degree <= 4; ++degree) {
      std::vector<Bracket> brackets, narrower;
      std::vector<Quad> roots, narrower_roots;
      for (const Bracket& bracket : logged) {
        if (bracket.p.degree != degree) continue;
        brackets.push_back(bracket);
        roots.push_back(exact_root(bracket));
        Bracket inside;
        if (random_narrower_bracket(bracket, roots.back(), rng, inside)) {
          narrower.push_back(inside);
          narrower_roots.push_back(roots.back());
        }
      }
      if (brackets.empty()) continue;
      const std::string name =
          std::string(std::strrchr(input, '/') ? std::strrchr(input, '/') + 1 : input) + " deg " +
          std::to_string(degree);
      report(name.c_str(), brackets, roots, errors);
      report((name + " narrower").c_str(), narrower, narrower_roots, errors);
    }
  }
  if (errors_path) {
    FILE* file = std::fopen(errors_path, "w");
    for (double error : errors) std::fprintf(file, "%.17g\n", error);
    std::fclose(file);
  }
  if (compare_path) {
    FILE* file = std::fopen(compare_path, "r");
    int worse = 0, better = 0;
    double before;
    for (double error : errors) {
      if (std::fscanf(file, "%lf", &before) != 1) break;
      worse += error > before;
      better += error < before;
    }
    std::fclose(file);
    std::printf("against %s: %d roots worse, %d better\n", compare_path, worse, better);
  }
}
