// GET /api/jobs/{id}/image through the Api on its io thread, with the intake pool held: a
// done job's final image is made and encoded on the pool, and requests meanwhile wait for it.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <future>
#include <optional>
#include <string>

#include <boost/asio/executor_work_guard.hpp>

#include "coordinator/http/api.h"

namespace tessera {
namespace {

namespace http = boost::beast::http;

// A distinct value per pixel and pass, as a worker would return it.
void merge(Job& job, int unit) {
  std::vector<float> values;
  const int pass = job.plan.stages[job.plan.units[unit].stage].pass;
  for (PixelCoord p : expand(job.plan.units[unit].pixels))
    for (int c = 0; c < 3; ++c)
      values.push_back(static_cast<float>(p.x + 8 * p.y + 3 * pass + c) / 80.0f);
  job.apply_result(unit, values, RenderStats{});
}

std::string body_of(const HttpResponse& response) {
  return {response.body().data(), response.body().size()};
}

struct ApiWithHeldPool : ::testing::Test {
  boost::asio::io_context io;
  // The io thread (this one) waits for the pool's results rather than stopping when idle.
  boost::asio::executor_work_guard<boost::asio::io_context::executor_type> waits_for_pool =
      boost::asio::make_work_guard(io);
  JobStore jobs{4};
  Scheduler scheduler{SchedulerOptions{}};
  MetricsRegistry registry;
  ServiceMetrics metrics{registry};
  IntakePool pool{io, 1, 9};
  Api api{io, jobs, scheduler, pool, metrics, ApiConfig{}};
  // Set by the test; else broken when the fixture ends (first: the pool's thread is joined).
  std::promise<void> release;

  Job& make_job() {
    JobRequest r;
    r.bundle = {"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}};
    r.spec.settings.width = r.plan.width = 8;
    r.spec.settings.height = r.plan.height = 8;
    r.spec.settings.passes = r.plan.passes = 2;
    Job* job = jobs.create(std::move(r), "10.0.0.7");
    api.watch(*job);
    return *job;
  }
  // The pool's one thread waits until release is set.
  void hold_pool() {
    pool.submit([held = release.get_future().share()] {
      held.wait();
      return std::function<void()>();
    });
  }
  // Asks for the job's image; `answer` is set once the Api responds (run_until).
  void ask(const Job& job, std::optional<HttpResponse>& answer, const std::string& format) {
    HttpRequest request{http::verb::get,
                        "/api/jobs/" + std::to_string(job.id) + "/image?format=" + format, 11};
    api.handle(std::move(request), {}, [&answer](HttpResponse r) { answer = std::move(r); });
  }
  void run_until(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!done() && std::chrono::steady_clock::now() < deadline)
      io.run_one_for(std::chrono::milliseconds(50));
  }
};

TEST_F(ApiWithHeldPool, ARequestWhileTheFinalImageIsMadeGetsTheFinalImage) {
  Job& job = make_job();
  merge(job, 0);
  std::optional<HttpResponse> preview;
  ask(job, preview, "png");
  run_until([&] { return preview.has_value(); });
  ASSERT_TRUE(preview);
  ASSERT_EQ(preview->result_int(), 200u);

  for (int u = 1; u < static_cast<int>(job.plan.units.size()); ++u) merge(job, u);
  const Image final_image = job.frame_buffer().resolve();
  hold_pool();
  job.finish(JobState::Done, "", Clock::now());  // its final image queued behind the held task
  std::optional<HttpResponse> answer, exr;
  ask(job, answer, "png");
  ask(job, exr, "exr");
  io.poll();
  EXPECT_FALSE(answer) << "answered before the final image was made: " << body_of(*answer);
  EXPECT_FALSE(exr);
  EXPECT_TRUE(job.final_encoded().empty());

  release.set_value();
  run_until([&] { return answer.has_value(); });
  ASSERT_TRUE(answer);
  ASSERT_EQ(answer->result_int(), 200u);
  run_until([&] { return !job.final_encoded().empty(); });  // the EXR too, then kept
  ASSERT_EQ(job.final_encoded().count("png"), 1u);
  EXPECT_EQ(body_of(*answer), *job.final_encoded().at("png"));
  EXPECT_NE(body_of(*answer), body_of(*preview));
  EXPECT_EQ(std::string((*answer)[http::field::etag]),
            "\"" + std::to_string(job.id) + "-" + std::to_string(job.version()) + "-png\"");
  EXPECT_EQ(body_of(*answer), encode_image(final_image, "png"));
  ASSERT_TRUE(exr);
  EXPECT_EQ(body_of(*exr), encode_image(final_image, "exr"));
}

}  // namespace
}  // namespace tessera
