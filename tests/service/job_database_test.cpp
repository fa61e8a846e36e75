// The coordinator's durable job store (coordinator/store): round trips, a crash before flush,
// schema refusal and migration, shared bundle files, retention by age and size, paging, and a
// full store that fails the write without damaging what it holds.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "coordinator/store/content_files.h"
#include "coordinator/store/job_database.h"
#include "coordinator/store/sqlite.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// A fresh data directory per test, removed afterwards.
class JobDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tessera-job-db-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::size_t files_in(const std::string& folder) const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_ / folder)) ++n;
    return n;
  }

  fs::path dir_;
};

// A wall-clock time with whole microseconds, what the store keeps.
WallClock::time_point at_seconds(long long s) {
  return WallClock::time_point(std::chrono::duration_cast<WallClock::duration>(
      std::chrono::seconds(1'700'000'000 + s) + 123'456us));
}

StoredRequest make_request(const std::string& scene = "camera { }\n") {
  StoredRequest request;
  request.bundle.main = "scenes/main.sdl";
  request.bundle.format = "sdl";
  request.bundle.files = {{"scenes/main.sdl", scene}, {"meshes/a.obj", std::string("v\0 1", 4)}};
  request.spec.settings.width = 64;
  request.spec.settings.height = 48;
  request.spec.settings.aa_samples = 5;
  request.spec.overrides.max_depth = 3;
  request.plan.width = 64;
  request.plan.height = 48;
  request.plan.passes = 4;
  request.plan.progressive = false;
  request.plan.order = UnitOrder::Scanline;
  request.plan.preview = PreviewMode::Area;
  request.plan.unit_pixels = 777;
  request.priority = 3;
  request.effects = {"shadows", "reflection"};
  request.warnings = {"main.sdl:3:1: unused"};
  request.seconds_per_pixel_pass = 1.25e-7;
  request.predicted_seconds = 4.5;
  request.prediction_threads = 6;
  // Numbers whose every digit matters, and the flag the status's camera form leaves out.
  request.camera = Camera{{0.1 + 0.2, -1e-300, 5}, {0, 1.0 / 3, 0}, {0, 1, 1e-9}, 33.5, true};
  request.viewpoints = {{"Start", Camera{}},
                        {"world.wrl:12:3", Camera{{1, 2, 3}, {1, 2, 2}, {0, 1, 0}, 28.6, true}}};
  return request;
}

// Values whose exact bits matter: signed zero, a subnormal, a NaN with a payload, infinity.
FloatValues awkward_values(int seed, std::size_t n) {
  FloatValues values(n);
  for (std::size_t i = 0; i < n; ++i) values[i] = static_cast<float>(seed) + 1.0f / float(i + 3);
  values[0] = -0.0f;
  values[1] = std::bit_cast<float>(0x00000001u);
  values[2] = std::bit_cast<float>(0x7fc01234u);
  values[n - 1] = std::numeric_limits<float>::infinity();
  return values;
}

bool same_bytes(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

RenderStats stats_with(std::uint64_t camera_rays, double seconds) {
  RenderStats stats;
  stats.camera_rays = camera_rays;
  stats.pixels = 12;
  stats.seconds = seconds;
  return stats;
}

// A region job (issue 21 §4) resumes with the region's plan: the region travels in the stored
// settings and the plan is made from them again.
TEST_F(JobDatabaseTest, ARegionJobRestoresItsRegionsPlan) {
  StoredRequest request = make_request();
  request.spec.settings.region = PixelRect{8, 4, 40, 28};
  request.plan.region = request.spec.settings.region;
  JobDatabase(dir_).add_job(request, at_seconds(0));
  const std::vector<StoredJob> jobs = JobDatabase(dir_).load_all();
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].request.spec.settings.region, (PixelRect{8, 4, 40, 28}));
  EXPECT_EQ(jobs[0].request.plan.region, (PixelRect{8, 4, 40, 28}));
  EXPECT_EQ(make_plan(jobs[0].request.plan).total_cost, 4LL * 32 * 24);  // 4 passes
}

