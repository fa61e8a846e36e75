// The HTTP API of docs/SERVICE.md and the static page over the job store and the scheduler.
// Light routes answer at once on the io thread; submissions, predictions and image encodings
// go to the intake pool under a budget, and their results come back to the io thread.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include "coordinator/http/http_server.h"
#include "coordinator/http/intake_pool.h"
#include "coordinator/http/submit_policy.h"
#include "coordinator/jobs/job_persistence.h"
#include "coordinator/jobs/job_store.h"
#include "coordinator/jobs/limits.h"
#include "coordinator/metrics/service_metrics.h"
#include "coordinator/scheduler/scheduler.h"

namespace tessera {

struct ApiConfig {
  ServiceLimits limits;
  std::optional<std::filesystem::path> scenes_dir;
  std::filesystem::path web_dir;
  SubmitPolicy submit;
  double max_intake_seconds = 10;         // wall time of one submission or prediction
  int max_jobs_per_client = 8;            // unfinished jobs per peer address
  JobPersistence* persistence = nullptr;  // the durable store; jobs live in memory only without
};

class Api {
 public:
  Api(boost::asio::io_context& io, JobStore& jobs, Scheduler& scheduler, IntakePool& pool,
      ServiceMetrics& metrics, ApiConfig config)
      : io_(io),
        jobs_(jobs),
        scheduler_(scheduler),
        pool_(pool),
        metrics_(metrics),
        config_(std::move(config)) {}
  // On the io thread; `respond` is called once, at once or when the pool's work is done.
  void handle(HttpRequest request, const boost::asio::ip::tcp::endpoint& peer, HttpRespond respond);
  // Sets the job's on_released and on_changed to the two below; every job, restored ones too.
  void watch(Job& job);
  // A job has freed its buffers: a done one's final image is made and encoded on the pool (and
  // stored); until then requests for its image wait for that encoding.
  void on_released(Job& job);
  // A job merged a unit or finished: the long polls waiting for its tiles are answered (posted,
  // so that the merge's other bookkeeping comes first).
  void on_changed(Job& job);

 private:
  using Query = std::map<std::string, std::string>;
  // What heavy work leaves for the io thread: it makes the response there.
  using Finish = std::function<HttpResponse()>;

  void route(HttpRequest& request, const std::string& path, const Query& query,
             const std::string& client, HttpRespond& respond);
  void create_job(HttpRequest& request, const Query& query, const std::string& client,
                  HttpRespond& respond);
  // POST /api/jobs/{id}/rerender: a new job of `job`'s bundle and settings, the body's
  // settings over them.
  void rerender(HttpRequest& request, const Job& job, const std::string& client,
                HttpRespond& respond);
  // The intake both share: the per-client cap, `read` and admission on the pool under a
  // budget, then the job created and scheduled on the io thread; 201 with its status.
  void submit_job(const std::string& client, HttpRespond& respond,
                  std::function<Submission()> read);
  // The time a job would take, without submitting it (the page asks as settings change).
  void predict(HttpRequest& request, const Query& query, HttpRespond& respond);
  void job_image(const HttpRequest& request, Job& job, const Query& query, HttpRespond& respond);
  // Answers the requests waiting for `key`'s encoding of `version` (a superseded one answers
  // none) with `bytes`, null when it failed; keeps the bytes for the next requests or not.
  void encoded(const std::pair<std::int64_t, std::string>& key, std::uint64_t version,
               std::shared_ptr<const std::string> bytes, bool keep);
  // GET /api/jobs/{id}/tiles?since=N[&wait=MS]: answered at once when units merged since the
  // N-th (or the job is finished), else held until one merges or MS pass.
  void job_tiles(const HttpRequest& request, Job& job, const Query& query, HttpRespond& respond);
  void answer_tile_waiters(std::int64_t job_id);
  HttpResponse static_file(const std::string& path);
  // Runs `work` on the pool under a deadline of --max-intake-seconds: 503 when the pool's
  // queue is full, 422 when the deadline passes first (the late result is then dropped).
  void offload(HttpRespond respond, std::function<Finish(const IntakeBudget&)> work);

  boost::asio::io_context& io_;
  JobStore& jobs_;
  Scheduler& scheduler_;
  IntakePool& pool_;
  ServiceMetrics& metrics_;
  ApiConfig config_;
  // The last encoding per job and format (polling pages ask for the same version many
  // times); requests for a version being encoded wait for that one encoding, a done job's
  // final one included.
  struct Encoding {
    std::uint64_t version = 0;
    bool encoding = false;                     // on the pool now
    std::shared_ptr<const std::string> bytes;  // null while encoding
    // Each gets the bytes (null when the image is gone) and the version they show.
    std::vector<std::function<void(std::shared_ptr<const std::string>, std::uint64_t)>> waiting;
  };
  std::map<std::pair<std::int64_t, std::string>, Encoding> encoded_;
  // Long polls of /tiles, by job: each is answered once, by a merge or by its timer.
  struct TilesWaiter {
    std::size_t since = 0;
    bool gzip = false;
    HttpRespond respond;
    std::unique_ptr<boost::asio::steady_timer> timer;
  };
  std::map<std::int64_t, std::vector<std::shared_ptr<TilesWaiter>>> tile_waiters_;
};

// "/a/b?x=1&y=%20" -> path "/a/b" and {x: "1", y: " "}.
std::pair<std::string, std::map<std::string, std::string>> split_target(std::string_view target);

}  // namespace tessera
