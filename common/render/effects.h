// The effect set: which effects a scene calls for (DESIGN.md §2, "effects on demand"). The
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
  DirectionalLight = 1u << 13,  // lights at infinity (VRML DirectionalLight, headlight)
};

class EffectSet {
 public:
  void add(Effect e) { bits_ |= static_cast<std::uint32_t>(e); }
  bool has(Effect e) const { return (bits_ & static_cast<std::uint32_t>(e)) != 0; }
  std::uint32_t bits() const { return bits_; }
  // Stable lower-case names ("hard_shadows", ...) in declaration order, for reports and JSON.
  std::vector<std::string> names() const;
  friend bool operator==(const EffectSet&, const EffectSet&) = default;

 private:
  std::uint32_t bits_ = 0;
};

}  // namespace tessera
