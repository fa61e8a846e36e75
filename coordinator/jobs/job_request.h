// Admission of a job: turns a submission (its files and settings, decoded from the request by
// coordinator/http/submission.h) into a validated job request, or an ApiError with the right
// refusal (unprocessable or too large over its IntakeBudget). The scene is parsed and prepared
// here, so a bad scene is a bad request that never reaches a worker; the bundle keeps exactly
// the files the scene read.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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
  bool strict = false;  // settings.strict: what loading warns about is refused (LoadBudget::strict)
  // The loaded scene's camera (the camera setting's when given) and VRML's Viewpoints, for the
  // page's navigation; kept in the store with the job (a job stored by schema version 1 has
  // neither, and shows its camera setting if any).
  std::optional<Camera> camera;
  std::vector<NamedCamera> viewpoints;
};

// What a request submits, whatever its content type.
struct Submission {
  std::map<std::string, std::string> files;  // bundle path -> bytes
  std::string main;                          // the scene file's bundle path
  std::string format = "sdl";                // "sdl" or "vrml"
  nlohmann::json settings = nlohmann::json::object();
};

// Runs off the io thread (IntakePool); the budget is checked between its stages.
JobRequest admit_job(const Submission& submission, const ServiceLimits& limits,
                     const std::optional<std::filesystem::path>& scenes_dir,
                     const IntakeBudget& budget = {});

// At admission, on the io thread where the connected `threads` are known: the request's units
// cut smaller so that a pass keeps the threads busy (unit_pixels_for_threads, plan.h).
void fit_units_to_threads(JobRequest& request, int threads);

// The settings object of a request ({"width", "height", "aa", ...}); throws ApiError.
void parse_settings(const nlohmann::json& settings, const ServiceLimits& limits, JobRequest& out);

}  // namespace tessera