TEST_F(JobDatabaseTest, RoundTripsAJobItsResultsAndImages) {
  std::vector<FloatValues> sent = {awkward_values(1, 12), awkward_values(2, 3),
                                   awkward_values(3, 300)};
  std::int64_t id = 0;
  {
    JobDatabase db(dir_);
    id = db.add_job(make_request(), at_seconds(0));
    db.set_state(id, "running");
    EXPECT_EQ(db.append_result(id, 7, sent[0], stats_with(11, 0.5), "alpha"), 0);
    EXPECT_EQ(db.append_result(id, 2, sent[1], stats_with(22, 0.25), "beta"), 1);
    EXPECT_EQ(db.append_result(id, 5, sent[2], stats_with(33, 0.125), "alpha"), 2);
    db.flush();
    db.finish_job(id, "done", "", at_seconds(9),
                  {{"image.png", std::string("\x89PNG\0\1", 6)}, {"image.exr", "exr"}});
  }
  JobDatabase db(dir_);
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs.size(), 1u);
  const StoredJob& job = jobs[0];
  StoredRequest expected = make_request();
  EXPECT_EQ(job.id, id);
  EXPECT_EQ(job.request.bundle, expected.bundle);
  EXPECT_EQ(to_json(job.request.spec), to_json(expected.spec));
  EXPECT_EQ(job.request.plan.width, 64);
  EXPECT_EQ(job.request.plan.height, 48);
  EXPECT_EQ(job.request.plan.passes, 4);
  EXPECT_FALSE(job.request.plan.progressive);
  EXPECT_EQ(job.request.plan.order, UnitOrder::Scanline);
  EXPECT_EQ(job.request.plan.preview, PreviewMode::Area);
  EXPECT_EQ(job.request.plan.unit_pixels, 777);
  EXPECT_EQ(job.request.priority, 3);
  EXPECT_EQ(job.request.effects, expected.effects);
  EXPECT_EQ(job.request.warnings, expected.warnings);
  EXPECT_EQ(job.request.seconds_per_pixel_pass, 1.25e-7);
  EXPECT_FALSE(job.request.uncalibrated_prediction);
  EXPECT_EQ(job.request.predicted_seconds, 4.5);
  EXPECT_EQ(job.request.prediction_threads, 6);
  EXPECT_EQ(job.request.camera, expected.camera);
  EXPECT_EQ(job.request.viewpoints, expected.viewpoints);
  EXPECT_EQ(job.state, "done");
  EXPECT_EQ(job.created, at_seconds(0));
  EXPECT_EQ(job.finished, at_seconds(9));

  ASSERT_EQ(job.results.size(), 3u);
  const int units[] = {7, 2, 5};
  const char* workers[] = {"alpha", "beta", "alpha"};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(job.results[i].sequence, static_cast<std::int64_t>(i));
    EXPECT_EQ(job.results[i].unit, units[i]);
    EXPECT_TRUE(same_bytes(job.results[i].values, sent[i])) << "result " << i;
    EXPECT_EQ(job.results[i].stats.camera_rays, 11u * (i + 1));
    EXPECT_EQ(job.results[i].worker, workers[i]);
  }
  EXPECT_EQ(job.results[2].stats.seconds, 0.125);
  EXPECT_EQ(job.images, (std::vector<std::string>{"image.exr", "image.png"}));
  EXPECT_EQ(read_whole_file(db.image_path(id, "image.png")), std::string("\x89PNG\0\1", 6));
}

// A job whose scene gave no camera (none is stored for it) and no Viewpoints.
TEST_F(JobDatabaseTest, AJobWithoutCameraOrViewpointsRoundTrips) {
  StoredRequest request = make_request();
  request.camera.reset();
  request.viewpoints.clear();
  JobDatabase(dir_).add_job(request, at_seconds(0));
  const std::vector<StoredJob> jobs = JobDatabase(dir_).load_all();
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_FALSE(jobs[0].request.camera);
  EXPECT_TRUE(jobs[0].request.viewpoints.empty());
}

