#include "worker/render_loop/render_loop.h"

#include <atomic>
#include <chrono>
#include <optional>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "common/loaders/scene_loader.h"
#include "common/render/prepared_scene.h"
#include "common/render/render.h"

namespace tessera {

namespace {
constexpr std::size_t kCachedBundles = 8;
}

// A job as this worker holds it: the bundle, and the scene prepared once, on first use.
// `cancelled` is also the flag its units' renders poll (render/interrupt.h), so cancel_job and
// clear() stop a unit in the middle of a pixel.
struct PreparedJob {
  std::int64_t id = 0;
  JobSpec spec;
  std::shared_ptr<const Bundle> bundle;
  std::atomic<bool> cancelled{false};
  std::atomic<bool> failure_reported{false};
  std::once_flag prepare_once;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<PreparedScene> prepared;
  std::string error;  // set when preparing failed

  // `threads`: the render threads, which wait for the preparation anyway (the BVH build uses them).
  void prepare(int threads) {
    std::call_once(prepare_once, [this, threads] {
      try {
        MemorySource source(bundle->files);
        const std::optional<SceneFormat> format = scene_format_named(bundle->format);
        if (!format) throw std::runtime_error("unknown scene format \"" + bundle->format + "\"");
        // Cancelling stops a long load as it stops a render.
        LoadBudget budget;
        budget.cancel = &cancelled;
        scene = std::make_unique<Scene>(
            load_scene(source, bundle->main, *format, budget, spec.overrides.camera));
        if (cancelled) return;  // the job went while loading: skip building its BVH
        apply_overrides(*scene, spec.overrides);
        prepared = std::make_unique<PreparedScene>(*scene, spec.settings.bvh, threads);
      } catch (const std::exception& e) {
        error = e.what();
      }
    });
  }
};

RenderLoop::RenderLoop(int threads, ReportSink sink) : sink_(std::move(sink)) {
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { run(); });
}

RenderLoop::~RenderLoop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, job] : jobs_) job->cancelled = true;  // stops the units being traced
    queue_.clear();
  }
  wake_.notify_all();
  for (auto& t : threads_) t.join();
}

std::vector<std::string> RenderLoop::cached_hashes() const {
  std::lock_guard lock(mutex_);
  return {bundle_order_.begin(), bundle_order_.end()};
}

bool RenderLoop::open_job(std::int64_t job, const JobSpec& spec, const std::string& hash,
                          std::optional<Bundle> bundle) {
  std::lock_guard lock(mutex_);
  auto cached = bundles_.find(hash);
  std::shared_ptr<const Bundle> files;
  if (bundle) {
    files = std::make_shared<const Bundle>(std::move(*bundle));
    if (cached == bundles_.end()) {
      bundles_[hash] = files;
      bundle_order_.push_back(hash);
      if (bundle_order_.size() > kCachedBundles) {
        bundles_.erase(bundle_order_.front());
        bundle_order_.pop_front();
      }
    }
  } else if (cached != bundles_.end()) {
    files = cached->second;
  } else {
    return false;
  }
  auto prepared = std::make_shared<PreparedJob>();
  prepared->id = job;
  prepared->spec = spec;
  prepared->bundle = std::move(files);
  jobs_[job] = std::move(prepared);
  return true;
}

void RenderLoop::add_unit(std::int64_t job, std::int64_t unit, int pass, const UnitPixels& pixels) {
  {
    std::lock_guard lock(mutex_);
    auto it = jobs_.find(job);
    if (it == jobs_.end()) return;  // cancelled meanwhile
    queue_.push_back({it->second, unit, pass, pixels});
  }
  wake_.notify_one();
}

void RenderLoop::cancel_job(std::int64_t job) {
  std::lock_guard lock(mutex_);
  auto it = jobs_.find(job);
  if (it == jobs_.end()) return;
  it->second->cancelled = true;
  jobs_.erase(it);
  std::erase_if(queue_, [&](const Task& t) { return t.job->id == job; });
}

void RenderLoop::clear() {
  std::lock_guard lock(mutex_);
  for (auto& [id, job] : jobs_) job->cancelled = true;
  jobs_.clear();
  queue_.clear();
}

void RenderLoop::run() {
  for (;;) {
    Task task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    if (!task.job->cancelled) render(task);
  }
}

void RenderLoop::render(const Task& task) {
  PreparedJob& job = *task.job;
  job.prepare(static_cast<int>(threads_.size()));
  if (job.cancelled) return;
  if (!job.prepared) {
    if (!job.failure_reported.exchange(true)) {
      spdlog::warn("job {}: {}", job.id, job.error);
      sink_(JobFailedMessage{.job = job.id, .error = job.error});
    }
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<PixelCoord> pixels = expand(task.pixels);
  std::vector<Rgb> colours(pixels.size());
  RenderStats stats;
  try {
    render_pixels(*job.prepared, job.spec.settings, pixels, task.pass, colours, stats,
                  {.cancel = &job.cancelled});
  } catch (const RenderInterrupted&) {
    return;  // cancelled: the coordinator expects nothing more of this job
  } catch (const std::exception& e) {
    if (!job.failure_reported.exchange(true))
      sink_(JobFailedMessage{.job = job.id, .error = e.what()});
    return;
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Pass values travel as float32, the precision the frame buffer accumulates (frame_buffer.h).
  FloatValues values;
  values.reserve(colours.size() * 3);
  for (const Rgb& c : colours) {
    values.push_back(static_cast<float>(c.r));
    values.push_back(static_cast<float>(c.g));
    values.push_back(static_cast<float>(c.b));
  }
  if (job.cancelled) return;
  sink_(
      ResultMessage{.job = job.id, .unit = task.unit, .stats = stats, .values = std::move(values)});
}

}  // namespace tessera
