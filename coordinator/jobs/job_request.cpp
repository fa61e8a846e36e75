#include "coordinator/jobs/job_request.h"

#include <algorithm>
#include <map>

#include "common/image/decoded_texture.h"
#include "common/loaders/recording_source.h"
#include "common/loaders/scene_loader.h"
#include "common/loaders/scene_source.h"
#include "common/render/prepared_scene.h"
#include "common/render/render.h"
#include "common/render/sample_lattice.h"
#include "common/render/time_prediction.h"
#include "common/texture/image_texture.h"
#include "coordinator/jobs/api_error.h"

namespace tessera {
namespace {

using nlohmann::json;

ApiError bad_request(const std::string& detail) {
  return ApiError(Refusal::bad_request, "bad_request", detail);
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

// A scene that produces more than the load budget allows: too large when it is a limit on
// bytes (what the request would make the coordinator hold), else unprocessable; located where
// it was passed.
ApiError over_load_budget(const LoadBudgetExceeded& e) {
  const LoadLimit limit = e.limit();
  const bool bytes = limit == LoadLimit::BytesRead || limit == LoadLimit::BytesProduced ||
                     limit == LoadLimit::FileBytes;
  return ApiError(bytes ? Refusal::too_large : Refusal::unprocessable, "over_budget", e.what(),
                  {{"limit", e.limit_name()},
                   {"value", e.limit_value()},
                   {"file", e.where().file},
                   {"line", e.where().line},
                   {"column", e.where().column}});
}

// Workers have no image library (they start without OpenImageIO): every texture the scene
// reads travels in the bundle decoded, bit for bit what decoding it here gives. Each image
// may take a second to decode (up to kMaxTexturePixels), so each is started within the budget.
std::map<std::string, std::string> decoded_textures(const Scene& scene,
                                                    const IntakeBudget& budget) {
  std::map<std::string, std::string> files;
  for (const ImageFile& image : scene.images)
    if (!is_decoded_texture(image.bytes)) {
      budget.check("decoding the textures");
      files[image.path] =
          encode_decoded_texture(decode_image(image.bytes, image.path, kMaxTexturePixels),
                                 image_channels(image.bytes, image.path));
    }
  return files;
}

// The probe traces lone pixels; where a render's pixels share their grid samples
// (render/sample_lattice.h) each traces only a share of them, which depends on how the plan
// lays its units out: the share of the plan made with at most two passes (every pass after
// the first is laid out as the second) and units of the default size (a unit's edges, whose
// lattice points it traces again, move the share by a few percent between sizes).
double plan_traced_share(const PlanOptions& plan, const EffectSet& effects,
                         const RenderSettings& settings) {
  if (!samples_depend_on_position_only(effects, settings) || settings.aa_samples <= 1) return 1;
  PlanOptions first_two = plan;
  first_two.passes = std::min(plan.passes, 2);
  return traced_share(make_plan(first_two), plan.passes, settings.aa_samples);
}

// The one place where a request's budget meets the loader and the probe.
void check_scene(const Submission& sub, const std::optional<std::filesystem::path>& scenes_dir,
                 const ServiceLimits& limits, const IntakeBudget& budget, JobRequest& out) {
  for (const auto& [path, bytes] : sub.files)
    if (!is_plain_relative_path(path))
      throw ApiError(Refusal::bad_request, "bad_bundle",
                     "file path \"" + path + "\" leaves the bundle");
  if (!is_plain_relative_path(sub.main))
    throw ApiError(Refusal::bad_request, "bad_bundle",
                   "scene path \"" + sub.main + "\" leaves the bundle");
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
    Scene scene = load_scene(source, sub.main, *scene_format_named(sub.format), load_budget,
                             out.spec.overrides.camera);
    budget.check("loading the scene");
    apply_overrides(scene, out.spec.overrides);
    if (scene.globals.max_recursion_depth > limits.max_depth)
      throw bad_request("maxRecursionDepth " + std::to_string(scene.globals.max_recursion_depth) +
                        " is over this service's limit of " + std::to_string(limits.max_depth));
    out.warnings = scene.warnings;
    out.camera = scene.camera;
    out.viewpoints = scene.viewpoints;
    {
      const PreparedScene prepared(scene, out.spec.settings.bvh);
      budget.check("preparing the scene");
      const EffectSet effects = render_effects(prepared, out.spec.settings);
      out.effects = effects.names();
      const CostProbe probe = probe_render_cost(prepared, out.spec.settings);
      out.seconds_per_pixel_pass =
          probe.seconds_per_pixel_pass() * plan_traced_share(out.plan, effects, out.spec.settings);
      out.probe_cut_short = probe.cut_short;
      budget.check("the cost probe");
      out.plan.unit_pixels = unit_pixels_for_cost(out.seconds_per_pixel_pass);
      for (const auto& u : prepared.unsupported()) out.warnings.push_back(u);
    }  // its BVHs and decoded textures are freed before the textures are decoded again here
    textures = decoded_textures(scene, budget);
  } catch (const LoadBudgetExceeded& e) {
    if (e.limit() == LoadLimit::Deadline) throw budget.over_time("loading the scene");
    throw over_load_budget(e);
  } catch (const SceneError& e) {
    throw ApiError(Refusal::bad_request, "scene_error", e.what(),
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

void fit_units_to_threads(JobRequest& request, int threads) {
  request.plan.unit_pixels =
      unit_pixels_for_threads(request.plan, threads, request.seconds_per_pixel_pass);
}

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
  // A side left out takes its default (640 x 480), which may be over a lowered side limit
  // (found by fuzz_job_request); a side given was checked above.
  if (r.width > limits.max_side || r.height > limits.max_side)
    throw bad_request("the image is " + std::to_string(r.width) + " x " + std::to_string(r.height) +
                      " (a side not given takes its default), over " + "this service's limit of " +
                      std::to_string(limits.max_side) + " a side");
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
  out.plan.region = r.region;
  // The schema's choices are the names these take (tests/service/coordinator_test.cpp).
  out.plan.order = parse_unit_order(settings.schedule.order);
  out.plan.preview = parse_preview_mode(settings.schedule.preview);
}

JobRequest admit_job(const Submission& submission, const ServiceLimits& limits,
                     const std::optional<std::filesystem::path>& scenes_dir,
                     const IntakeBudget& budget) {
  if (!scene_format_named(submission.format))
    throw bad_request("format must be \"sdl\" or \"vrml\"");
  JobRequest out;
  parse_settings(submission.settings, limits, out);
  budget.check("decoding the request");
  check_scene(submission, scenes_dir, limits, budget, out);
  return out;
}

}  // namespace tessera