// The schema as a store holds it: every table's and index's statement, by name.
std::string schema_of(const fs::path& dir) {
  sqlite::Connection raw((dir / "tessera.db").string());
  sqlite::Statement select(raw, "SELECT name, sql FROM sqlite_schema ORDER BY name");
  std::string schema;
  while (select.step())
    schema += select.column_text(0) + ": " +
              (select.is_null(1) ? std::string("(implicit)") : select.column_text(1)) + "\n";
  return schema;
}

// A store written by a coordinator of schema version 1 (tests/service/data/job_store_v1: its
// database as `sqlite3 .dump` printed it, and its one bundle file) holds one queued job. Opened
// now, it is migrated: the job loads as it was, without camera or Viewpoints, new jobs keep
// theirs, and the store's schema is the one a new store gets.
TEST_F(JobDatabaseTest, MigratesAVersion1StoreWhoseJobsKeepWorking) {
  const fs::path fixture = fs::path(TESSERA_SOURCE_DIR) / "tests/service/data/job_store_v1";
  fs::create_directories(dir_);
  fs::copy(fixture / "bundles", dir_ / "bundles", fs::copy_options::recursive);
  {
    sqlite::Connection raw((dir_ / "tessera.db").string());
    raw.exec(read_whole_file(fixture / "tessera.sql"));
    ASSERT_EQ(raw.query_int("PRAGMA user_version"), 1);
  }
  {
    JobDatabase db(dir_);
    std::vector<StoredJob> jobs = db.load_all();
    ASSERT_EQ(jobs.size(), 1u);
    const StoredJob& old_job = jobs[0];
    EXPECT_EQ(old_job.id, 1);
    EXPECT_EQ(old_job.state, "queued");
    EXPECT_EQ(old_job.request.bundle.main, "scene.sdl");
    EXPECT_EQ(old_job.request.spec.settings.width, 16);
    EXPECT_FALSE(old_job.request.spec.overrides.camera);
    EXPECT_EQ(old_job.request.plan.width, 16);
    EXPECT_FALSE(old_job.request.camera);
    EXPECT_TRUE(old_job.request.viewpoints.empty());
    EXPECT_EQ(db.add_job(make_request(), at_seconds(1)), 2);
  }
  const std::vector<StoredJob> jobs = JobDatabase(dir_).load_all();
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[1].request.camera, make_request().camera);
  EXPECT_EQ(jobs[1].request.viewpoints, make_request().viewpoints);
  {
    sqlite::Connection raw((dir_ / "tessera.db").string());
    EXPECT_EQ(raw.query_int("PRAGMA user_version"), JobDatabase::kSchemaVersion);
  }
  const fs::path fresh = dir_ / "fresh";
  { JobDatabase created(fresh); }
  EXPECT_EQ(schema_of(dir_), schema_of(fresh));
}

TEST_F(JobDatabaseTest, ACrashLosesOnlyTheResultsNotFlushed) {
  std::int64_t id = 0;
  {
    JobDatabase db(dir_);
    id = db.add_job(make_request(), at_seconds(0));
    db.append_result(id, 0, awkward_values(0, 6), {}, "w");
    db.append_result(id, 1, awkward_values(1, 6), {}, "w");
    db.flush();
    db.append_result(id, 2, awkward_values(2, 6), {}, "w");
    EXPECT_EQ(db.queued(), 1u);
  }  // destroyed without flush: the process died
  // What a crash between writing a file and committing its row leaves: swept at open.
  write_file_atomically(dir_ / "bundles" / "0badc0de", "orphan bundle");
  write_file_atomically(dir_ / "bundles" / ".tmp-feed", "torn temporary");
  fs::create_directories(dir_ / "images" / "99");
  JobDatabase db(dir_);
  EXPECT_EQ(files_in("bundles"), 1u);
  EXPECT_EQ(files_in("images"), 0u);
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0].results.size(), 2u);
  EXPECT_TRUE(same_bytes(jobs[0].results[1].values, awkward_values(1, 6)));
  // The resumed job continues the sequence after what was stored.
  EXPECT_EQ(db.append_result(id, 2, awkward_values(2, 6), {}, "w"), 2);
  db.flush();
  EXPECT_EQ(db.load_all()[0].results.size(), 3u);
}

