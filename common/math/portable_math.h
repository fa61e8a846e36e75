// The elementary functions whose results reach a pixel, with the same bits on every x86-64 host.
//
// glibc (2.36) picks sin, cos, tan, acos, atan2, exp, log and pow at run time (ifunc): an FMA
// variant on CPUs with FMA and AVX2, an SSE2 one on others, and the two differ by one ulp in
// about one call in 1,300 to 80,000 (docs/STABILITY.md, "libm's results depend on the host
// CPU"). These go instead to SLEEF's deterministic scalar functions (`Sleef_cinz_*d1_u10purec`:
// plain C compiled for baseline x86-64, SSE2 only, no dispatch, no calls; within 1.0 ulp), so a
// rotation, a cone, a texture or fog computes the same double whatever CPU runs it
// (tests/math/portable_math_test.cpp runs itself with glibc's SSE2 variants to check).
// std::hypot and std::sqrt stay: glibc does not dispatch hypot, and sqrt is IEEE's.
#pragma once

namespace tessera {

double sin(double x);
double cos(double x);
double tan(double x);
double acos(double x);
double atan2(double y, double x);
double exp(double x);
double log(double x);
double pow(double x, double y);

// sin x and cos x from one argument reduction: half the cost of the two calls.
struct SinCos {
  double sin, cos;
};
SinCos sincos(double x);

}  // namespace tessera
