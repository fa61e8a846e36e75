#include "common/render/sample_lattice.h"

namespace tessera {

long long shared_unit_rays(const UnitPixels& unit, int aa) {
  const long long pixels = pixel_count(unit);
  const long long w = unit.rect.width(), h = unit.rect.height();
  if (unit.step != 1 || !worth_a_lattice(pixels, w * h, aa)) return aa * pixels;
  if (aa == 9) return (2 * w + 1) * (2 * h + 1) - (w * h - pixels);  // all but skipped centres
  return (w + 1) * (h + 1) + pixels;  // 5 points: every corner, the traced pixels' centres
}

double traced_share(const Plan& first_two, int passes, int aa) {
  double rays[2] = {0, 0}, samples[2] = {0, 0};  // of pass 0, of a later pass
  for (const WorkUnit& unit : first_two.units) {
    const int later = first_two.stages[static_cast<std::size_t>(unit.stage)].pass > 0 ? 1 : 0;
    rays[later] += static_cast<double>(shared_unit_rays(unit.pixels, aa));
    samples[later] += static_cast<double>(aa) * static_cast<double>(unit.cost);
  }
  const double later_passes = passes > 1 ? passes - 1 : 0;
  const double all = samples[0] + later_passes * samples[1];
  return all > 0 ? (rays[0] + later_passes * rays[1]) / all : 1;
}

}  // namespace tessera
