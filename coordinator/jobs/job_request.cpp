#include "coordinator/jobs/job_request.h"

#include <algorithm>
#include <map>
#include <set>

#include "common/image/decoded_texture.h"
#include "common/loaders/recording_source.h"
#include "common/loaders/scene_loader.h"
#include "common/loaders/scene_source.h"
#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/render/time_prediction.h"
#include "common/texture/image_texture.h"
#include "coordinator/jobs/api_error.h"
#include "coordinator/jobs/multipart.h"
#include "coordinator/jobs/tar_reader.h"

namespace tessera {
namespace {

using nlohmann::json;

ApiError bad_request(const std::string& detail) { return ApiError(400, "bad_request", detail); }

std::string get_string(const json& s, const char* key, const std::string& fallback) {
  if (!s.contains(key)) return fallback;
  if (!s[key].is_string()) throw bad_request(std::string("settings.") + key + " must be a string");
  return s[key].get<std::string>();
}

// The most a job request may ask of a setting: its range, narrowed by this service's limits.
double request_max(const SettingSpec& spec, const ServiceLimits& limits) {
  switch (spec.cap) {
    case ServiceCap::None:
      break;
    case ServiceCap::Side:
      return std::min<double>(spec.max, limits.max_side);
    case ServiceCap::Passes:
      return std::min<double>(spec.max, limits.max_passes);
    case ServiceCap::ConeSamples:
      return std::min<double>(spec.max, limits.max_cone_samples);
    case ServiceCap::Depth:
      return std::min<double>(spec.max, limits.max_depth);
  }
  return spec.max;
}

// Query values of a tar upload, typed the way a JSON body would have them.
json settings_from_query(const std::map<std::string, std::string>& query) {
  json s = json::object();
  for (const auto& [key, value] : query) {
    if (key == "main" || key == "format") continue;
    json parsed = json::parse(value, nullptr, false);
    s[key] = parsed.is_discarded() || parsed.is_object() ? json(value) : parsed;
  }
  return s;
}

// The scene's name in the bundle when the request gives none: what error messages call it.
std::string default_main(const std::string& format) {
  return format == "vrml" ? "scene.wrl" : "scene.sdl";
}

struct Submission {
  std::map<std::string, std::string> files;
  std::string main = default_main("sdl");
  std::string format = "sdl";
  json settings = json::object();
};

Submission read_json_submission(std::string_view body,
                                const std::optional<std::filesystem::path>& scenes_dir) {
  const json j = json::parse(body, nullptr, false);
  if (!j.is_object()) throw ApiError(400, "bad_json", "the body is not a JSON object");
  static const std::set<std::string> known = {"scene", "scene_file", "format",
                                              "files", "main",       "settings"};
  for (const auto& [key, value] : j.items())
    if (!known.count(key)) throw bad_request("unknown field \"" + key + "\"");
  Submission sub;
  sub.format = get_string(j, "format", "sdl");
  sub.main = get_string(j, "main", default_main(sub.format));
  if (j.contains("files")) {
    if (!j["files"].is_object()) throw bad_request("files must map paths to file contents");
    for (const auto& [path, bytes] : j["files"].items()) {
      if (!bytes.is_string()) throw bad_request("files[\"" + path + "\"] must be a string");
      sub.files[path] = bytes.get<std::string>();
    }
  }
  if (j.contains("scene")) {
    if (!j["scene"].is_string()) throw bad_request("scene must be the scene's text");
    sub.files[sub.main] = j["scene"].get<std::string>();
  } else if (j.contains("scene_file")) {
    if (!scenes_dir) throw bad_request("scene_file needs a coordinator started with --scenes-dir");
    sub.main = get_string(j, "scene_file", "");
  } else if (!sub.files.count(sub.main)) {
    throw bad_request("give the scene as \"scene\" (text), \"scene_file\" or in \"files\"");
  }
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) throw bad_request("settings must be an object");
    sub.settings = j["settings"];
  }
  return sub;
}

