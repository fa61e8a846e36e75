// tessera-coordinator: the HTTP API and page, the job store and the scheduler, and the port
// workers connect to (docs/SERVICE.md). One io thread does the I/O and owns the jobs and the
// scheduler; scene intake and image encoding run on a small pool (IntakePool).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <malloc.h>

#include <spdlog/spdlog.h>
#include <boost/asio/signal_set.hpp>
#include <nlohmann/json.hpp>

#include "common/protocol/handshake.h"
#include "common/protocol/tls.h"
#include "coordinator/http/api.h"
#include "coordinator/jobs/idle_memory.h"
#include "coordinator/metrics/service_metrics.h"
#include "coordinator/options.h"
#include "coordinator/workers/local_workers.h"
#include "coordinator/workers/worker_link.h"

namespace {

// Every 250 ms: time limits and speculation, then the merged results written to the store
// (a crash loses at most this much work) and retention; freed memory kept for the next job goes
// back to the system once idle (idle_memory.h).
void tick_every(boost::asio::steady_timer& timer, tessera::Scheduler& scheduler,
                tessera::JobStore& jobs, tessera::JobPersistence& persistence,
                tessera::IdleMemory& idle_memory) {
  timer.expires_after(std::chrono::milliseconds(250));
  timer.async_wait([&](boost::system::error_code ec) {
    if (ec) return;
    scheduler.tick();
    persistence.tick(jobs, scheduler);
    idle_memory.tick(scheduler.has_unfinished_jobs(), tessera::IdleMemory::Clock::now());
    tick_every(timer, scheduler, jobs, persistence, idle_memory);
  });
}

// Written to a temporary name and renamed, so a reader never sees half a file.
void write_port_file(const std::filesystem::path& path, unsigned short http_port,
                     unsigned short worker_port) {
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial);
    out << nlohmann::json{{"http_port", http_port}, {"worker_port", worker_port}}.dump() << "\n";
    if (!out) throw std::runtime_error("cannot write " + partial.string());
  }
  std::filesystem::rename(partial, path);
}

