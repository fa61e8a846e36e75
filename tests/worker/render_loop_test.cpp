// The worker's render loop on its own: the bundle cache (a second job of the same hash opens
// without its bundle, the ninth bundle evicts the oldest, a job whose bundle is neither sent
// nor cached does not open: the session answers that with missing_bundle) and cancel (its
// queued units are dropped and no result of the job follows).
#include "worker/render_loop/render_loop.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace tessera {
namespace {

using namespace std::chrono_literals;

// A bundle per index: the same scene with a different comment, so each has its own hash.
Bundle bundle(int index) {
  return {"scene.sdl", "sdl", {{"scene.sdl", "! bundle " + std::to_string(index) + "\nsphere\n"}}};
}

JobSpec spec(int size, int aa_samples = 1) {
  JobSpec s;
  s.settings.width = s.settings.height = size;
  s.settings.aa_samples = aa_samples;
  return s;
}

UnitPixels whole_image(int size) { return {.rect = {0, 0, size, size}}; }

using Report = RenderLoop::Report;

std::int64_t job_of(const Report& report) {
  return std::visit([](const auto& message) { return message.job; }, report);
}

// Collects what the loop reports; render threads call it.
class Sink {
 public:
  RenderLoop::ReportSink callback() {
    return [this](Report r) {
      std::lock_guard lock(mutex_);
      reports_.push_back(std::move(r));
      arrived_.notify_all();
    };
  }
  // Waits until `count` reports arrived (or 10 s passed); returns all of them.
  std::vector<Report> wait_for(std::size_t count) {
    std::unique_lock lock(mutex_);
    arrived_.wait_for(lock, 10s, [&] { return reports_.size() >= count; });
    return reports_;
  }
  std::vector<Report> now() {
    std::lock_guard lock(mutex_);
    return reports_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::vector<Report> reports_;
};

TEST(RenderLoopBundles, ASecondJobOfTheSameHashOpensWithoutItsBundle) {
  Sink sink;
  RenderLoop loop(1, sink.callback());
  const std::string hash = content_hash(bundle(0));
  ASSERT_TRUE(loop.open_job(1, spec(4), hash, bundle(0)));
  EXPECT_EQ(loop.cached_hashes(), std::vector<std::string>{hash});
  ASSERT_TRUE(loop.open_job(2, spec(4), hash, std::nullopt));
  loop.add_unit(2, 0, 0, whole_image(4));
  const std::vector<Report> reports = sink.wait_for(1);
  ASSERT_EQ(reports.size(), 1u);
  const auto* result = std::get_if<ResultMessage>(&reports[0]);
  ASSERT_TRUE(result);
  EXPECT_EQ(result->job, 2);
  EXPECT_EQ(result->values.size(), 16u * 3);
  EXPECT_EQ(result->stats.pixels, 16u);
}

TEST(RenderLoopBundles, AnUnknownHashWithoutItsBundleDoesNotOpen) {
  Sink sink;
  RenderLoop loop(1, sink.callback());
  EXPECT_FALSE(loop.open_job(1, spec(4), content_hash(bundle(0)), std::nullopt));
  loop.add_unit(1, 0, 0, whole_image(4));  // a unit of a job not open is dropped
  std::this_thread::sleep_for(100ms);
  EXPECT_TRUE(sink.now().empty());
}

TEST(RenderLoopBundles, TheNinthBundleEvictsTheOldest) {
  Sink sink;
  RenderLoop loop(1, sink.callback());
  std::vector<std::string> hashes;
  for (int i = 0; i < 9; ++i) {
    hashes.push_back(content_hash(bundle(i)));
    ASSERT_TRUE(loop.open_job(i, spec(4), hashes.back(), bundle(i)));
  }
  EXPECT_EQ(loop.cached_hashes(), std::vector<std::string>(hashes.begin() + 1, hashes.end()));
  EXPECT_FALSE(loop.open_job(100, spec(4), hashes[0], std::nullopt));
  for (int i = 1; i < 9; ++i) EXPECT_TRUE(loop.open_job(100 + i, spec(4), hashes[i], std::nullopt));
  // Sending a cached bundle again does not count as a new one: nothing more is evicted.
  ASSERT_TRUE(loop.open_job(200, spec(4), hashes[1], bundle(1)));
  EXPECT_EQ(loop.cached_hashes().size(), 8u);
  EXPECT_TRUE(loop.open_job(201, spec(4), hashes[2], std::nullopt));
}

TEST(RenderLoopFailure, AJobWhoseSceneDoesNotLoadIsReportedFailedOnce) {
  Sink sink;
  RenderLoop loop(1, sink.callback());
  const Bundle broken{"scene.sdl", "sdl", {{"scene.sdl", "sphere {\n"}}};
  ASSERT_TRUE(loop.open_job(1, spec(4), content_hash(broken), broken));
  ASSERT_TRUE(loop.open_job(2, spec(4), content_hash(bundle(0)), bundle(0)));
  // One thread takes the units in order: the failure, a unit that reports nothing more, then
  // the other job's result.
  loop.add_unit(1, 0, 0, whole_image(4));
  loop.add_unit(1, 1, 0, whole_image(4));
  loop.add_unit(2, 0, 0, whole_image(4));
  const std::vector<Report> reports = sink.wait_for(2);
  ASSERT_EQ(reports.size(), 2u);
  const auto* failed = std::get_if<JobFailedMessage>(&reports[0]);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->job, 1);
  EXPECT_NE(failed->error.find("scene.sdl"), std::string::npos) << failed->error;
  EXPECT_FALSE(failed->missing_bundle);
  EXPECT_TRUE(std::holds_alternative<ResultMessage>(reports[1]));
}

TEST(RenderLoopCancel, ACancelledJobsQueuedUnitsAreDroppedAndSendNothing) {
  Sink sink;
  RenderLoop loop(1, sink.callback());
  // Units of 64 x 64 pixels, 9 samples each: milliseconds to tens of milliseconds each.
  ASSERT_TRUE(loop.open_job(1, spec(64, 9), content_hash(bundle(0)), bundle(0)));
  ASSERT_TRUE(loop.open_job(2, spec(4), content_hash(bundle(0)), std::nullopt));
  constexpr int kUnits = 1000;  // far more than the one thread renders in the grace below
  for (int u = 0; u < kUnits; ++u) loop.add_unit(1, u, 0, whole_image(64));
  ASSERT_GE(sink.wait_for(1).size(), 1u);
  loop.cancel_job(1);
  const std::size_t at_cancel = sink.now().size();
  std::this_thread::sleep_for(300ms);  // a unit being traced stops within milliseconds
  const std::size_t after = sink.now().size();
  EXPECT_LE(after, at_cancel + 1) << "results kept coming after the cancel";
  EXPECT_LT(after, static_cast<std::size_t>(kUnits));
  // The thread is free at once: the next job's unit is the next report.
  loop.add_unit(2, 0, 0, whole_image(4));
  const std::vector<Report> reports = sink.wait_for(after + 1);
  ASSERT_EQ(reports.size(), after + 1);
  EXPECT_EQ(job_of(reports.back()), 2);
  for (std::size_t i = 0; i < after; ++i) EXPECT_EQ(job_of(reports[i]), 1);
}

}  // namespace
}  // namespace tessera