Submission read_tar_submission(std::string_view body,
                               const std::map<std::string, std::string>& query) {
  Submission sub;
  try {
    sub.files = read_tar(body);
  } catch (const std::exception& e) {
    throw ApiError(400, "bad_bundle", e.what());
  }
  if (auto it = query.find("format"); it != query.end()) sub.format = it->second;
  if (auto it = query.find("main"); it != query.end()) {
    sub.main = it->second;
  } else if (!sub.files.count(sub.main)) {
    // A single top-level scene file of the format (.sdl; .wrl, .wrl.gz, .wrz) is the scene.
    const auto is_scene = [&](const std::string& path) {
      return sub.format == "vrml" ? scene_format_of(path) == SceneFormat::Vrml
                                  : path.ends_with(".sdl");
    };
    std::vector<std::string> top;
    for (const auto& [path, bytes] : sub.files)
      if (path.find('/') == std::string::npos && is_scene(path)) top.push_back(path);
    if (top.size() != 1) throw bad_request("name the bundle's scene file with ?main=PATH");
    sub.main = top.front();
  }
  sub.settings = settings_from_query(query);
  return sub;
}

// Fields `scene` (text), `settings` (JSON), `main`, `format`; `file` parts keep their file
// names as bundle paths (curl -F 'file=@m.obj;filename=meshes/m.obj').
Submission read_multipart_submission(std::string_view body, const std::string& boundary) {
  std::vector<FormPart> parts;
  try {
    parts = parse_multipart(body, boundary);
  } catch (const std::exception& e) {
    throw ApiError(400, "bad_bundle", e.what());
  }
  Submission sub;
  std::optional<std::string> scene, main;
  for (FormPart& part : parts) {
    if (part.name == "scene") {
      scene = std::move(part.data);
    } else if (part.name == "settings") {
      sub.settings = json::parse(part.data, nullptr, false);
      if (!sub.settings.is_object())
        throw ApiError(400, "bad_json", "settings is not a JSON object");
    } else if (part.name == "main") {
      main = part.data;
    } else if (part.name == "format") {
      sub.format = part.data;
    } else if (part.name == "file" && part.filename) {
      sub.files[*part.filename] = std::move(part.data);
    } else {
      throw bad_request("unknown form field \"" + part.name + "\"");
    }
  }
  sub.main = main.value_or(default_main(sub.format));
  if (scene) sub.files[sub.main] = std::move(*scene);
  if (!sub.files.count(sub.main)) throw bad_request("the form has no scene (field \"scene\")");
  return sub;
}

// A scene that produces more than the load budget allows: 413 when it is a limit on bytes
// (what the request would make the coordinator hold), else 422; located where it was passed.
ApiError over_load_budget(const LoadBudgetExceeded& e) {
  const LoadLimit limit = e.limit();
  const bool bytes = limit == LoadLimit::BytesRead || limit == LoadLimit::BytesProduced ||
                     limit == LoadLimit::FileBytes;
  return ApiError(bytes ? 413 : 422, "over_budget", e.what(),
                  {{"limit", e.limit_name()},
                   {"value", e.limit_value()},
                   {"file", e.where().file},
                   {"line", e.where().line},
                   {"column", e.where().column}});
}

// Workers have no image library (they start without OpenImageIO): every texture the scene
// reads travels in the bundle decoded, bit for bit what decoding it here gives.
std::map<std::string, std::string> decoded_textures(const Scene& scene) {
  std::map<std::string, std::string> files;
  for (const ImageFile& image : scene.images)
    if (!is_decoded_texture(image.bytes))
      files[image.path] =
          encode_decoded_texture(decode_image(image.bytes, image.path, kMaxTexturePixels),
                                 image_channels(image.bytes, image.path));
  return files;
}

