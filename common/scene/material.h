// Surface materials: the parameters of SDL §3.2.5 and §3.2.8, with the defaults of Hill's SDL.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "common/scene/rgb.h"

namespace tessera {

// A solid (3D) texture, SDL §3.2.8: type 0 is none; the parameters are stored as written.
struct SolidTexture {
  int type = 0;
  std::vector<double> params;
  friend bool operator==(const SolidTexture&, const SolidTexture&) = default;
};

// A flat (2D) texture: an image file or a procedural type. `decal` is method 0 (replace the
// ambient colour, no diffuse or specular), otherwise the texture modulates.
struct FlatTexture {
  enum class Kind { None, Image, Procedural };
  Kind kind = Kind::None;
  std::string image_file;  // resolved path inside the scene's folder or bundle
  int procedural_type = 0;
  std::vector<double> params;
  bool decal = false;
  double tile_s = 1, tile_t = 1;
  double offset_s = 0, offset_t = 0;  // flatTextureOffset
  // VRML's placement (TextureTransform, ISO/IEC 14772-1 §6.48) instead of the offset and
  // tiles: (s, t) becomes (m[0] s + m[1] t + m[2], m[3] s + m[4] t + m[5]), and the texture
  // repeats beyond the square instead of being clipped to it.
  std::optional<std::array<double, 6>> transform;
  bool clamp_s = false, clamp_t = false;  // VRML's repeatS, repeatT FALSE: an image's edges go on
  friend bool operator==(const FlatTexture&, const FlatTexture&) = default;
};

struct Material {
  Rgb emissive{0, 0, 0};
  Rgb ambient{0.1, 0.1, 0.1};
  Rgb diffuse{0.8, 0.8, 0.8};
  Rgb specular{0, 0, 0};
  double specular_exponent = 1;
  double surface_roughness = 0;
  bool light_back_faces = false;
  double reflectivity = 0;
  double gloss_strength = 0;
  double transparency = 0;
  double translucency_strength = 0;
  int priority = 1;  // air has priority 0, below every object
  double speed_of_light = 1;
  bool retain_ambient_color = false;
  bool retain_diffuse_color = false;
  bool retain_specular_reflection = false;
  bool disable_refraction = false;
  SolidTexture solid_texture;
  FlatTexture flat_texture;
  // A mesh with corner colours (Mesh::corner_colours) takes its diffuse colour from them,
  // modulating this material's; as a decal (a VRML shape without a Material) they show as they
  // are, unlit, like a decal flat texture.
  bool corner_colours_decal = false;
  friend bool operator==(const Material&, const Material&) = default;
};

}  // namespace tessera
