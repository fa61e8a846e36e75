// Flat textures (SDL §3.2.8, §4.3.2): an image or a procedural pattern on the square
// [0, 1] x [0, 1] of texture space, placed by flatTextureOffset and repeated tile-s x tile-t
// times, applied as a decal or modulating.
#pragma once

#include <array>
#include <optional>
#include <variant>

#include "common/image/image.h"
#include "common/scene/material.h"
#include "common/scene/rgb.h"
#include "common/texture/texture_coordinates.h"

namespace tessera {

struct ImagePattern {  // imageTexture, decoded once per prepared scene
  const Image* image = nullptr;
};
struct FlatCheckerboard {  // proceduralTexture 1: white and black tiles
  double tiles_s = 1, tiles_t = 1;
};
struct RadialColours {  // proceduralTexture 2: from the centre of the square to its edge
  Rgb inside, outside;
};

using FlatPattern = std::variant<ImagePattern, FlatCheckerboard, RadialColours>;

struct PreparedFlatTexture {
  FlatPattern pattern;
  bool decal = false;
  double tile_s = 1, tile_t = 1;
  double offset_s = 0, offset_t = 0;
  std::optional<std::array<double, 6>> transform;  // FlatTexture::transform (VRML)
  bool clamp_s = false, clamp_t = false;           // FlatTexture::clamp_s, clamp_t (VRML)
};

// The prepared form of a loaded flat texture, with `image` its decoded file (for an image
// texture); nullopt for none.
std::optional<PreparedFlatTexture> make_flat_texture(const FlatTexture& texture,
                                                     const Image* image);

// §4.3.2's housekeeping: the offset added with a wrap-around, the result clipped to [0, 1],
// then scaled by the tile counts (the patterns repeat with period 1). With a VRML transform,
// that transform instead, unclipped.
TexCoord place_on_texture(const PreparedFlatTexture& texture, TexCoord st);

// The texture's colour at shape coordinates `st` (placed, then looked up).
Rgb flat_texture_colour(const PreparedFlatTexture& texture, TexCoord st);

}  // namespace tessera
