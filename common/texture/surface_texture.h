// The texturing of a hit (SDL §4.3, figure 4.4): a mesh's corner colours (VRML's Color) first
// modulate the ambient and diffuse colours (the material's are white, so they replace them,
// as ISO/IEC 14772-1 §4.14.4 says) or, as a decal, replace the ambient term and drop the
// lights; a shape's solid texture then modulates its ambient and diffuse colours; its flat
// texture modulates them as well, or, as a decal, replaces the ambient term with the
// texture's own colour and drops diffuse and specular light, so that the texture shows as it
// is, lit or not.
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
  const Mesh* coloured_mesh = nullptr;  // a mesh with corner colours
  bool colour_decal = false;            // its colours show unlit (Material::corner_colours_decal)
  bool empty() const { return !solid && !flat && coloured_mesh == nullptr; }
};

SurfaceColours textured_colours(const ObjectTexture& texture, const Instance& instance,
                                const WorldHit& hit, SurfaceColours colours);

}  // namespace tessera
