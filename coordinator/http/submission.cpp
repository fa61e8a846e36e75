#include "coordinator/http/submission.h"

#include <set>
#include <vector>

#include "common/loaders/scene_loader.h"
#include "coordinator/http/multipart.h"
#include "coordinator/http/tar_reader.h"
#include "coordinator/jobs/api_error.h"

namespace tessera {
namespace {

using nlohmann::json;

ApiError bad_request(const std::string& detail) {
  return ApiError(Refusal::bad_request, "bad_request", detail);
}

std::string get_string(const json& s, const char* key, const std::string& fallback) {
  if (!s.contains(key)) return fallback;
  if (!s[key].is_string()) throw bad_request(std::string(key) + " must be a string");
  return s[key].get<std::string>();
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

Submission read_json_submission(std::string_view body,
                                const std::optional<std::filesystem::path>& scenes_dir) {
  const json j = json::parse(body, nullptr, false);
  if (!j.is_object())
    throw ApiError(Refusal::bad_request, "bad_json", "the body is not a JSON object");
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
  sub.main = default_main(sub.format);
  try {
    sub.files = read_tar(body);
  } catch (const std::exception& e) {
    throw ApiError(Refusal::bad_request, "bad_bundle", e.what());
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
    throw ApiError(Refusal::bad_request, "bad_bundle", e.what());
  }
  Submission sub;
  std::optional<std::string> scene, main;
  for (FormPart& part : parts) {
    if (part.name == "scene") {
      scene = std::move(part.data);
    } else if (part.name == "settings") {
      sub.settings = json::parse(part.data, nullptr, false);
      if (!sub.settings.is_object())
        throw ApiError(Refusal::bad_request, "bad_json", "settings is not a JSON object");
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

}  // namespace

Submission read_rerender(std::string_view body, const Bundle& bundle, json settings) {
  const json j = body.empty() ? json::object() : json::parse(body, nullptr, false);
  if (!j.is_object())
    throw ApiError(Refusal::bad_request, "bad_json", "the body is not a JSON object");
  for (const auto& [key, value] : j.items())
    if (key != "settings") throw bad_request("unknown field \"" + key + "\"");
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) throw bad_request("settings must be an object");
    for (const auto& [key, value] : j["settings"].items()) {
      if (!value.is_null())
        settings[key] = value;
      else if (settings.erase(key) == 0 && !find_setting(key))
        throw bad_request("unknown setting \"" + key + "\"");
    }
  }
  Submission sub;
  sub.files = bundle.files;
  sub.main = bundle.main;
  sub.format = bundle.format;
  sub.settings = std::move(settings);
  return sub;
}

Submission read_submission(const JobUpload& upload,
                           const std::optional<std::filesystem::path>& scenes_dir) {
  const std::string_view type = upload.content_type;
  if (type.starts_with("application/x-tar") || type.starts_with("application/tar"))
    return read_tar_submission(upload.body, upload.query);
  if (type.starts_with("application/json")) return read_json_submission(upload.body, scenes_dir);
  if (const auto boundary = multipart_boundary(type))
    return read_multipart_submission(upload.body, *boundary);
  throw ApiError(Refusal::unsupported_media_type, "unsupported_media_type",
                 "POST JSON (application/json), a tar bundle (application/x-tar) or a form "
                 "(multipart/form-data)");
}

JobRequest parse_job_request(const JobUpload& upload, const ServiceLimits& limits,
                             const std::optional<std::filesystem::path>& scenes_dir,
                             const IntakeBudget& budget) {
  return admit_job(read_submission(upload, scenes_dir), limits, scenes_dir, budget);
}

}  // namespace tessera
