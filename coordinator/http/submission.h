// POST /api/jobs bodies: a JSON object, a tar bundle or a multipart form, and POST
// /api/jobs/{id}/rerender bodies over an earlier job, each decoded into the same Submission (files,
// main file, format, settings) that admission checks (coordinator/jobs/job_request.h). Malformed
// bodies are a 400 or 415 ApiError naming what is wrong; nothing here reads the scene.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "common/protocol/bundle.h"
#include "coordinator/jobs/intake_budget.h"
#include "coordinator/jobs/job_request.h"
#include "coordinator/jobs/limits.h"

namespace tessera {

struct JobUpload {
  std::string_view body;
  std::string_view content_type;
  std::map<std::string, std::string> query;  // settings for tar uploads
};

// `scenes_dir`: the coordinator's --scenes-dir, which a JSON body's "scene_file" names into.
Submission read_submission(const JobUpload& upload,
                           const std::optional<std::filesystem::path>& scenes_dir);

// A rerender's body, `{"settings": {...}}` (empty: `{}`), over a job's bundle and settings (its
// job_settings_json): each setting given replaces the job's, and null drops it (its default,
// or for an override the scene's own). Copies the bundle: call it off the io thread.
Submission read_rerender(std::string_view body, const Bundle& bundle, nlohmann::json settings);

// The whole intake of one request: read_submission, then admit_job. Off the io thread.
JobRequest parse_job_request(const JobUpload& upload, const ServiceLimits& limits,
                             const std::optional<std::filesystem::path>& scenes_dir,
                             const IntakeBudget& budget = {});

}  // namespace tessera
