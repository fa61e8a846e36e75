// The solid textures of SDL §3.2.8 (types 1-9): colours defined throughout object space, looked
// up at the hit's object-space point (eq. 4.27), so a texture moves rigidly with its shape.
// The manual names the types and their parameters but gives no formulas; the ones chosen here
// are written in docs/SDL.md §4.5. Every scale is a length in object units: a coordinate is
// divided by it, and a zero scale makes that coordinate 0.
#pragma once

#include <optional>
#include <variant>

#include "common/math/vec3.h"
#include "common/scene/material.h"
#include "common/scene/rgb.h"

namespace tessera {

enum class DistanceMeasure { Euclid, Manhattan, SinSin, SinCos };

struct Checkerboard3D {  // type 1: white and black cells
  Vec3 scale;
};
struct ColourBars {  // type 2: red, green and blue bars along x, y and z, stacked
  Vec3 scale;
};
struct RgbCubes {  // type 3: every cell runs through the RGB colour cube
  Vec3 scale;
};
struct Contours1 {  // type 4: contour lines of one coordinate
  int axis = 0;
  double scale = 1;
};
struct Contours2 {  // type 5: contour lines of a distance in a coordinate plane
  int first_axis = 0, second_axis = 1;
  DistanceMeasure measure = DistanceMeasure::Euclid;
  double first_scale = 1, second_scale = 1;
};
struct Contours3 {  // type 6: contour lines of a distance in space
  DistanceMeasure measure = DistanceMeasure::Euclid;
  Vec3 scale;
};
struct WoodGrain {  // type 7: rings around the z axis, wobbled and twisted
  double ring_thickness = 1, wobble_strength = 0, wobbles = 0, twist = 0;
  Rgb first, second;
  bool smooth = false;
};
struct Marble {  // type 8: sine veins along one axis, disturbed by turbulence
  int axis = 0;
  double turbulence = 0;
  Rgb weights;
};
struct CowSpots {  // type 9: black where the noise exceeds the threshold, white elsewhere
  double threshold = 0.5;
};

using SolidPattern = std::variant<Checkerboard3D, ColourBars, RgbCubes, Contours1, Contours2,
                                  Contours3, WoodGrain, Marble, CowSpots>;

// The pattern of a loaded solid texture (parameters as the loader checked them); nullopt for
// type 0, none.
std::optional<SolidPattern> make_solid_pattern(const SolidTexture& texture);

// The texture's colour at object-space point `p`, each component in [0, 1] (wood grain and
// marble: between their colours or weights).
Rgb solid_texture_colour(const SolidPattern& pattern, const Vec3& p);

}  // namespace tessera
