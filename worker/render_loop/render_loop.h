// The worker's render loop: bundles cached by content hash, one prepared scene per job (built
// by the first unit that needs it), and a pool of render threads tracing units. Public members
// are called from the session's thread; what the units come to (a result, or the job's failure)
// leaves through `ReportSink` on render threads, and the session sends it.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "common/progressive/unit_pixels.h"
#include "common/protocol/bundle.h"
#include "common/protocol/job_spec.h"
#include "common/protocol/messages.h"

namespace tessera {

struct PreparedJob;

class RenderLoop {
 public:
  using Report = std::variant<ResultMessage, JobFailedMessage>;
  using ReportSink = std::function<void(Report)>;
  RenderLoop(int threads, ReportSink sink);
  ~RenderLoop();
  RenderLoop(const RenderLoop&) = delete;
  RenderLoop& operator=(const RenderLoop&) = delete;

  std::vector<std::string> cached_hashes() const;
  // Opens a job with its bundle, or with the cached bundle of that hash when `bundle` is
  // empty. Returns false when neither is available.
  bool open_job(std::int64_t job, const JobSpec& spec, const std::string& hash,
                std::optional<Bundle> bundle);
  void add_unit(std::int64_t job, std::int64_t unit, int pass, const UnitPixels& pixels);
  void cancel_job(std::int64_t job);
  // The connection is gone: every job and queued unit goes with it (the coordinator re-queues).
  void clear();

 private:
  struct Task {
    std::shared_ptr<PreparedJob> job;
    std::int64_t unit;
    int pass;
    UnitPixels pixels;
  };
  void run();
  void render(const Task& task);

  ReportSink sink_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::deque<Task> queue_;
  std::map<std::int64_t, std::shared_ptr<PreparedJob>> jobs_;
  std::map<std::string, std::shared_ptr<const Bundle>> bundles_;
  std::list<std::string> bundle_order_;  // oldest first, for eviction
  std::vector<std::thread> threads_;
};

}  // namespace tessera
