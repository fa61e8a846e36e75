// The scheduler against fake workers: real FrameConnections on loopback whose far ends the
// test reads, and results handed to the scheduler directly. The scheduler reads a clock the
// test steps, so its deadlines are tested exactly however busy the machine is.
#include "coordinator/scheduler/scheduler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>

#include "common/protocol/messages.h"

namespace tessera {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

struct FakeWorker {
  explicit FakeWorker(tcp::socket socket) : peer(std::move(socket)) {}
  std::int64_t id = 0;
  tcp::socket peer;
  FrameDecoder decoder;
  std::vector<JobMessage> jobs;    // received, in order
  std::vector<UnitMessage> units;  // received, in order
  std::vector<CancelMessage> cancels;
};

class SchedulerTest : public ::testing::Test {
 protected:
  // Speculation at once by default; the deadline tests pass their own options.
  explicit SchedulerTest(
      SchedulerOptions options = {.speculation_factor = 0,
                                  .min_speculation = std::chrono::milliseconds(0)})
      : acceptor_(io_, tcp::endpoint(asio::ip::address_v4::loopback(), 0)),
        scheduler_(with_test_clock(options)) {}

  SchedulerOptions with_test_clock(SchedulerOptions options) {
    options.clock = [this] { return now_; };
    return options;
  }

  void advance(double seconds) {
    now_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  }

