// The HTTP API of docs/SERVICE.md and the static page: a function from request to response
// over the job store and the scheduler.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "coordinator/http/http_server.h"
#include "coordinator/jobs/job_store.h"
#include "coordinator/jobs/limits.h"
#include "coordinator/scheduler/scheduler.h"

namespace tessera {

struct ApiConfig {
  ServiceLimits limits;
  std::optional<std::filesystem::path> scenes_dir;
  std::filesystem::path web_dir;
};

class Api {
 public:
  Api(JobStore& jobs, Scheduler& scheduler, ApiConfig config)
      : jobs_(jobs), scheduler_(scheduler), config_(std::move(config)) {}
  HttpResponse handle(const HttpRequest& request);

 private:
  HttpResponse route(const HttpRequest& request, const std::string& path,
                     const std::map<std::string, std::string>& query);
  HttpResponse create_job(const HttpRequest& request,
                          const std::map<std::string, std::string>& query);
  // The time a job would take, without submitting it (the page asks as settings change).
  HttpResponse predict(const HttpRequest& request, const std::map<std::string, std::string>& query);
  HttpResponse job_image(const HttpRequest& request, const Job& job,
                         const std::map<std::string, std::string>& query);
  HttpResponse static_file(const std::string& path);

  JobStore& jobs_;
  Scheduler& scheduler_;
  ApiConfig config_;
  // The last encoding per job and format: polling pages ask for the same version many times.
  struct EncodedImage {
    std::uint64_t version = 0;
    std::string bytes;
  };
  std::map<std::pair<std::int64_t, std::string>, EncodedImage> encoded_;
};

// "/a/b?x=1&y=%20" -> path "/a/b" and {x: "1", y: " "}.
std::pair<std::string, std::map<std::string, std::string>> split_target(std::string_view target);

}  // namespace tessera
