#include "common/protocol/job_spec.h"

#include <type_traits>

#include "common/protocol/frame.h"
#include "common/protocol/json_integer.h"

namespace tessera {

void apply_overrides(Scene& scene, const SceneOverrides& o) {
  if (o.max_depth) scene.globals.max_recursion_depth = *o.max_depth;
  if (o.min_weight) {
    scene.globals.min_reflectivity = *o.min_weight;
    scene.globals.min_transparency = *o.min_weight;
  }
}

namespace {

nlohmann::json to_json(const Vec3& v) { return {v.x, v.y, v.z}; }

std::optional<Vec3> vec3_from_json(const nlohmann::json& j) {
  if (!j.is_array() || j.size() != 3) return std::nullopt;
  for (const nlohmann::json& c : j)
    if (!c.is_number()) return std::nullopt;
  return Vec3{j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

// {"eye": [x, y, z], "look_at": [x, y, z], "up": [x, y, z], "fov": degrees}, every key given
// and no other.
std::optional<Camera> camera_from_json(const nlohmann::json& j) {
  if (!j.is_object() || j.size() != 4 || !j.contains("fov") || !j["fov"].is_number())
    return std::nullopt;
  Camera camera;
  for (auto [key, field] : {std::pair{"eye", &camera.eye}, std::pair{"look_at", &camera.look_at},
                            std::pair{"up", &camera.up}}) {
    const std::optional<Vec3> v = j.contains(key) ? vec3_from_json(j[key]) : std::nullopt;
    if (!v) return std::nullopt;
    *field = *v;
  }
  camera.view_angle = j["fov"].get<double>();
  return camera;
}

}  // namespace

nlohmann::json camera_to_json(const Camera& camera) {
  return {{"eye", to_json(camera.eye)},
          {"look_at", to_json(camera.look_at)},
          {"up", to_json(camera.up)},
          {"fov", camera.view_angle}};
}

nlohmann::json setting_to_json(const SettingValue& value) {
  return std::visit(
      [](const auto& v) -> nlohmann::json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>)
          return nullptr;
        else if constexpr (std::is_same_v<T, Camera>)
          return camera_to_json(v);
        else if constexpr (std::is_same_v<T, PixelRect>)
          return {v.x0, v.y0, v.x1, v.y1};
        else
          return v;
      },
      value);
}

std::optional<SettingValue> setting_from_json(const SettingSpec& spec, const nlohmann::json& j) {
  switch (spec.type) {
    case SettingType::Integer:
      if (const auto v = json_integer<std::int64_t>(j)) return *v;
      break;
    case SettingType::Number:
      if (j.is_number()) return j.get<double>();
      break;
    case SettingType::Boolean:
      if (j.is_boolean()) return j.get<bool>();
      break;
    case SettingType::Choice:
      if (j.is_string()) return j.get<std::string>();
      break;
    case SettingType::Seed:
      if (j.is_number_unsigned()) return j.get<std::uint64_t>();
      break;
    case SettingType::Camera:
      if (const std::optional<Camera> camera = camera_from_json(j)) return *camera;
      break;
    case SettingType::Region: {
      // [x0, y0, x1, y1]: four integers that fit an int (their range is setting_error's).
      if (!j.is_array() || j.size() != 4) break;
      int v[4];
      for (int i = 0; i < 4; ++i) {
        const std::optional<int> coordinate = json_integer<int>(j[i]);
        if (!coordinate || *coordinate < 0) return std::nullopt;
        v[i] = *coordinate;
      }
      return PixelRect{v[0], v[1], v[2], v[3]};
    }
  }
  return std::nullopt;
}

// The settings are the wire layer's of the schema; an unset override is left out.
nlohmann::json to_json(const JobSpec& spec) {
  JobSettings settings;
  settings.render = spec.settings;
  settings.overrides = spec.overrides;
  nlohmann::json j = nlohmann::json::object();
  for (const SettingSpec& setting : settings_schema()) {
    if (!(setting.layers & kWire)) continue;
    const SettingValue value = setting.access.get(settings);
    if (!std::holds_alternative<std::monostate>(value))
      j[std::string(setting.name)] = setting_to_json(value);
  }
  return j;
}

JobSpec job_spec_from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw ProtocolError("bad job settings: not an object");
  JobSettings settings;
  for (const SettingSpec& setting : settings_schema()) {
    if (!(setting.layers & kWire)) continue;
    const std::string name(setting.name);
    if (!j.contains(name)) {
      // Only an override may be left out (the scene's value).
      if (std::holds_alternative<std::monostate>(setting.default_value())) continue;
      throw ProtocolError("bad job settings: no " + name);
    }
    const std::optional<SettingValue> value = setting_from_json(setting, j[name]);
    const std::optional<std::string> error =
        value ? setting_error(setting, *value) : "must be " + describe_values(setting);
    if (error) throw ProtocolError("bad job settings: " + name + " " + *error);
    setting.access.set(settings, *value);
  }
  if (const std::optional<std::string> error = settings_error(settings.render))
    throw ProtocolError("bad job settings: " + *error);
  return {settings.render, settings.overrides};
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