// The one place where a request's budget meets the loader and the probe.
void check_scene(const Submission& sub, const std::optional<std::filesystem::path>& scenes_dir,
                 const ServiceLimits& limits, const IntakeBudget& budget, JobRequest& out) {
  for (const auto& [path, bytes] : sub.files)
    if (!is_plain_relative_path(path))
      throw ApiError(400, "bad_bundle", "file path \"" + path + "\" leaves the bundle");
  if (!is_plain_relative_path(sub.main))
    throw ApiError(400, "bad_bundle", "scene path \"" + sub.main + "\" leaves the bundle");
  const MemorySource submitted(sub.files);
  std::optional<DirectorySource> folder;
  if (scenes_dir) folder.emplace(*scenes_dir);
  // Submitted files first, then the configured scenes folder; the bundle holds exactly the
  // files the scene read.
  RecordingSource source(submitted, folder ? &*folder : nullptr);
  std::map<std::string, std::string> textures;
  LoadBudget load_budget;  // the defaults of docs/SERVICE.md's "Load budget", and our deadline
  load_budget.deadline = budget.deadline;
  load_budget.strict = out.strict;
  try {
    Scene scene = load_scene(source, sub.main, *scene_format_named(sub.format), load_budget);
    budget.check("loading the scene");
    apply_overrides(scene, out.spec.overrides);
    if (scene.globals.max_recursion_depth > limits.max_depth)
      throw bad_request("maxRecursionDepth " + std::to_string(scene.globals.max_recursion_depth) +
                        " is over this service's limit of " + std::to_string(limits.max_depth));
    const PreparedScene prepared(scene, out.spec.settings.bvh);
    budget.check("preparing the scene");
    out.effects = render_effects(prepared, out.spec.settings).names();
    const CostProbe probe = probe_render_cost(prepared, out.spec.settings);
    out.seconds_per_pixel_pass = probe.seconds_per_pixel_pass();
    out.probe_cut_short = probe.cut_short;
    budget.check("the cost probe");
    out.plan.unit_pixels = unit_pixels_for_cost(out.seconds_per_pixel_pass);
    textures = decoded_textures(scene);
    out.warnings = scene.warnings;
    for (const auto& u : prepared.unsupported()) out.warnings.push_back(u);
  } catch (const LoadBudgetExceeded& e) {
    if (e.limit() == LoadLimit::Deadline) throw budget.over_time("loading the scene");
    throw over_load_budget(e);
  } catch (const SceneError& e) {
    throw ApiError(400, "scene_error", e.what(),
                   {{"file", e.where().file},
                    {"line", e.where().line},
                    {"column", e.where().column},
                    {"message", e.message()}});
  }
  out.bundle.main = sub.main;
  out.bundle.format = sub.format;
  out.bundle.files = source.files();
  for (auto& [path, bytes] : textures) out.bundle.files[path] = std::move(bytes);
}

}  // namespace

void parse_settings(const json& s, const ServiceLimits& limits, JobRequest& out) {
  JobSettings settings;
  for (const auto& [key, value] : s.items()) {
    const SettingSpec* spec = find_setting(key);
    if (!spec || !(spec->layers & kJobRequest))
      throw bad_request("unknown setting \"" + key + "\"");
    const double max = request_max(*spec, limits);
    const std::optional<SettingValue> parsed = setting_from_json(*spec, value);
    const std::optional<std::string> error =
        parsed ? setting_error(*spec, *parsed, max) : "must be " + describe_values(*spec, max);
    if (error) throw bad_request("settings." + key + " " + *error);
    spec->access.set(settings, *parsed);
  }
  const RenderSettings& r = settings.render;
  if (static_cast<long long>(r.width) * r.height > limits.max_pixels)
    throw bad_request("width x height is over this service's limit of " +
                      std::to_string(limits.max_pixels) + " pixels");
  if (const std::optional<std::string> error = settings_error(r))
    throw bad_request("settings." + *error);
  out.spec = {r, settings.overrides};
  out.priority = settings.schedule.priority;
  out.strict = settings.load.strict;
  out.plan.width = r.width;
  out.plan.height = r.height;
  out.plan.passes = r.passes;
  out.plan.progressive = settings.schedule.progressive;
  out.plan.region = plan_region(r);
  // The schema's choices are the names these take (tests/service/coordinator_test.cpp).
  out.plan.order = parse_unit_order(settings.schedule.order);
  out.plan.preview = parse_preview_mode(settings.schedule.preview);
}

JobRequest parse_job_request(const JobUpload& upload, const ServiceLimits& limits,
                             const std::optional<std::filesystem::path>& scenes_dir,
                             const IntakeBudget& budget) {
  const std::string_view type = upload.content_type;
  Submission sub;
  if (type.starts_with("application/x-tar") || type.starts_with("application/tar"))
    sub = read_tar_submission(upload.body, upload.query);
  else if (type.starts_with("application/json"))
    sub = read_json_submission(upload.body, scenes_dir);
  else if (const auto boundary = multipart_boundary(type))
    sub = read_multipart_submission(upload.body, *boundary);
  else
    throw ApiError(415, "unsupported_media_type",
                   "POST JSON (application/json), a tar bundle (application/x-tar) or a form "
                   "(multipart/form-data)");
  if (!scene_format_named(sub.format)) throw bad_request("format must be \"sdl\" or \"vrml\"");
  JobRequest out;
  parse_settings(sub.settings, limits, out);
  budget.check("decoding the request");
  check_scene(sub, scenes_dir, limits, budget, out);
  return out;
}

}  // namespace tessera
