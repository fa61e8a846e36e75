// Light sources of SDL §3.2.2 (positional point lights and spotlights) and VRML's
// DirectionalLight (a light at infinity), in world space.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "common/math/vec3.h"
#include "common/scene/rgb.h"

namespace tessera {

// lightAttenuation: f = min(1, 1 / (kc + kl d + kq d^2)), eq. 4.12.
struct LightAttenuation {
  double constant = 1, linear = 0, quadratic = 0;
  bool is_identity() const { return constant == 1 && linear == 0 && quadratic == 0; }
  friend bool operator==(const LightAttenuation&, const LightAttenuation&) = default;
};

struct Spot {
  Vec3 direction{0, 0, -1};     // where the cone points (unit length after loading)
  double cutoff_degrees = 180;  // half-angle of the cone
  double exponent = 0;          // cos^exponent fall-off inside the cone
  friend bool operator==(const Spot&, const Spot&) = default;
};

// Objects [begin, end) of Scene::objects.
struct ObjectRange {
  std::uint32_t begin = 0, end = 0;
  bool contains(std::uint32_t object) const { return object >= begin && object < end; }
  friend bool operator==(const ObjectRange&, const ObjectRange&) = default;
};

struct Light {
  Vec3 position;
  Rgb color{1, 1, 1};  // both the diffuse and the specular colour of the light
  bool is_spot = false;
  Spot spot;  // meaningful when is_spot
  // A light at infinity (VRML DirectionalLight, the headlight): its rays travel along
  // `direction` (unit length) everywhere, with no attenuation; `position` is unused.
  bool is_directional = false;
  Vec3 direction{0, 0, -1};
  // What a directional light lights: VRML's DirectionalLight lights only the objects under
  // its parent grouping node (§6.16), which the loader lays down as ranges of objects. Empty:
  // every object. Objects outside the scope still cast its shadows.
  std::vector<ObjectRange> scope;
  // A positional light's own attenuation and reach (VRML's PointLight and SpotLight): the
  // attenuation replaces the scene's lightAttenuation for this light, and beyond `radius` the
  // light lights nothing. SDL lights have neither.
  std::optional<LightAttenuation> attenuation;
  double radius = std::numeric_limits<double>::infinity();
  // False for VRML's headlight: a directional light along the view whose shadows a viewer
  // would see as black fringes beside foreground objects, where a browser shows none.
  bool casts_shadows = true;
  bool lights(std::uint32_t object) const {
    if (scope.empty()) return true;
    for (const ObjectRange& range : scope)
      if (range.contains(object)) return true;
    return false;
  }
  friend bool operator==(const Light&, const Light&) = default;
};

}  // namespace tessera
