// VRML's Background gradient (ISO/IEC 14772-1 §6.5): the colour of a direction that meets
// nothing, by its angle from the Background's up axis.
#pragma once

#include <vector>

#include "common/math/vec3.h"
#include "common/scene/rgb.h"

namespace tessera {

// The sky's colours run from straight up (sky_colours[0]) through one more colour at each of
// sky_angles, linear in the angle between them, the last filling the rest of the sphere. The
// ground's run the same way from straight down and cover the sky within its last angle.
struct SkyGradient {
  Vec3 up{0, 1, 0};                   // unit: the Background's +y in world space
  std::vector<double> sky_angles;     // radians from straight up, increasing
  std::vector<Rgb> sky_colours;       // one more than sky_angles
  std::vector<double> ground_angles;  // radians from straight down, increasing
  std::vector<Rgb> ground_colours;    // one more than ground_angles, or none
  // The colour of the unit direction `d`.
  Rgb colour(const Vec3& d) const;
  friend bool operator==(const SkyGradient&, const SkyGradient&) = default;
};

}  // namespace tessera
