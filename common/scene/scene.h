// The parsed scene: plain data, as the loaders produce it and the wire protocol ships it.
// The renderer builds its own prepared form from it (render/prepared_scene.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/math/affine.h"
#include "common/scene/camera.h"
#include "common/scene/light.h"
#include "common/scene/material.h"
#include "common/scene/mesh.h"
#include "common/scene/motion.h"
#include "common/scene/shape.h"
#include "common/scene/sky_gradient.h"
#include "common/scene/source_location.h"

namespace tessera {

// atmosphericAttenuation <front-plane> <front-scale> <back-plane> <back-scale> <r> <g> <b>.
struct AtmosphericAttenuation {
  double front_distance = 0, front_scale = 1, back_distance = 1, back_scale = 1;
  Rgb color;
  friend bool operator==(const AtmosphericAttenuation&, const AtmosphericAttenuation&) = default;
};

// fog <fog-start> <fog-end> <r> <g> <b>: linear in the Euclidean distance (eq. 4.22-4.23).
struct Fog {
  double start = 0, end = 1;
  Rgb color;
  // VRML's EXPONENTIAL fog (§4.14.4): exp(-d / (end - d)) of the colour is kept for d < end,
  // none beyond; SDL's fog is linear between start and end (eq. 4.22-4.23).
  bool exponential = false;
  friend bool operator==(const Fog&, const Fog&) = default;
};

// Global scene attributes of SDL §3.2.7.
struct SceneGlobals {
  Rgb background{0, 0, 0};
  // VRML's Background gradient: when set, it gives the background by direction instead.
  std::optional<SkyGradient> sky;
  Rgb global_ambient{0.1, 0.1, 0.1};
  LightAttenuation light_attenuation;
  std::optional<AtmosphericAttenuation> atmospheric_attenuation;
  std::optional<Fog> fog;
  // Lower bounds on how far secondary rays start from a surface. The offsets themselves come
  // from floating-point error bounds; these only enlarge them when a scene sets them.
  double shadow_feeler_epsilon = 0;
  double reflectivity_epsilon = 0;
  double transparency_epsilon = 0;
  double mesh_epsilon = 0;
  bool adapted_shadow_computation = false;
  double min_reflectivity = 0.01;
  double min_transparency = 0.01;
  int max_recursion_depth = 5;
  bool show_extents = false;
  // motionBlur <frame-length> <#time-samples>: the shutter is open from -frame-length/2 to
  // +frame-length/2 (eq. 4.53-4.54), sampled at that many jittered times per camera sample.
  double motion_blur_frame_length = 1;
  int motion_blur_time_samples = 8;
  friend bool operator==(const SceneGlobals&, const SceneGlobals&) = default;
};

// One shape instance: geometry in object space, its object-to-world transform and material.
struct SceneObject {
  ShapeGeometry geometry;
  Affine transform;  // object to world (the CT when the shape was written)
  Material material;
  SourceLocation where;                // the shape keyword, for messages
  std::optional<ObjectMotion> motion;  // mbEnable: moves during the shutter
};

// The bytes of an image file a scene names (imageTexture), read once per path by the loader so
// that it travels in the scene's bundle; the renderer decodes it (render/prepared_scene.h).
struct ImageFile {
  std::string path;      // resolved, root-relative
  std::string bytes;     // the file as stored: any format OpenImageIO reads
  SourceLocation where;  // the first imageTexture that names it, for messages
};

struct Scene {
  Camera camera;
  // VRML's Viewpoints in file order, Inlined files' not included; camera is the first's
  // unless a camera setting replaced it. Empty for SDL.
  std::vector<NamedCamera> viewpoints;
  SceneGlobals globals;
  std::vector<Light> lights;
  std::vector<SceneObject> objects;
  std::vector<Mesh> meshes;
  std::vector<ImageFile> images;
  // Things the loader accepted but that change nothing, or that this renderer does not
  // simulate yet, each with its location. Shown to users, never dropped silently.
  std::vector<std::string> warnings;
};

}  // namespace tessera
