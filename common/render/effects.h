// The effect set: which effects a scene calls for (docs/ARCHITECTURE.md, "Effects on demand"). The
// render plan is built from it, and every render reports it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

enum class Effect : std::uint32_t {
  HardShadows = 1u << 0,
  Reflection = 1u << 1,
  Refraction = 1u << 2,
  LightAttenuation = 1u << 3,
  Spotlights = 1u << 4,
  AntiAliasing = 1u << 5,
  Meshes = 1u << 6,
  SurfaceRoughness = 1u << 7,
  AtmosphericAttenuation = 1u << 8,
  Fog = 1u << 9,
  SolidTexture = 1u << 10,
  ImageTexture = 1u << 11,
  ProceduralTexture = 1u << 12,
  MotionBlur = 1u << 13,
  Csg = 1u << 14,               // boolean objects (union, intersection, difference)
  Gloss = 1u << 15,             // blurred reflection: a cone of reflected rays (§4.1.4)
  Translucency = 1u << 16,      // blurred refraction: a cone of refracted rays (§4.1.4)
  SoftShadows = 1u << 17,       // a cone of shadow feelers per light (§4.2.1)
  ShowExtents = 1u << 18,       // objects' bounding boxes drawn as white bars (§3.2.7)
  DirectionalLight = 1u << 19,  // lights at infinity (VRML DirectionalLight, headlight)
  VertexColors = 1u << 20,      // meshes coloured per vertex or per face (VRML Color)
  SkyGradient = 1u << 21,       // a background coloured by direction (VRML Background angles)
};

class EffectSet {
 public:
  void add(Effect e) { bits_ |= static_cast<std::uint32_t>(e); }
  void remove(Effect e) { bits_ &= ~static_cast<std::uint32_t>(e); }
  bool has(Effect e) const { return (bits_ & static_cast<std::uint32_t>(e)) != 0; }
  std::uint32_t bits() const { return bits_; }
  // Stable lower-case names ("hard_shadows", ...) in declaration order, for reports and JSON.
  std::vector<std::string> names() const;
  friend bool operator==(const EffectSet&, const EffectSet&) = default;

 private:
  std::uint32_t bits_ = 0;
};

}  // namespace tessera
