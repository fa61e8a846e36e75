// What the job store keeps of a job, as plain records: the request as submitted, its state,
// the merged unit results in merge order and the names of its final images. Independent of
// coordinator/jobs/job.h on purpose: the in-memory job and its stored form change separately,
// and the coordinator converts between them in one place.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/progressive/plan.h"
#include "common/protocol/bundle.h"
#include "common/protocol/job_spec.h"
#include "common/scene/camera.h"
#include "common/stats/render_stats.h"

namespace tessera {

using WallClock = std::chrono::system_clock;  // stored times: for retention across restarts

// A job as submitted. The bundle is stored once per content hash, under bundles/<hash>.
struct StoredRequest {
  Bundle bundle;
  JobSpec spec;  // stored as the JSON of to_json(JobSpec)
  PlanOptions plan;
  int priority = 1;
  std::vector<std::string> effects, warnings;
  // The prediction made at submission (issue 5).
  double seconds_per_pixel_pass = 0;
  std::optional<double> uncalibrated_prediction, predicted_seconds;
  int prediction_threads = 0;
  // The loaded scene's camera (the camera setting's when given) and VRML's Viewpoints, which a
  // job's status shows for the page's navigation. A job stored by schema version 1 has none.
  std::optional<Camera> camera;
  std::vector<NamedCamera> viewpoints;
};

// One merged unit result. Replaying a job's results in sequence order into a fresh frame
// buffer gives bit-identical values: the floats are stored as their exact bytes.
struct StoredResult {
  std::int64_t sequence = 0;  // 0, 1, 2... per job, in merge order
  int unit = 0;
  std::vector<float> values;  // 3 floats per pixel of the unit, as merged
  RenderStats stats;
  std::string worker;
};

// A final encoded image of a finished job, e.g. {"image.png", bytes}.
struct StoredImage {
  std::string name;  // a plain file name: letters, digits, '.', '-', '_'; not starting with '.'
  std::string bytes;
};

struct StoredJob {
  std::int64_t id = 0;
  StoredRequest request;
  // The coordinator's vocabulary (to_string(JobState)); the store only needs `finished` to know
  // which jobs retention may delete.
  std::string state;
  std::string error;
  WallClock::time_point created;                  // kept to the microsecond
  std::optional<WallClock::time_point> finished;  // set once the job is done, failed or cancelled
  std::vector<StoredResult> results;              // in sequence order
  std::vector<std::string> images;                // names; the bytes are files (image_path)
};

// One row of a listing: the job without its request and results.
struct JobListing {
  std::int64_t id = 0;
  std::string state, error;
  WallClock::time_point created;
  std::optional<WallClock::time_point> finished;
  std::int64_t results = 0;
};

}  // namespace tessera
