// POST /api/jobs: turns a request body into a validated job request, or an ApiError with the
// right status (422/413 over its IntakeBudget). The scene is parsed and prepared here, so a bad
// scene is a 400 that never reaches a worker; the bundle keeps exactly the files the scene read.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/progressive/plan.h"
#include "common/protocol/bundle.h"
#include "common/protocol/job_spec.h"
#include "coordinator/jobs/intake_budget.h"
#include "coordinator/jobs/limits.h"

namespace tessera {

struct JobRequest {
  Bundle bundle;
  JobSpec spec;
  PlanOptions plan;
  int priority = 1;
  std::vector<std::string> effects, warnings;
  double seconds_per_pixel_pass = 0;  // measured by a probe on the coordinator (issue 5)
  bool probe_cut_short = false;       // the probe hit its deadline: the cost is a lower bound
  bool strict = false;  // settings.strict: what loading warns about is a 400 (LoadBudget::strict)
  // The loaded scene's camera (the camera setting's when given) and VRML's Viewpoints, for the
  // page's navigation; a job restored from the store knows only its camera setting.
  std::optional<Camera> camera;
  std::vector<NamedCamera> viewpoints;
};

struct JobUpload {
  std::string_view body;
  std::string_view content_type;
  std::map<std::string, std::string> query;  // settings for tar uploads
};

// Runs off the io thread (IntakePool); the budget is checked between its stages.
JobRequest parse_job_request(const JobUpload& upload, const ServiceLimits& limits,
                             const std::optional<std::filesystem::path>& scenes_dir,
                             const IntakeBudget& budget = {});

// The settings object of a request ({"width", "height", "aa", ...}); throws ApiError.
void parse_settings(const nlohmann::json& settings, const ServiceLimits& limits, JobRequest& out);

}  // namespace tessera
