// The texturing of a hit (SDL §4.3, figure 4.4): a shape's solid texture always modulates its
// ambient and diffuse colours; its flat texture then modulates them as well, or, as a decal,
// replaces the ambient term with the texture's own colour and drops diffuse and specular
// light, so that the texture shows as it is, lit or not.
#pragma once

#include <optional>

#include "common/geometry/instance.h"
#include "common/scene/rgb.h"
#include "common/texture/flat_texture.h"
#include "common/texture/solid_texture.h"

namespace tessera {

// The colours the lighting model uses at one hit.
struct SurfaceColours {
  Rgb ambient_term;  // eq. 4.5 before the opacity factor: ambient x globalAmbient
  Rgb diffuse;
  bool lit = true;  // false for a decal: no diffuse or specular term, no shadow feelers
};

// A shape's textures, prepared once per scene.
struct ObjectTexture {
  std::optional<SolidPattern> solid;
  std::optional<PreparedFlatTexture> flat;
  bool empty() const { return !solid && !flat; }
};

SurfaceColours textured_colours(const ObjectTexture& texture, const Instance& instance,
                                const WorldHit& hit, SurfaceColours colours);

}  // namespace tessera
