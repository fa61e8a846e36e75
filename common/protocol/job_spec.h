// What a worker needs besides the bundle to render a job's units: the render settings and the
// scene overrides of the page's controls (recursion depth, minimum weight, camera). Coordinator and
// worker apply the same overrides to the same parsed scene. The fields and their ranges are
// the wire layer's settings of common/settings/settings_schema.h.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "common/progressive/unit_pixels.h"
#include "common/scene/scene.h"
#include "common/settings/render_settings.h"
#include "common/settings/settings_schema.h"
#include "common/stats/render_stats.h"

namespace tessera {

struct JobSpec {
  RenderSettings settings;
  SceneOverrides overrides;
};

// The scene globals among the overrides (max_depth, min_weight); the camera is the loader's
// to put in place (load_scene), before anything that depends on it is made.
void apply_overrides(Scene& scene, const SceneOverrides& overrides);

nlohmann::json to_json(const JobSpec& spec);
// Throws ProtocolError for missing, mistyped or out-of-range fields.
JobSpec job_spec_from_json(const nlohmann::json& j);

// A setting's value as JSON, and back in the setting's type (an integer for Integer, any number
// for Number); nullopt when the JSON holds another type. The job request reads its settings
// with it too.
nlohmann::json setting_to_json(const SettingValue& value);
// {"eye": [x, y, z], "look_at": [x, y, z], "up": [x, y, z], "fov": degrees}: the camera
// setting's form, also in a job's status.
nlohmann::json camera_to_json(const Camera& camera);
std::optional<SettingValue> setting_from_json(const SettingSpec& spec, const nlohmann::json& j);

nlohmann::json to_json(const RenderStats& stats);
RenderStats stats_from_json(const nlohmann::json& j);

}  // namespace tessera
