// What a worker needs besides the bundle to render a job's units: the render settings and the
// scene overrides of the page's controls (recursion depth, minimum weight). Coordinator and
// worker apply the same overrides to the same parsed scene.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "common/render/settings.h"
#include "common/render/stats.h"
#include "common/scene/scene.h"

namespace tessera {

struct SceneOverrides {
  std::optional<int> max_depth;      // maxRecursionDepth
  std::optional<double> min_weight;  // minReflectivity and minTransparency
  friend bool operator==(const SceneOverrides&, const SceneOverrides&) = default;
};

struct JobSpec {
  RenderSettings settings;
  SceneOverrides overrides;
};

void apply_overrides(Scene& scene, const SceneOverrides& overrides);

nlohmann::json to_json(const JobSpec& spec);
// Throws ProtocolError for missing or mistyped fields.
JobSpec job_spec_from_json(const nlohmann::json& j);

nlohmann::json to_json(const RenderStats& stats);
RenderStats stats_from_json(const nlohmann::json& j);

}  // namespace tessera