// Every merged unit's values (up to 786 kB) are allocated on the io thread and freed by the
// store's thread once written, a few hundred at a time. With glibc's defaults the freed heap
// went back to the system whenever more than twice the largest such buffer lay free at its top,
// and the next results faulted it in again, zeroed: 6,000-16,000 page faults a 2048x2048 job on
// the io thread (docs/SCALING.md). Buffers below 1 MB come from the heap, and what is freed
// stays until the coordinator is idle (idle_memory.h). Not only up to 64 MB: the store writes
// a tick's results (250 ms of them, 75 MB when workers return 25 M pixel passes a second) and
// frees them at once, so a 64 MB limit gave the rest back and the next tick's results faulted
// it in again (up to 32,000 page faults a later job). Trimming then never lowered the peak, which
// the next tick reaches again.
void keep_freed_heap() {
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tessera;
  namespace asio = boost::asio;
  keep_freed_heap();
  const auto parsed = parse_coordinator_options(std::vector<std::string>(argv + 1, argv + argc));
  if (std::holds_alternative<CoordinatorHelp>(parsed)) {
    std::fputs(coordinator_usage().c_str(), stdout);
    return 0;
  }
  if (const auto* error = std::get_if<std::string>(&parsed)) {
    spdlog::error("{} (tessera-coordinator --help lists the options)", *error);
    return 2;
  }
  CoordinatorOptions options = std::get<CoordinatorOptions>(parsed);
  if (options.secret.empty() && !options.insecure) {
    // Authentication is off only when asked for; local workers get this one by environment.
    options.secret = make_nonce();
    spdlog::warn("no --secret given: remote workers cannot join (local workers can)");
  }
  try {
    asio::io_context io;
    JobStore jobs(options.limits.max_jobs);
    MetricsRegistry registry;
    ServiceMetrics metrics(registry);
    Scheduler scheduler({.max_job_seconds = options.limits.max_job_seconds, .metrics = &metrics});
    registry.add_collector([&] {
      std::map<JobState, int> by_state;
      for (JobState state : {JobState::Queued, JobState::Running, JobState::Done, JobState::Failed,
                             JobState::Cancelled})
        by_state[state] = 0;
      for (const auto& [id, job] : jobs.all()) ++by_state[job->state()];
      for (const auto& [state, count] : by_state) metrics.jobs.with({to_string(state)}).set(count);
      const Scheduler::WorkerTotals totals = scheduler.worker_totals();
      metrics.workers.set(totals.workers);
      metrics.worker_threads.set(totals.threads);
    });
    JobPersistence persistence(options.data_dir, options.keep_finished, options.max_disk_bytes);
    scheduler.set_observer(&persistence);
    registry.add_collector([&] {
      try {
        metrics.store_bytes.set(static_cast<double>(persistence.size_bytes()));
      } catch (const StoreError& e) {
        spdlog::error("job store size: {}", e.cause());  // the gauge keeps its last value
      }
    });
    const auto address = asio::ip::make_address(options.bind);
    const auto tls = options.tls_cert ? make_server_tls(*options.tls_cert, *options.tls_key)
                                      : nullptr;  // both ports plain
    if (!tls && !address.is_loopback())
      spdlog::warn(
          "no --tls-cert: the worker port and the API on {} are plaintext; anyone on the "
          "path can read scenes and images and alter results (docs/SECURITY.md)",
          options.bind);
    WorkerListener workers(io, {address, options.worker_port}, {options.secret, options.insecure},
                           scheduler, options.timing, {}, tls);
    workers.observe_traffic(
        [&metrics](bool sent, std::optional<MessageType> type, std::size_t bytes) {
          metrics.count_worker_frame(sent, type, bytes);
        });
    // A few submissions may wait for a thread; beyond that they get 503 at once.
    IntakePool intake(io, options.intake_threads, options.intake_threads + 8);
    Api api(io, jobs, scheduler, intake, metrics,
            {options.limits, options.scenes_dir, options.web_dir, options.submit,
             static_cast<double>(options.max_intake_seconds), options.max_jobs_per_client,
             &persistence});
    persistence.restore(jobs, scheduler, [&api](Job& job) { api.watch(job); });
    HttpServer http(
        io, {address, options.http_port},
        {options.limits.max_body_bytes, options.max_http_connections, tls},
        [&api](HttpRequest r, const asio::ip::tcp::endpoint& peer, HttpRespond respond) {
          api.handle(std::move(r), peer, std::move(respond));
        });
    spdlog::info("page and API at {}://{}:{}/ ; workers connect to port {}{}",
                 tls ? "https" : "http", options.bind, http.port(), workers.port(),
                 tls ? " with TLS" : "");
    if (options.port_file) write_port_file(*options.port_file, http.port(), workers.port());
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int threads = options.local_threads > 0
                            ? options.local_threads
                            : std::max(1, cores / std::max(1, options.local_workers));
    LocalWorkers local(options.worker_binary, options.local_workers, threads, workers.port(),
                       options.insecure ? "" : options.secret, tls != nullptr);
    asio::signal_set signals(io, SIGINT, SIGTERM);
    signals.async_wait([&](boost::system::error_code, int) { io.stop(); });
    asio::steady_timer timer(io);
    IdleMemory idle_memory;
    tick_every(timer, scheduler, jobs, persistence, idle_memory);
    io.run();
    // A graceful stop writes what merged since the last tick: only a crash loses it.
    persistence.write_out();
    if (intake.pending() > 0) {
      // A runaway scene would hold the exit until its budget stops it: leave without it
      // (local workers get SIGTERM from the kernel as we exit, PR_SET_PDEATHSIG).
      spdlog::warn("stopping with {} requests still in intake", intake.pending());
      spdlog::shutdown();
      std::_Exit(0);
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