  JobRequest request(int width, int height, int passes, int priority = 1) {
    JobRequest r;
    r.bundle = {"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}};
    r.spec.settings.width = width;
    r.spec.settings.height = height;
    r.spec.settings.passes = passes;
    r.plan = {.width = width, .height = height, .passes = passes, .unit_pixels = 16};
    r.priority = priority;
    return r;
  }

  Job& add_job(int width, int height, int passes, int priority = 1) {
    Job* job = store_.create(request(width, height, passes, priority));
    scheduler_.add_job(*job);
    return *job;
  }

  FakeWorker& add_worker(int threads, std::set<std::string> cached = {}) {
    tcp::socket client(io_);
    client.connect(acceptor_.local_endpoint());
    auto connection =
        std::make_shared<FrameConnection>(acceptor_.accept(), FrameLimits{}, ConnectionTiming{});
    connection->start([](Frame) {}, [](const std::string&) {});
    auto& w = workers_.emplace_back(std::make_unique<FakeWorker>(std::move(client)));
    w->id = scheduler_.add_worker({"w", "test", threads, std::move(cached)}, connection);
    scheduler_.fill_slots();
    return *w;
  }

  // Lets the connections write, then collects what each fake worker received.
  void drain() {
    for (int i = 0; i < 20; ++i) io_.poll();
    for (auto& w : workers_) {
      w->peer.non_blocking(true);
      char buf[65536];
      boost::system::error_code ec;
      for (std::size_t n; (n = w->peer.read_some(asio::buffer(buf), ec)) > 0 && !ec;)
        w->decoder.feed(std::string_view(buf, n));
      while (auto f = w->decoder.next())
        if (f->type == MessageType::Unit)
          w->units.push_back(decode<UnitMessage>(*f));
        else if (f->type == MessageType::Job)
          w->jobs.push_back(decode<JobMessage>(*f));
        else if (f->type == MessageType::Cancel)
          w->cancels.push_back(decode<CancelMessage>(*f));
    }
  }

  // What an honest worker sends for a unit of `pixels` pixels.
  static Frame result(const Job& job, std::int64_t unit, float value = 0.5f, double seconds = 0) {
    const long long pixels = job.plan.units[static_cast<std::size_t>(unit)].cost;
    RenderStats stats;
    stats.seconds = seconds;
    stats.pixels = stats.samples = stats.camera_rays = static_cast<std::uint64_t>(pixels);
    return encode(
        ResultMessage{.job = job.id,
                      .unit = unit,
                      .stats = stats,
                      .values = FloatValues(static_cast<std::size_t>(pixels) * 3, value)});
  }

  // As the worker link hands it over: decoded, then to the scheduler.
  void deliver(FakeWorker& w, const Frame& frame) {
    scheduler_.on_result(w.id, decode<ResultMessage>(frame));
  }

  // `seconds`: the render time the worker reports for the unit.
  void send_result(FakeWorker& w, const UnitMessage& unit, const Job& job, double seconds = 0) {
    deliver(w, result(job, unit.unit, 0.5f, seconds));
  }

  void report_failure(FakeWorker& w, const Job& job, const std::string& error) {
    scheduler_.on_job_failed(w.id, JobFailedMessage{.job = job.id, .error = error});
  }

  Clock::time_point now_ = Clock::now();  // the scheduler's clock
  asio::io_context io_;
  tcp::acceptor acceptor_;
  JobStore store_{16};
  Scheduler scheduler_;
  std::vector<std::unique_ptr<FakeWorker>> workers_;
};

TEST_F(SchedulerTest, KeepsThreadsPlusPrefetchInFlight) {
  add_job(64, 64, 1);
  FakeWorker& w = add_worker(4);
  drain();
  EXPECT_EQ(w.units.size(), 6u);  // 4 threads + 2 prefetch
}

TEST_F(SchedulerTest, ALostWorkersUnitsGoToOthers) {
  const Job& job = add_job(64, 64, 1);
  FakeWorker& a = add_worker(2);
  drain();
  ASSERT_EQ(a.units.size(), 3u);
  FakeWorker& b = add_worker(1);
  drain();
  scheduler_.remove_worker(a.id);
  std::set<std::int64_t> got;
  for (std::size_t answered = 0; answered < b.units.size() && answered < 12; ++answered) {
    if (answered > 0) got.insert(b.units[answered].unit);
    send_result(b, b.units[answered], job);  // makes room for the re-queued units
    drain();
  }
  for (const auto& f : a.units) EXPECT_TRUE(got.count(f.unit));
}

std::set<std::int64_t> unit_indices(const std::vector<UnitMessage>& units, std::size_t from,
                                    std::size_t to) {
  std::set<std::int64_t> indices;
  for (std::size_t i = from; i < to; ++i) indices.insert(units[i].unit);
  return indices;
}

TEST_F(SchedulerTest, AWorkerThatEvictedTheBundleGetsItAgainWithItsUnits) {
  Job& job = add_job(64, 64, 1);
  FakeWorker& w = add_worker(2, {job.hash});  // announced in hello, evicted since
  drain();
  ASSERT_EQ(w.jobs.size(), 1u);
  EXPECT_FALSE(w.jobs[0].bundle.has_value());
  ASSERT_EQ(w.units.size(), 3u);
  scheduler_.on_job_failed(
      w.id, JobFailedMessage{
                .job = job.id, .error = "bundle is not cached here", .missing_bundle = true});
  drain();
  EXPECT_EQ(job.state(), JobState::Running);
  ASSERT_EQ(w.jobs.size(), 2u);
  EXPECT_TRUE(w.jobs[1].bundle.has_value());
  ASSERT_EQ(w.units.size(), 6u);  // the same units again, after the bundle
  EXPECT_EQ(unit_indices(w.units, 0, 3), unit_indices(w.units, 3, 6));
}

TEST_F(SchedulerTest, AJobFailsWhenASecondWorkerReportsItAndOnlyThatJob) {
  Job& bad = add_job(64, 64, 1, 2);
  Job& good = add_job(64, 64, 1);
  FakeWorker& a = add_worker(1);
  FakeWorker& b = add_worker(1);
  drain();
  report_failure(a, bad, "scene.sdl:1:1: broken");
  EXPECT_EQ(bad.state(), JobState::Running);  // one worker's word
  report_failure(a, bad, "scene.sdl:1:1: broken");
  EXPECT_EQ(bad.state(), JobState::Running);  // nor twice the same worker's
  EXPECT_EQ(bad.warnings().size(), 1u);
  report_failure(b, bad, "out of memory");
  EXPECT_EQ(bad.state(), JobState::Failed);
  EXPECT_EQ(bad.error(), "worker w: scene.sdl:1:1: broken; also worker w: out of memory");
  EXPECT_NE(good.state(), JobState::Failed);
}

TEST_F(SchedulerTest, AFailureReportTakesTheJobFromThatWorkerOnly) {
  Job& job = add_job(64, 64, 1);
  FakeWorker& a = add_worker(1);
  drain();
  ASSERT_EQ(a.units.size(), 2u);
  FakeWorker& b = add_worker(1);
  drain();
  report_failure(a, job, "broken");
  drain();
  ASSERT_EQ(a.cancels.size(), 1u);
  EXPECT_EQ(a.cancels[0].job, job.id);
  EXPECT_EQ(scheduler_.workers()[0].in_flight, 0u);
  // A result the reporting worker had already rendered is dropped, not held against it.
  const long long done = job.done_cost();
  EXPECT_NO_THROW(send_result(a, a.units[0], job));
  EXPECT_EQ(job.done_cost(), done);
  // The other worker renders the whole job, the taken-back units included; none go back to a.
  std::set<std::int64_t> got;
  for (std::size_t i = 0; i < b.units.size() && i < 400; ++i) {
    got.insert(b.units[i].unit);
    send_result(b, b.units[i], job);
    drain();
  }
  EXPECT_EQ(job.state(), JobState::Done);
  EXPECT_EQ(a.units.size(), 2u);
  for (const auto& f : a.units) EXPECT_TRUE(got.count(f.unit));
}

TEST_F(SchedulerTest, WithOneWorkerAFailureWaitsForASecondUntilTheTimeLimit) {
  Job& job = add_job(64, 64, 1);
  FakeWorker& w = add_worker(1);
  drain();
  report_failure(w, job, "broken");
  scheduler_.tick();
  drain();
  EXPECT_EQ(job.state(), JobState::Running);
  EXPECT_EQ(w.units.size(), 2u);  // nothing more of it goes back to the reporting worker
  ASSERT_EQ(job.warnings().size(), 1u);
  EXPECT_NE(job.warnings()[0].find("broken"), std::string::npos);
  advance(3600);  // past the time limit
  scheduler_.tick();
  EXPECT_EQ(job.state(), JobState::Failed);
  EXPECT_EQ(job.error(),
            "worker w: broken (not confirmed by a second worker within the time limit of 600 s)");
}

TEST_F(SchedulerTest, AJobFailedForAJobNeverSentIsRefused) {
  Job& sent = add_job(64, 64, 1);
  FakeWorker& w = add_worker(1);  // its slots fill with the first job's units
  Job& other = add_job(64, 64, 1);
  drain();
  ASSERT_EQ(w.jobs.size(), 1u);
  EXPECT_THROW(report_failure(w, other, "broken"), ProtocolError);
  EXPECT_EQ(other.state(), JobState::Queued);
  EXPECT_TRUE(other.warnings().empty());
  EXPECT_EQ(sent.state(), JobState::Running);
}

TEST_F(SchedulerTest, ResultsThatBreakARuleAreRefusedAndChangeNothing) {
  Job& job = add_job(64, 64, 1);
  FakeWorker& w = add_worker(1);
  Job& other = add_job(64, 64, 1);  // never sent to w: its slots are full
  drain();
  ASSERT_EQ(w.units.size(), 2u);
  const std::int64_t unit = w.units[0].unit;
  const std::set<std::int64_t> held = unit_indices(w.units, 0, 2);
  int unsent = 0;
  while (held.count(unsent)) ++unsent;
  const Frame good = result(job, unit);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto with_pixel = [&](float v) {
    Frame f = good;
    ResultMessage r = decode<ResultMessage>(f);
    r.values[4] = v;
    return encode(r);
  };
  auto with_stat = [&](const char* key, const nlohmann::json& value) {
    Frame f = good;
    f.header["stats"][key] = value;
    return f;
  };
  Frame short_payload = good;
  const std::string_view all = good.payload.view();
  short_payload.payload = std::string(all.substr(0, all.size() - 12));
  Frame miscounted = good;
  miscounted.header["count"] = 1;
  const std::map<std::string, Frame> forged = {
      {"NaN pixel", with_pixel(nan)},
      {"infinite pixel", with_pixel(inf)},
      {"one pixel short", short_payload},
      {"wrong count", miscounted},
      {"unit never sent", result(job, unsent)},
      {"job never sent", result(other, 0)},
      {"negative count", with_stat("shadow_rays", -1)},
      {"fractional count", with_stat("samples", 1.5)},
      {"pixels not the unit's", with_stat("pixels", 1)},
      {"more NaN samples than samples", with_stat("nan_samples", 1u << 30)},
      {"seconds beyond the wall time", with_stat("seconds", 3600.0)},
      {"negative seconds", with_stat("seconds", -1.0)},
      {"rays beyond any machine", with_stat("reflection_rays", std::uint64_t{1} << 50)},
  };
  // Cancelled, the other job would drop late results silently, but not one it never sent.
  ASSERT_TRUE(scheduler_.cancel(other.id));
  for (const auto& [name, frame] : forged) {
    EXPECT_THROW(deliver(w, frame), ProtocolError) << name;
    EXPECT_EQ(job.done_cost(), 0) << name;
    EXPECT_EQ(other.done_cost(), 0) << name;
  }
  EXPECT_EQ(job.stats().camera_rays, 0u);
  // The honest result passes every check, and only once. A negative value is honest: a VRML
  // world may have negative colours.
  const Frame honest = with_pixel(-0.25f);
  EXPECT_NO_THROW(deliver(w, honest));
  EXPECT_EQ(job.done_cost(), job.plan.units[static_cast<std::size_t>(unit)].cost);
  EXPECT_THROW(deliver(w, honest), ProtocolError);
}

TEST_F(SchedulerTest, StragglersAreDuplicatedAndTheLateResultDropped) {
  const Job& job = add_job(2, 2, 1);  // one level, one unit
  FakeWorker& slow = add_worker(1);
  drain();
  ASSERT_EQ(slow.units.size(), 1u);
  FakeWorker& idle = add_worker(1);
  scheduler_.tick();
  drain();
  ASSERT_EQ(idle.units.size(), 1u);
  EXPECT_EQ(idle.units[0].unit, slow.units[0].unit);
  send_result(idle, idle.units[0], job);
  EXPECT_EQ(job.state(), JobState::Done);
  drain();
  // The loser is told to stop rendering the job it still holds.
  ASSERT_EQ(slow.cancels.size(), 1u);
  EXPECT_EQ(slow.cancels[0].job, job.id);
  send_result(slow, slow.units[0], job);  // the loser: the job is gone from the scheduler
  EXPECT_EQ(job.done_cost(), job.plan.total_cost);
}

// A worker that is busy (as many units as threads) keeps its prefetch slots for new work: it
// takes no duplicate until a thread of its own is idle.
TEST_F(SchedulerTest, OnlyAWorkerWithIdleThreadsTakesADuplicate) {
  const Job& first = add_job(2, 2, 1);  // one unit each
  add_job(2, 2, 1);
  FakeWorker& a = add_worker(1);  // 1 thread + 1 prefetch slot: the unit of each job
  drain();
  ASSERT_EQ(a.units.size(), 2u);
  ASSERT_EQ(a.units[0].job, first.id);
  const Job& second = add_job(2, 2, 1);  // pending while `a` is full
  FakeWorker& b = add_worker(1);
  scheduler_.tick();
  drain();
  ASSERT_EQ(b.units.size(), 1u);
  EXPECT_EQ(b.units[0].job, second.id);
  // b's thread is busy; its free prefetch slot must not take a straggler (deadline zero here).
  scheduler_.tick();
  drain();
  EXPECT_EQ(b.units.size(), 1u);
  send_result(b, b.units[0], second);  // now b's thread is idle: it takes the oldest straggler
  drain();
  ASSERT_EQ(b.units.size(), 2u);
  EXPECT_EQ(b.units[1].job, first.id);
  EXPECT_EQ(b.units[1].unit, a.units[0].unit);
}

// A worker never duplicates its own unit: it skips its stragglers, however old, for the oldest
// of another worker.
TEST_F(SchedulerTest, AnIdleWorkerDuplicatesTheOldestStragglerNotItsOwn) {
  const Job& job = add_job(8, 4, 1);  // four units
  FakeWorker& b = add_worker(2);      // 2 threads + 1 prefetch: three units at time 0
  drain();
  ASSERT_EQ(b.units.size(), 3u);
  advance(1);
  FakeWorker& a = add_worker(1);  // the fourth unit, at time 1
  drain();
  ASSERT_EQ(a.units.size(), 1u);
  send_result(b, b.units[1], job);
  drain();
  EXPECT_EQ(b.units.size(), 3u) << "both of b's threads are still busy";
  send_result(b, b.units[2], job);  // a thread idle; b's own unit 0 is the oldest straggler
  drain();
  ASSERT_EQ(b.units.size(), 4u);
  EXPECT_EQ(b.units[3].unit, a.units[0].unit);
}

// The scheduler's defaults: a straggler is duplicated after 3 x the job's mean unit time and
// not before 0.3 s.
class SpeculationDeadlineTest : public SchedulerTest {
 protected:
  SpeculationDeadlineTest()
      : SchedulerTest(
            {.speculation_factor = 3, .min_speculation = std::chrono::milliseconds(600)}) {}
};

TEST_F(SpeculationDeadlineTest, NoDuplicateBeforeTheMinimum) {
  add_job(2, 2, 1);  // one unit: no mean yet, the minimum decides
  FakeWorker& slow = add_worker(1);
  FakeWorker& idle = add_worker(1);
  drain();
  ASSERT_EQ(slow.units.size(), 1u);
  EXPECT_TRUE(idle.units.empty());
  advance(0.599);
  scheduler_.tick();
  drain();
  EXPECT_TRUE(idle.units.empty());
  advance(0.002);
  scheduler_.tick();
  drain();
  ASSERT_EQ(idle.units.size(), 1u);
  EXPECT_EQ(idle.units[0].unit, slow.units[0].unit);
}

TEST_F(SpeculationDeadlineTest, NoDuplicateBeforeFactorTimesTheMeanUnitTime) {
  // Four units: the slow worker takes two, and the other two once its first result shows a
  // short round trip (its slots grow), so the other worker finds only stragglers.
  const Job& job = add_job(8, 4, 1);
  FakeWorker& slow = add_worker(1);
  drain();
  ASSERT_EQ(slow.units.size(), 2u);
  // The first unit reports 0.6 s of rendering, back 0.61 s after it was sent (a 10 ms round
  // trip): the mean is 0.6 s, the second unit's deadline 1.8 s after its dispatch at 0.
  advance(0.61);
  send_result(slow, slow.units[0], job, 0.6);
  FakeWorker& idle = add_worker(1);
  drain();
  ASSERT_EQ(slow.units.size(), 4u) << "the other units go to the slow worker's grown slots";
  advance(1.189);  // past the minimum and past the mean, not past 3 x the mean
  scheduler_.tick();
  drain();
  EXPECT_TRUE(idle.units.empty());
  advance(0.002);
  scheduler_.tick();
  drain();
  ASSERT_EQ(idle.units.size(), 1u);
  EXPECT_EQ(idle.units[0].unit, slow.units[1].unit);
}

TEST_F(SchedulerTest, ALateDuplicateOfARunningJobIsDropped) {
  const Job& job = add_job(16, 16, 1);  // several units
  FakeWorker& slow = add_worker(1);
  drain();
  const UnitMessage first = slow.units[0];
  FakeWorker& idle = add_worker(1);
  drain();
  // The idle worker took new units first; answer them until it is given the straggler.
  for (std::size_t i = 0; i < idle.units.size() && i < 64; ++i) {
    if (idle.units[i].unit == first.unit) break;
    send_result(idle, idle.units[i], job);
    scheduler_.tick();
    drain();
  }
  ASSERT_EQ(idle.units.back().unit, first.unit);
  send_result(idle, idle.units.back(), job);
  const long long done = job.done_cost();
  send_result(slow, first, job);
  EXPECT_EQ(job.done_cost(), done);
  EXPECT_EQ(scheduler_.workers()[0].dropped_results, 1);
}

TEST_F(SchedulerTest, ALaterPassWaitsForTheEarlierOne) {
  const Job& job = add_job(8, 8, 2);
  FakeWorker& w = add_worker(64);
  drain();
  for (const auto& f : w.units) EXPECT_EQ(f.pass, 0);
  const std::size_t pass0 = w.units.size();
  for (std::size_t i = 0; i + 1 < pass0; ++i) send_result(w, w.units[i], job);
  drain();
  EXPECT_EQ(w.units.size(), pass0);  // one pass-0 unit still out: nothing of pass 1 yet
  send_result(w, w.units[pass0 - 1], job);
  drain();
  ASSERT_GT(w.units.size(), pass0);
  EXPECT_EQ(w.units[pass0].pass, 1);
}

TEST_F(SchedulerTest, WorkersAreSharedByPriority) {
  const Job& low = add_job(64, 64, 4, 1);
  const Job& high = add_job(64, 64, 4, 3);
  FakeWorker& w = add_worker(1);
  std::map<std::int64_t, long long> cost;
  for (int round = 0; round < 60; ++round) {
    drain();
    const UnitMessage f = w.units.back();
    const Job& job = f.job == low.id ? low : high;
    cost[job.id] += job.plan.units[static_cast<std::size_t>(f.unit)].cost;
    w.units.clear();
    send_result(w, f, job);
  }
  const double ratio = static_cast<double>(cost[high.id]) / static_cast<double>(cost[low.id]);
  EXPECT_NEAR(ratio, 3.0, 0.6);
}

TEST_F(SchedulerTest, CancelFreesTheWorkersAtOnce) {
  const Job& job = add_job(64, 64, 1);
  const Job& other = add_job(64, 64, 1);
  FakeWorker& a = add_worker(2);
  FakeWorker& b = add_worker(1);
  drain();
  EXPECT_TRUE(scheduler_.cancel(job.id));
  drain();
  EXPECT_EQ(job.state(), JobState::Cancelled);
  // Every worker holding the job is sent one Cancel for it (and none for the other job).
  // Their slots keep only the other job's units.
  const std::vector<Scheduler::WorkerView> workers = scheduler_.workers();
  for (FakeWorker* w : {&a, &b}) {
    const auto held = [&](const Job& j) {
      return std::count_if(w->units.begin(), w->units.end(),
                           [&](const UnitMessage& f) { return f.job == j.id; });
    };
    ASSERT_GT(held(job), 0);
    ASSERT_EQ(w->cancels.size(), 1u);
    EXPECT_EQ(w->cancels[0].job, job.id);
    EXPECT_EQ(static_cast<long>(workers[w == &a ? 0 : 1].in_flight), held(other));
  }
  EXPECT_FALSE(scheduler_.cancel(job.id));
  EXPECT_EQ(other.state(), JobState::Running);
}

// Calibration learns from a job that ran alone: speed = (render seconds / predicted threads) /
// uncalibrated prediction; overhead = wall seconds - render seconds per thread.
TEST_F(SchedulerTest, CalibrationLearnsSpeedAndOverheadFromItsInputs) {
  Job& job = add_job(2, 2, 1);
  job.uncalibrated_prediction = 0.5;
  job.prediction_threads = 4;
  FakeWorker& w = add_worker(1);
  drain();
  ASSERT_EQ(w.units.size(), 1u);
  advance(0.15);
  send_result(w, w.units[0], job, 0.2);  // 0.2 render seconds: 0.05 per predicted thread
  ASSERT_EQ(job.state(), JobState::Done);
  const Prediction p = scheduler_.predict(1e-3, 1000);  // 1 s on the one thread, uncalibrated
  EXPECT_DOUBLE_EQ(p.factor, 0.2 / 4 / 0.5);
  EXPECT_NEAR(p.overhead_seconds, 0.15 - 0.05, 1e-9);
  ASSERT_TRUE(p.seconds);
  EXPECT_DOUBLE_EQ(*p.seconds, p.overhead_seconds + p.factor * 1.0);
}

TEST_F(SchedulerTest, AJobThatRanBesideAnotherDoesNotCalibrate) {
  Job& first = add_job(2, 2, 1);
  Job& second = add_job(2, 2, 1);
  for (Job* job : {&first, &second})
    job->uncalibrated_prediction = 0.5, job->prediction_threads = 1;
  FakeWorker& w = add_worker(1);  // 1 thread + 1 prefetch: one unit of each
  drain();
  ASSERT_EQ(w.units.size(), 2u);
  for (const UnitMessage& f : w.units) send_result(w, f, f.job == first.id ? first : second, 0.2);
  ASSERT_EQ(first.state(), JobState::Done);
  ASSERT_EQ(second.state(), JobState::Done);
  const Prediction p = scheduler_.predict(1e-3, 1000);
  EXPECT_EQ(p.factor, 1);
  EXPECT_EQ(p.overhead_seconds, 0);
}

}  // namespace
}  // namespace tessera
