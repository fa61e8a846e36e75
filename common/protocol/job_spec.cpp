#include "common/protocol/job_spec.h"

#include "common/protocol/frame.h"

namespace tessera {

void apply_overrides(Scene& scene, const SceneOverrides& o) {
  if (o.max_depth) scene.globals.max_recursion_depth = *o.max_depth;
  if (o.min_weight) {
    scene.globals.min_reflectivity = *o.min_weight;
    scene.globals.min_transparency = *o.min_weight;
  }
}

nlohmann::json to_json(const JobSpec& spec) {
  const RenderSettings& s = spec.settings;
  nlohmann::json j = {{"width", s.width},
                      {"height", s.height},
                      {"aa", s.aa_samples},
                      {"stochastic", s.stochastic},
                      {"jitter", s.jitter},
                      {"seed", s.seed},
                      {"passes", s.passes},
                      {"bvh", s.bvh == BvhMode::Sah},
                      {"time_samples", s.time_samples}};
  j["shadows"] = to_string(s.shadows);
  j["cone_samples"] = s.cone_samples;
  j["shadow_jitter"] = s.shadow_jitter;
  j["normalize"] = s.normalize_colors;
  j["brightness"] = s.normalize_brightness;
  if (spec.overrides.max_depth) j["max_depth"] = *spec.overrides.max_depth;
  if (spec.overrides.min_weight) j["min_weight"] = *spec.overrides.min_weight;
  return j;
}

JobSpec job_spec_from_json(const nlohmann::json& j) {
  JobSpec spec;
  RenderSettings& s = spec.settings;
  try {
    s.width = j.at("width").get<int>();
    s.height = j.at("height").get<int>();
    s.aa_samples = j.at("aa").get<int>();
    s.stochastic = j.at("stochastic").get<bool>();
    s.jitter = j.at("jitter").get<double>();
    s.seed = j.at("seed").get<std::uint64_t>();
    s.passes = j.at("passes").get<int>();
    s.time_samples = j.at("time_samples").get<int>();
    s.bvh = j.at("bvh").get<bool>() ? BvhMode::Sah : BvhMode::None;
    const std::optional<ShadowMode> shadows = parse_shadow_mode(j.at("shadows").get<std::string>());
    if (!shadows) throw ProtocolError("bad job settings: unknown shadow mode");
    s.shadows = *shadows;
    s.cone_samples = j.at("cone_samples").get<int>();
    s.shadow_jitter = j.at("shadow_jitter").get<double>();
    s.normalize_colors = j.at("normalize").get<bool>();
    s.normalize_brightness = j.at("brightness").get<double>();
    if (j.contains("max_depth")) spec.overrides.max_depth = j["max_depth"].get<int>();
    if (j.contains("min_weight")) spec.overrides.min_weight = j["min_weight"].get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("bad job settings: ") + e.what());
  }
  return spec;
}

nlohmann::json to_json(const RenderStats& s) {
  return {{"camera_rays", s.camera_rays},
          {"shadow_rays", s.shadow_rays},
          {"reflection_rays", s.reflection_rays},
          {"refraction_rays", s.refraction_rays},
          {"shape_tests", s.intersections.shape_tests},
          {"triangle_tests", s.intersections.triangle_tests},
          {"bvh_nodes", s.intersections.bvh_nodes},
          {"pixels", s.pixels},
          {"samples", s.samples},
          {"nan_samples", s.nan_samples},
          {"ray_budget_pixels", s.ray_budget_pixels},
          {"seconds", s.seconds}};
}

RenderStats stats_from_json(const nlohmann::json& j) {
  RenderStats s;
  auto u64 = [&](const char* key) { return j.value<std::uint64_t>(key, 0); };
  try {
    s.camera_rays = u64("camera_rays");
    s.shadow_rays = u64("shadow_rays");
    s.reflection_rays = u64("reflection_rays");
    s.refraction_rays = u64("refraction_rays");
    s.intersections.shape_tests = u64("shape_tests");
    s.intersections.triangle_tests = u64("triangle_tests");
    s.intersections.bvh_nodes = u64("bvh_nodes");
    s.pixels = u64("pixels");
    s.samples = u64("samples");
    s.nan_samples = u64("nan_samples");
    s.ray_budget_pixels = u64("ray_budget_pixels");
    s.seconds = j.value("seconds", 0.0);
  } catch (const nlohmann::json::exception& e) {
    throw ProtocolError(std::string("bad statistics: ") + e.what());
  }
  return s;
}

}  // namespace tessera
