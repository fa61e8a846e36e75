#include "common/math/portable_math.h"
#include <sleef.h>

// SLEEF's deterministic (`cinz`: the same result whatever the build, no FMA) scalar functions,
// named down to their build: `purec` is plain C compiled for baseline x86-64 (SSE2 only; a
// `purecfma` build sits beside it), so nothing is chosen by the CPU at run time.
namespace tessera {

double sin(double x) { return Sleef_cinz_sind1_u10purec(x); }
double cos(double x) { return Sleef_cinz_cosd1_u10purec(x); }
double tan(double x) { return Sleef_cinz_tand1_u10purec(x); }
double acos(double x) { return Sleef_cinz_acosd1_u10purec(x); }
double atan2(double y, double x) { return Sleef_cinz_atan2d1_u10purec(y, x); }
double exp(double x) { return Sleef_cinz_expd1_u10purec(x); }
double log(double x) { return Sleef_cinz_logd1_u10purec(x); }
double pow(double x, double y) { return Sleef_cinz_powd1_u10purec(x, y); }
SinCos sincos(double x) {
  const Sleef_double_2 r = Sleef_cinz_sincosd1_u10purec(x);
  return {r.x, r.y};
}

}  // namespace tessera
