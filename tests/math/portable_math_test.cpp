// portable_math.h: the same bits on every x86-64 host, and the accuracy libm had.
//
// glibc picks its FMA or SSE2 variants of sin, cos, ... by the CPU; the tunable
// GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA makes it pick the SSE2 ones on an FMA host, as a
// host without FMA would. This binary runs a copy of itself under the tunable and compares the
// bits each function returns over a million arguments with its own.
#include "common/math/portable_math.h"
#include <gtest/gtest.h>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

namespace tessera {
namespace {

constexpr const char* kChildVariable = "TESSERA_PORTABLE_MATH_DIGESTS";
constexpr const char* kSse2Variants = "GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA";
constexpr int kArguments = 1 << 20;

// Arguments in the ranges scenes use: angles and exponents in [-10, 10], cosines in [-1, 1].
struct Arguments {
  double a, b, c;
};
Arguments arguments(std::uint64_t i) {
  auto unit = [](std::uint64_t z) {  // splitmix64's output as a double in [0, 1)
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  };
  const std::uint64_t z = (i + 1) * 3 * 0x9e3779b97f4a7c15ULL;
  return {(unit(z) - 0.5) * 20, (unit(z + 0x9e3779b97f4a7c15ULL) - 0.5) * 20,
          unit(z + 2 * 0x9e3779b97f4a7c15ULL) * 2 - 1};
}

using Function = double (*)(const Arguments&);
// Each routed function beside libm's, which the tunable must change (else the test proves
// nothing); volatile pointers keep the compiler from folding or inlining libm's.
std::map<std::string, Function> functions() {
  static double (*volatile libm_sin)(double) = std::sin, (*volatile libm_cos)(double) = std::cos,
                           (*volatile libm_tan)(double) = std::tan,
                           (*volatile libm_acos)(double) = std::acos,
                           (*volatile libm_exp)(double) = std::exp,
                           (*volatile libm_log)(double) = std::log;
  static double (*volatile libm_atan2)(double, double) = std::atan2,
                                               (*volatile libm_pow)(double, double) = std::pow;
  return {
      {"sin", [](const Arguments& x) { return tessera::sin(x.a); }},
      {"cos", [](const Arguments& x) { return tessera::cos(x.a); }},
      {"tan", [](const Arguments& x) { return tessera::tan(x.a); }},
      {"acos", [](const Arguments& x) { return tessera::acos(x.c); }},
      {"exp", [](const Arguments& x) { return tessera::exp(x.a); }},
      {"log", [](const Arguments& x) { return tessera::log(std::fabs(x.a)); }},
      {"atan2", [](const Arguments& x) { return tessera::atan2(x.a, x.b); }},
      {"pow", [](const Arguments& x) { return tessera::pow(std::fabs(x.a), x.b); }},
      {"sincos sin", [](const Arguments& x) { return tessera::sincos(x.a).sin; }},
      {"sincos cos", [](const Arguments& x) { return tessera::sincos(x.a).cos; }},
      {"libm sin", [](const Arguments& x) { return libm_sin(x.a); }},
      {"libm cos", [](const Arguments& x) { return libm_cos(x.a); }},
      {"libm tan", [](const Arguments& x) { return libm_tan(x.a); }},
      {"libm acos", [](const Arguments& x) { return libm_acos(x.c); }},
      {"libm exp", [](const Arguments& x) { return libm_exp(x.a); }},
      {"libm log", [](const Arguments& x) { return libm_log(std::fabs(x.a)); }},
      {"libm atan2", [](const Arguments& x) { return libm_atan2(x.a, x.b); }},
      {"libm pow", [](const Arguments& x) { return libm_pow(std::fabs(x.a), x.b); }},
  };
}

// FNV-1a over the result bits of every argument.
std::uint64_t digest(Function f) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (int i = 0; i < kArguments; ++i) {
    const auto bits = std::bit_cast<std::uint64_t>(f(arguments(static_cast<std::uint64_t>(i))));
    for (int byte = 0; byte < 8; ++byte) h = (h ^ ((bits >> (8 * byte)) & 0xff)) * 0x100000001b3ULL;
  }
  return h;
}

// The child: with kChildVariable set, print "name digest" lines and leave before any test runs.
[[maybe_unused]] const bool kChild = [] {
  if (std::getenv(kChildVariable) == nullptr) return false;
  for (const auto& [name, f] : functions())
    std::printf("%s=%llu\n", name.c_str(), static_cast<unsigned long long>(digest(f)));
  std::exit(0);
}();

std::map<std::string, std::uint64_t> child_digests(const std::string& environment) {
  const std::string command = environment + " " + kChildVariable + "=1 '" +
                              std::filesystem::read_symlink("/proc/self/exe").string() + "'";
  std::map<std::string, std::uint64_t> digests;
  std::FILE* child = popen(command.c_str(), "r");
  char line[256];
  while (child != nullptr && std::fgets(line, sizeof line, child) != nullptr) {
    const std::string text(line);
    const auto equals = text.find('=');
    if (equals != std::string::npos)
      digests[text.substr(0, equals)] = std::stoull(text.substr(equals + 1));
  }
  if (child != nullptr) pclose(child);
  return digests;
}

TEST(PortableMath, SameBitsWithGlibcsSse2Variants) {
  const auto sse2 = child_digests(kSse2Variants);
  ASSERT_EQ(sse2.size(), functions().size()) << "the child printed no digests";
  int libm_changed = 0;
  for (const auto& [name, f] : functions()) {
    const bool same = digest(f) == sse2.at(name);
    if (name.starts_with("libm "))
      libm_changed += same ? 0 : 1;
    else
      EXPECT_TRUE(same) << name << " gives other bits with glibc's SSE2 variants";
  }
  // The control: on an FMA host the tunable must change some of libm's results.
  if (__builtin_cpu_supports("fma") && __builtin_cpu_supports("avx2")) {
    EXPECT_GT(libm_changed, 0) << "the tunable did not select glibc's SSE2 variants";
  }
}

// SLEEF's u10 functions are within 1 ulp of the exact value and glibc's within about 0.5; over
// 4 million arguments they were never more than 1 ulp apart (docs/STABILITY.md).
TEST(PortableMath, WithinOneUlpOfLibm) {
  const auto functions_now = functions();
  for (const std::string name :
       {"sin", "cos", "tan", "acos", "exp", "log", "atan2", "pow", "sincos sin", "sincos cos"}) {
    const Function portable = functions_now.at(name);
    // sincos's halves against libm's sin and cos.
    const Function libm = functions_now.at("libm " + name.substr(name.find(' ') + 1));
    for (int i = 0; i < kArguments; i += 16) {
      const Arguments x = arguments(static_cast<std::uint64_t>(i));
      const double p = portable(x), l = libm(x);
      ASSERT_TRUE(p == l || std::nextafter(l, p) == p)
          << name << " " << x.a << " " << x.b << " " << x.c << ": " << p << " vs " << l;
    }
  }
}

}  // namespace
}  // namespace tessera