// A bundle file swapped for another valid bundle, or for garbage: loading names the job.
TEST_F(JobDatabaseTest, ABundleFileThatDoesNotMatchItsHashNamesItsJob) {
  JobDatabase db(dir_);
  std::int64_t id = db.add_job(make_request(), at_seconds(0));
  db.add_job(make_request("camera { fov 10 }\n"), at_seconds(0));
  fs::path file = dir_ / "bundles" / content_hash(make_request().bundle);
  for (std::string content :
       {read_whole_file(dir_ / "bundles" /
                        content_hash(make_request("camera { fov 10 }\n").bundle)),
        std::string("{}\n")}) {
    write_file_atomically(file, content);
    try {
      db.load_all();
      FAIL() << "a damaged bundle was loaded";
    } catch (const StoreError& e) {
      EXPECT_EQ(e.jobs(), (std::vector<std::int64_t>{id})) << e.what();
    }
  }
}

TEST_F(JobDatabaseTest, IdsAreNeverReusedAcrossRestartsAndDeletions) {
  {
    JobDatabase db(dir_);
    EXPECT_EQ(db.add_job(make_request(), at_seconds(0)), 1);
    EXPECT_EQ(db.add_job(make_request(), at_seconds(0)), 2);
    db.finish_job(2, "done", "", at_seconds(1), {});
    EXPECT_EQ(db.prune(at_seconds(100), 10s, JobDatabase::kUnlimited),
              (std::vector<std::int64_t>{2}));
  }
  JobDatabase db(dir_);
  EXPECT_EQ(db.add_job(make_request(), at_seconds(0)), 3);
}

TEST_F(JobDatabaseTest, RefusesAnUnknownSchemaVersionAndAForeignDatabase) {
  { JobDatabase db(dir_); }
  const std::string newer = std::to_string(JobDatabase::kSchemaVersion + 1);
  {
    sqlite::Connection raw((dir_ / "tessera.db").string());
    raw.exec("PRAGMA user_version = " + newer);
  }
  try {
    JobDatabase db(dir_);
    FAIL() << "a newer schema was opened";
  } catch (const StoreError& e) {
    EXPECT_NE(std::string(e.what()).find("schema version " + newer), std::string::npos) << e.what();
  }

  fs::path other = dir_ / "other";
  fs::create_directories(other);
  {
    sqlite::Connection raw((other / "tessera.db").string());
    raw.exec("CREATE TABLE notes (text TEXT)");
  }
  EXPECT_THROW(JobDatabase{other}, StoreError);
}

TEST_F(JobDatabaseTest, BundleFilesAreSharedAndGoWithTheirLastJob) {
  JobDatabase db(dir_);
  std::int64_t a = db.add_job(make_request(), at_seconds(0));
  std::int64_t b = db.add_job(make_request(), at_seconds(1));
  std::int64_t c = db.add_job(make_request("camera { fov 40 }\n"), at_seconds(2));
  EXPECT_EQ(files_in("bundles"), 2u);
  EXPECT_TRUE(fs::exists(dir_ / "bundles" / content_hash(make_request().bundle)));

  db.finish_job(a, "done", "", at_seconds(3), {});
  db.finish_job(c, "cancelled", "", at_seconds(3), {});
  db.prune(at_seconds(100), 10s, JobDatabase::kUnlimited);
  EXPECT_EQ(files_in("bundles"), 1u);  // c's bundle went; a's is still b's
  EXPECT_TRUE(fs::exists(dir_ / "bundles" / content_hash(make_request().bundle)));

  db.finish_job(b, "failed", "worker lost", at_seconds(4), {});
  db.prune(at_seconds(100), 10s, JobDatabase::kUnlimited);
  EXPECT_EQ(files_in("bundles"), 0u);
  EXPECT_TRUE(db.load_all().empty());
}

