#include "coordinator/http/job_json.h"

#include "common/protocol/job_spec.h"

namespace tessera {

namespace {

double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

nlohmann::json levels_table(const Job& job, Clock::time_point now) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t s = 0; s < job.plan.stages.size(); ++s) {
    const Stage& st = job.plan.stages[s];
    const StageTiming& t = job.stage_timing()[s];
    const bool complete = t.units_done == st.unit_count;
    double time = 0;
    if (t.first_dispatch)
      time = seconds(*t.first_dispatch,
                     complete && t.last_result ? *t.last_result : job.finished().value_or(now));
    // As in the seeds' Figure 5.1.1: time per block, and per pixel of a block; here per block
    // traced (a level traces only its new anchors).
    const double per_block = st.traced > 0 ? time / static_cast<double>(st.traced) : 0;
    rows.push_back({{"level", st.level},
                    {"pass", st.pass},
                    {"block", st.block},
                    {"blocks", st.blocks},
                    {"pixels_per_block", static_cast<long long>(st.block) * st.block},
                    {"traced", st.traced},
                    {"preview_only", st.preview_only},
                    {"units", st.unit_count},
                    {"units_done", t.units_done},
                    {"complete", complete},
                    {"seconds", time},
                    {"seconds_per_block", per_block},
                    {"seconds_per_pixel", per_block / (static_cast<double>(st.block) * st.block)}});
  }
  return rows;
}

}  // namespace

nlohmann::json job_summary_json(const Job& job, Clock::time_point now) {
  const double progress = job.plan.total_cost > 0 ? static_cast<double>(job.done_cost()) /
                                                        static_cast<double>(job.plan.total_cost)
                                                  : 0;
  const Stage& stage = job.plan.stages[job.current_stage()];
  nlohmann::json j = {{"id", job.id},
                      {"state", to_string(job.state())},
                      {"width", job.spec.settings.width},
                      {"height", job.spec.settings.height},
                      {"level", stage.level > 0 ? stage.level : job.plan.levels},
                      {"levels", job.plan.levels},
                      {"pass", stage.pass},
                      {"passes", job.spec.settings.passes},
                      {"progress", progress},
                      {"percent", 100.0 * progress},
                      {"elapsed_seconds", job.elapsed_seconds(now)},
                      {"version", job.version()},
                      {"priority", job.priority}};
  const auto eta = job.eta_seconds(now);
  j["eta_seconds"] = eta ? nlohmann::json(*eta) : nlohmann::json(nullptr);
  j["predicted_seconds"] =
      job.predicted_seconds ? nlohmann::json(*job.predicted_seconds) : nlohmann::json(nullptr);
  if (!job.error().empty()) j["error"] = job.error();
  return j;
}

nlohmann::json job_settings_json(const Job& job) {
  nlohmann::json settings = to_json(job.spec);
  settings["order"] = to_string(job.plan_options.order);
  settings["preview"] = to_string(job.plan_options.preview);
  settings["progressive"] = job.plan_options.progressive;
  settings["priority"] = job.priority;
  return settings;
}

nlohmann::json job_status_json(const Job& job, Clock::time_point now) {
  nlohmann::json j = job_summary_json(job, now);
  j["settings"] = job_settings_json(job);
  j["stage"] = job.current_stage();
  j["levels_table"] = levels_table(job, now);
  j["effects"] = job.effects;
  j["warnings"] = job.warnings();
  j["stats"] = to_json(job.stats());
  j["tiles"] = job.tiles_next();
  j["scene"] = job.bundle->main;
  // The camera the page navigates from; its fov is the format's angle (docs/SERVICE.md).
  j["format"] = job.bundle->format;
  j["camera"] = job.camera ? camera_to_json(*job.camera) : nlohmann::json(nullptr);
  nlohmann::json viewpoints = nlohmann::json::array();
  for (const NamedCamera& v : job.viewpoints)
    viewpoints.push_back({{"name", v.name}, {"camera", camera_to_json(v.camera)}});
  j["viewpoints"] = viewpoints;
  nlohmann::json workers = nlohmann::json::array();
  for (const auto& [id, share] : job.shares())
    workers.push_back({{"id", id},
                       {"name", share.name},
                       {"units", share.units},
                       {"pixels", share.pixels},
                       {"seconds", share.seconds},
                       {"share", job.done_cost() > 0 ? static_cast<double>(share.pixels) /
                                                           static_cast<double>(job.done_cost())
                                                     : 0.0}});
  j["workers"] = workers;
  return j;
}

}  // namespace tessera
