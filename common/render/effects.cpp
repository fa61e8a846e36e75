#include "common/render/effects.h"

#include <array>
#include <utility>

namespace tessera {

namespace {
constexpr std::array<std::pair<Effect, const char*>, 22> kEffectNames{{
    {Effect::HardShadows, "hard_shadows"},
    {Effect::Reflection, "reflection"},
    {Effect::Refraction, "refraction"},
    {Effect::LightAttenuation, "light_attenuation"},
    {Effect::Spotlights, "spotlights"},
    {Effect::AntiAliasing, "anti_aliasing"},
    {Effect::Meshes, "meshes"},
    {Effect::SurfaceRoughness, "surface_roughness"},
    {Effect::AtmosphericAttenuation, "atmospheric_attenuation"},
    {Effect::Fog, "fog"},
    {Effect::SolidTexture, "solid_texture"},
    {Effect::ImageTexture, "image_texture"},
    {Effect::ProceduralTexture, "procedural_texture"},
    {Effect::MotionBlur, "motion_blur"},
    {Effect::Csg, "csg"},
    {Effect::Gloss, "gloss"},
    {Effect::Translucency, "translucency"},
    {Effect::SoftShadows, "soft_shadows"},
    {Effect::ShowExtents, "show_extents"},
    {Effect::DirectionalLight, "directional_light"},
    {Effect::VertexColors, "vertex_colors"},
    {Effect::SkyGradient, "sky_gradient"},
}};
}  // namespace

std::vector<std::string> EffectSet::names() const {
  std::vector<std::string> out;
  for (const auto& [effect, name] : kEffectNames)
    if (has(effect)) out.emplace_back(name);
  return out;
}

}  // namespace tessera