TEST_F(JobDatabaseTest, PruneByAgeDeletesOnlyFinishedJobsOlderThanTheKeep) {
  JobDatabase db(dir_);
  std::int64_t old_job = db.add_job(make_request(), at_seconds(0));
  std::int64_t recent = db.add_job(make_request(), at_seconds(0));
  std::int64_t running = db.add_job(make_request(), at_seconds(0));
  db.finish_job(old_job, "done", "", at_seconds(10), {{"image.png", "png"}});
  db.finish_job(recent, "done", "", at_seconds(50), {});
  db.set_state(running, "running");

  EXPECT_EQ(db.prune(at_seconds(100), 60s, JobDatabase::kUnlimited),
            (std::vector<std::int64_t>{old_job}));
  std::vector<JobListing> left = db.list(10);
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0].id, recent);
  EXPECT_EQ(left[1].id, running);
  EXPECT_FALSE(fs::exists(dir_ / "images" / std::to_string(old_job)));
}

TEST_F(JobDatabaseTest, PruneBySizeDeletesTheOldestFinishedFirst) {
  JobDatabase db(dir_);
  std::string image(100'000, 'x');
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(db.add_job(make_request(), at_seconds(0)));
  // Finished out of id order: age is by finish time.
  db.finish_job(ids[0], "done", "", at_seconds(30), {{"image.png", image}});
  db.finish_job(ids[1], "done", "", at_seconds(10), {{"image.png", image}});
  db.finish_job(ids[2], "done", "", at_seconds(20), {{"image.png", image}});
  db.append_result(ids[3], 0, FloatValues(30'000, 1.0f), {}, "w");  // 120 KB, unfinished
  db.flush();

  std::int64_t before = db.size_bytes();
  EXPECT_GT(before, 420'000);
  EXPECT_EQ(db.prune(at_seconds(40), 3600s, before - 150'000),
            (std::vector<std::int64_t>{ids[1], ids[2]}));
  EXPECT_LE(db.size_bytes(), before - 150'000);
  EXPECT_EQ(db.load_all().size(), 2u);

  // An unfinished job is never deleted, even when it alone is over the limit.
  EXPECT_EQ(db.prune(at_seconds(40), 3600s, 1), (std::vector<std::int64_t>{ids[0]}));
  ASSERT_EQ(db.load_all().size(), 1u);
  EXPECT_EQ(db.load_all()[0].id, ids[3]);
}

TEST_F(JobDatabaseTest, ListsInPagesAfterAnId) {
  JobDatabase db(dir_);
  for (int i = 0; i < 5; ++i) db.add_job(make_request(), at_seconds(i));
  db.append_result(4, 0, awkward_values(0, 3), {}, "w");
  db.flush();
  auto ids = [](const std::vector<JobListing>& page) {
    std::vector<std::int64_t> out;
    for (const JobListing& row : page) out.push_back(row.id);
    return out;
  };
  EXPECT_EQ(ids(db.list(2, 0)), (std::vector<std::int64_t>{1, 2}));
  std::vector<JobListing> page = db.list(2, 2);
  EXPECT_EQ(ids(page), (std::vector<std::int64_t>{3, 4}));
  EXPECT_EQ(page[1].results, 1);
  EXPECT_EQ(page[1].created, at_seconds(3));
  EXPECT_EQ(ids(db.list(2, 4)), (std::vector<std::int64_t>{5}));
  EXPECT_TRUE(db.list(2, 5).empty());
}

TEST_F(JobDatabaseTest, AFullStoreFailsTheWriteAndKeepsWhatItHeld) {
  std::int64_t finished = 0, running = 0;
  std::int64_t size = 0;
  {
    JobDatabase db(dir_);
    finished = db.add_job(make_request(), at_seconds(0));
    db.finish_job(finished, "done", "", at_seconds(1), {{"image.png", "png bytes"}});
    running = db.add_job(make_request("camera { fov 30 }\n"), at_seconds(2));
    db.append_result(running, 0, awkward_values(0, 3072), {}, "w");
    db.append_result(running, 1, awkward_values(1, 3072), {}, "w");
    db.flush();
    size = db.size_bytes();
  }
  {
    // Room for about 16 more results: a flush that was not one transaction would keep some.
    JobDatabase db(dir_, size + 200'000);
    // 100 results of 12 KB: their payloads' file counts, and is not written at all.
    const std::uintmax_t payload_bytes = fs::file_size(dir_ / "results" / std::to_string(running));
    for (int i = 0; i < 100; ++i)
      db.append_result(running, 2 + i, awkward_values(i, 3072), {}, "w");
    try {
      db.flush();
      FAIL() << "the results were written over the limit";
    } catch (const StoreError& e) {
      EXPECT_EQ(e.jobs(), (std::vector<std::int64_t>{running}));
      EXPECT_NE(e.cause().find("over its limit"), std::string::npos) << e.what();
    }
    EXPECT_EQ(db.queued(), 0u);
    EXPECT_EQ(fs::file_size(dir_ / "results" / std::to_string(running)), payload_bytes);
    // A bundle that fits SQLite's pages but not the byte budget: the store's own check.
    try {
      db.add_job(make_request(std::string(300'000, 'x')), at_seconds(3));
      FAIL() << "a job was stored over the limit";
    } catch (const StoreError& e) {
      EXPECT_NE(e.cause().find("over its limit"), std::string::npos) << e.what();
    }
    EXPECT_EQ(files_in("bundles"), 2u);  // the new bundle's file went with its row
    EXPECT_THROW(db.finish_job(running, "done", "", at_seconds(4),
                               {{"image.png", std::string(300'000, 'y')}}),
                 StoreError);
    EXPECT_FALSE(fs::exists(dir_ / "images" / std::to_string(running)));
    // Failing the job is a small write that still fits.
    db.finish_job(running, "failed", "the job store is full", at_seconds(5), {});
  }
  JobDatabase db(dir_);
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].id, finished);
  EXPECT_EQ(jobs[0].state, "done");
  EXPECT_EQ(read_whole_file(db.image_path(finished, "image.png")), "png bytes");
  EXPECT_EQ(jobs[1].state, "failed");
  ASSERT_EQ(jobs[1].results.size(), 2u);
  EXPECT_TRUE(same_bytes(jobs[1].results[1].values, awkward_values(1, 3072)));
  EXPECT_EQ(db.add_job(make_request(), at_seconds(6)), running + 1);
}

// The figure of issue 17 §1: one coordinator tick's flush of 100 unit results of 1024 pixels
// (12 KB each) must fit well inside the 250 ms tick, and a result must cost little more on disk
// than its floats.
TEST_F(JobDatabaseTest, FlushOfAHundredUnitResultsFitsATick) {
  JobDatabase db(dir_);
  std::int64_t id = db.add_job(make_request(), at_seconds(0));
  FloatValues values = awkward_values(0, 3 * 1024);
  std::int64_t empty = db.size_bytes();
  std::vector<double> seconds;
  for (int round = 0; round < 5; ++round) {
    for (int i = 0; i < 100; ++i) db.append_result(id, i, values, stats_with(1024, 0.01), "w");
    auto start = std::chrono::steady_clock::now();
    db.flush();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  double slowest = seconds.back();
  double per_result = static_cast<double>(db.size_bytes() - empty) / 500.0;
  std::printf(
      "flush of 100 results of 12 KB: median %.1f ms, slowest of 5 %.1f ms; "
      "%.0f bytes per result\n",
      seconds[2] * 1e3, slowest * 1e3, per_result);
  EXPECT_LT(slowest, 0.25);
  EXPECT_LT(per_result, 1.1 * 12288);
}

std::int64_t file_bytes(const fs::path& file) {
  return static_cast<std::int64_t>(fs::file_size(file));
}

// Payloads go to one file per job (schema version 3), which the budget counts whole.
TEST_F(JobDatabaseTest, PayloadsAreInTheJobsFileWhichTheBudgetCounts) {
  JobDatabase db(dir_);
  std::int64_t id = db.add_job(make_request(), at_seconds(0));
  const std::int64_t empty = db.size_bytes();
  for (int i = 0; i < 3; ++i) db.append_result(id, i, awkward_values(i, 3000), {}, "w");
  db.flush();
  const fs::path file = dir_ / "results" / std::to_string(id);
  EXPECT_EQ(file_bytes(file), 3 * 12'000);
  // The rows are small: the database grew by a page or two, not by the payloads again.
  EXPECT_GE(db.size_bytes() - empty, 3 * 12'000);
  EXPECT_LE(db.size_bytes() - empty, 3 * 12'000 + 2 * 4096);
}

// A crash between writing the payloads and committing their rows leaves bytes past the
// committed ones: the next open cuts them off, and the job's next payloads go where they were.
TEST_F(JobDatabaseTest, APayloadTailACrashLeftIsCutOffAtOpen) {
  std::int64_t id = 0;
  const fs::path file = dir_ / "results" / "1";
  {
    JobDatabase db(dir_);
    id = db.add_job(make_request(), at_seconds(0));
    for (int i = 0; i < 2; ++i) db.append_result(id, i, awkward_values(i, 300), {}, "w");
    db.flush();
  }
  ASSERT_EQ(file, dir_ / "results" / std::to_string(id));
  write_file_atomically(file, read_whole_file(file) + std::string(5000, '\x7f'));  // torn tail
  JobDatabase db(dir_);
  EXPECT_EQ(file_bytes(file), 2 * 1200);
  db.append_result(id, 2, awkward_values(2, 300), {}, "w");
  db.flush();
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs[0].results.size(), 3u);
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(same_bytes(jobs[0].results[i].values, awkward_values(i, 300))) << i;
  EXPECT_EQ(file_bytes(file), 3 * 1200);
}

// A row whose payload the file no longer holds (damaged, cut short or deleted from outside the
// store) is left out of its job, whose unit is then rendered again; the rest load as stored.
TEST_F(JobDatabaseTest, AResultWhosePayloadIsMissingOrDamagedIsLeftOut) {
  JobDatabase db(dir_);
  std::int64_t id = db.add_job(make_request(), at_seconds(0));
  for (int i = 0; i < 3; ++i) db.append_result(id, 10 + i, awkward_values(i, 300), {}, "w");
  db.flush();
  const fs::path file = dir_ / "results" / std::to_string(id);
  auto units = [&] {
    std::vector<int> out;
    const std::vector<StoredJob> jobs = db.load_all();
    for (const StoredResult& result : jobs.at(0).results) out.push_back(result.unit);
    return out;
  };
  std::string bytes = read_whole_file(file);
  bytes[1200 + 700] ^= 0x10;  // one bit of the second payload
  write_file_atomically(file, bytes);
  EXPECT_EQ(units(), (std::vector<int>{10, 12}));
  fs::resize_file(file, 2 * 1200 + 600);  // the third cut short
  EXPECT_EQ(units(), (std::vector<int>{10}));
  fs::remove(file);
  EXPECT_TRUE(units().empty());
  // The job goes on after its stored sequence.
  EXPECT_EQ(db.append_result(id, 11, awkward_values(1, 300), {}, "w"), 3);
  db.flush();
  EXPECT_EQ(units(), (std::vector<int>{11}));
}

// A result stored before schema version 3, its payload inline in its row, loads as it did, in
// sequence with the job's later results in its file.
TEST_F(JobDatabaseTest, AResultStoredInlineBeforeVersion3StillLoads) {
  std::int64_t id = 0;
  {
    JobDatabase db(dir_);
    id = db.add_job(make_request(), at_seconds(0));
  }
  {
    sqlite::Connection raw((dir_ / "tessera.db").string());
    const FloatValues values = awkward_values(0, 300);
    sqlite::Statement(raw,
                      "INSERT INTO results (job_id, sequence, unit, payload, stats, worker) "
                      "VALUES (?, 0, 4, ?, '{}', 'old')")
        .bind(1, id)
        .bind_blob(2, std::as_bytes(std::span(values)))
        .run();
  }
  JobDatabase db(dir_);
  EXPECT_EQ(db.append_result(id, 5, awkward_values(1, 300), {}, "new"), 1);
  db.flush();
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs[0].results.size(), 2u);
  EXPECT_EQ(jobs[0].results[0].worker, "old");
  EXPECT_TRUE(same_bytes(jobs[0].results[0].values, awkward_values(0, 300)));
  EXPECT_TRUE(same_bytes(jobs[0].results[1].values, awkward_values(1, 300)));
}

// A deleted job's payload file goes with it; one a crash left without its job goes at open.
TEST_F(JobDatabaseTest, AJobsPayloadFileGoesWithIt) {
  {
    JobDatabase db(dir_);
    std::int64_t id = db.add_job(make_request(), at_seconds(0));
    db.append_result(id, 0, awkward_values(0, 300), {}, "w");
    db.flush();
    EXPECT_EQ(files_in("results"), 1u);
    db.finish_job(id, "done", "", at_seconds(1), {});
    db.prune(at_seconds(100), 10s, JobDatabase::kUnlimited);
    EXPECT_EQ(files_in("results"), 0u);
  }
  write_file_atomically(dir_ / "results" / "77", "payloads of a job deleted before its file");
  JobDatabase db(dir_);
  EXPECT_EQ(files_in("results"), 0u);
}

// Waits until the store's thread has finished a flush after `before` of them.
void wait_for_background_flush(const JobDatabase& db, long long before) {
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (db.background_flushes() == before && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(5ms);
  ASSERT_GT(db.background_flushes(), before);
}

// flush_soon writes on the store's own thread what flush() would write, and a failure there
// waits in take_failures() for the coordinator's next tick.
TEST_F(JobDatabaseTest, FlushSoonWritesOnTheStoresThreadAndKeepsItsFailures) {
  std::int64_t job = 0, size = 0;
  {
    JobDatabase db(dir_);
    job = db.add_job(make_request(), at_seconds(0));
    for (int i = 0; i < 3; ++i) db.append_result(job, i, awkward_values(i, 3072), {}, "w");
    const long long before = db.background_flushes();
    db.flush_soon();
    wait_for_background_flush(db, before);
    EXPECT_EQ(db.queued(), 0u);
    EXPECT_TRUE(db.take_failures().empty());
    size = db.size_bytes();
  }
  {
    JobDatabase db(dir_, size + 200'000);  // room for about 16 more results
    for (int i = 0; i < 100; ++i) db.append_result(job, 3 + i, awkward_values(i, 3072), {}, "w");
    const long long before = db.background_flushes();
    db.flush_soon();
    wait_for_background_flush(db, before);
    const std::vector<StoreError> failures = db.take_failures();
    ASSERT_EQ(failures.size(), 1u);
    EXPECT_EQ(failures[0].jobs(), (std::vector<std::int64_t>{job}));
    EXPECT_TRUE(db.take_failures().empty());
  }
  JobDatabase db(dir_);
  std::vector<StoredJob> jobs = db.load_all();
  ASSERT_EQ(jobs.size(), 1u);
  ASSERT_EQ(jobs[0].results.size(), 3u);
  EXPECT_TRUE(same_bytes(jobs[0].results[2].values, awkward_values(2, 3072)));
}

}  // namespace
}  // namespace tessera
