#include "coordinator/store/job_database.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstring>
#include <iterator>
#include <optional>
#include <system_error>
#include <utility>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "coordinator/store/content_files.h"
#include "coordinator/store/flush_thread.h"
#include "coordinator/store/result_files.h"
#include "coordinator/store/sqlite.h"

namespace tessera {

// Payloads are the floats' native bytes; the store is read back on the machine that wrote it.
static_assert(std::endian::native == std::endian::little, "the store's blobs are little-endian");

namespace {

// 'TESS': marks the database as a Tessera job store, so that another application's SQLite file
// given as --data-dir is refused rather than written into.
constexpr std::int64_t kApplicationId = 0x54455353;

// The tables as schema version 1 made them. A new store is made at version 1 and then taken
// through every migration below, exactly as an old store is, so that a new store and a migrated
// one are the same.
constexpr const char* kSchemaVersion1 = R"sql(
CREATE TABLE bundles (
  hash TEXT PRIMARY KEY,
  bytes INTEGER NOT NULL
);
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY AUTOINCREMENT,
  bundle_hash TEXT NOT NULL REFERENCES bundles(hash),
  spec TEXT NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, passes INTEGER NOT NULL,
  progressive INTEGER NOT NULL, unit_order TEXT NOT NULL, preview TEXT NOT NULL,
  unit_pixels INTEGER NOT NULL,
  priority INTEGER NOT NULL,
  effects TEXT NOT NULL, warnings TEXT NOT NULL,
  seconds_per_pixel_pass REAL NOT NULL, uncalibrated_prediction REAL, predicted_seconds REAL,
  prediction_threads INTEGER NOT NULL,
  state TEXT NOT NULL, error TEXT NOT NULL,
  created_us INTEGER NOT NULL, finished_us INTEGER
);
CREATE INDEX jobs_by_finish ON jobs(finished_us) WHERE finished_us IS NOT NULL;
CREATE TABLE results (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  sequence INTEGER NOT NULL,
  unit INTEGER NOT NULL,
  payload BLOB NOT NULL,
  stats TEXT NOT NULL,
  worker TEXT NOT NULL,
  PRIMARY KEY (job_id, sequence)
);
CREATE TABLE images (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  name TEXT NOT NULL,
  bytes INTEGER NOT NULL,
  PRIMARY KEY (job_id, name)
);
)sql";

// One step of the schema: from version `to - 1` to version `to`, run in one transaction with
// the new user_version, so a crash leaves either version whole.
struct Migration {
  std::int64_t to;
  const char* sql;
};

constexpr Migration kMigrations[] = {
    // The scene's camera and Viewpoints (issue 21 §3): stored jobs had none, so a restored job
    // lost what the page navigates from. Old rows keep no camera and no Viewpoints.
    {2,
     "ALTER TABLE jobs ADD COLUMN camera TEXT;"
     "ALTER TABLE jobs ADD COLUMN viewpoints TEXT NOT NULL DEFAULT '[]'"},
    // Results' payloads in one file per job (result_files.h), the row keeping where: SQLite
    // copied each blob three times (its log, the checkpoint's read and write). Rows stored
    // before keep their payload inline (payload_offset NULL) and load as they did; the jobs'
    // result_file_bytes, what their files hold in committed rows, counts towards the budget.
    {3,
     "ALTER TABLE results ADD COLUMN payload_offset INTEGER;"
     "ALTER TABLE results ADD COLUMN payload_bytes INTEGER;"
     "ALTER TABLE results ADD COLUMN payload_check INTEGER;"
     "ALTER TABLE jobs ADD COLUMN result_file_bytes INTEGER NOT NULL DEFAULT 0"},
};
static_assert(std::size(kMigrations) == JobDatabase::kSchemaVersion - 1,
              "one migration per schema version after the first");

std::int64_t to_micros(WallClock::time_point t) {
  return std::chrono::duration_cast<std::chrono::microseconds>(t.time_since_epoch()).count();
}

WallClock::time_point from_micros(std::int64_t us) {
  return WallClock::time_point(
      std::chrono::duration_cast<WallClock::duration>(std::chrono::microseconds(us)));
}

std::string describe(const std::vector<std::int64_t>& jobs) {
  if (jobs.empty()) return "job store";
  std::string out = jobs.size() == 1 ? "job " : "jobs ";
  for (std::size_t i = 0; i < jobs.size(); ++i) out += (i ? ", " : "") + std::to_string(jobs[i]);
  return out;
}

// Runs a write and turns any failure below it (SQLite, file system) into a StoreError naming
// the jobs it was for.
template <class Write>
auto guarded(const std::vector<std::int64_t>& jobs, Write&& write) {
  try {
    return write();
  } catch (const StoreError&) {
    throw;
  } catch (const sqlite::SqliteError& e) {
    throw StoreError(jobs, e.what());
  } catch (const std::system_error& e) {
    throw StoreError(jobs, e.what());
  }
}

bool is_plain_file_name(const std::string& name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_'))
      return false;
  return true;
}

// A bundle file: the header of encode_bundle as one line of JSON, then its payload.
std::string serialize_bundle(const Bundle& bundle) {
  nlohmann::json header;
  std::string payload;
  encode_bundle(bundle, header, payload);
  return header.dump() + '\n' + payload;
}

Bundle parse_bundle(const std::string& bytes) {
  std::size_t newline = bytes.find('\n');
  if (newline == std::string::npos) throw std::runtime_error("no header line");
  return decode_bundle(nlohmann::json::parse(bytes.substr(0, newline)), bytes.substr(newline + 1));
}

// A camera as the store keeps it: the status's form (camera_to_json, whose numbers JSON gives
// back exactly) and which side of the image the angle spans, which that form leaves out.
nlohmann::json camera_record(const Camera& camera) {
  nlohmann::json record = camera_to_json(camera);
  record["fov_on_smaller_side"] = camera.view_angle_on_smaller_side;
  return record;
}

// Throws nlohmann::json's exceptions for a record this code did not write.
Camera camera_from_record(const nlohmann::json& record) {
  auto vec3 = [&](const char* key) {
    const nlohmann::json& v = record.at(key);
    return Vec3{v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()};
  };
  Camera camera;
  camera.eye = vec3("eye");
  camera.look_at = vec3("look_at");
  camera.up = vec3("up");
  camera.view_angle = record.at("fov").get<double>();
  camera.view_angle_on_smaller_side = record.at("fov_on_smaller_side").get<bool>();
  return camera;
}

std::string viewpoints_record(const std::vector<NamedCamera>& viewpoints) {
  nlohmann::json records = nlohmann::json::array();
  for (const NamedCamera& v : viewpoints)
    records.push_back({{"name", v.name}, {"camera", camera_record(v.camera)}});
  return records.dump();
}

std::vector<NamedCamera> viewpoints_from_record(const std::string& text) {
  std::vector<NamedCamera> viewpoints;
  for (const nlohmann::json& record : nlohmann::json::parse(text))
    viewpoints.push_back(
        {record.at("name").get<std::string>(), camera_from_record(record.at("camera"))});
  return viewpoints;
}

}  // namespace

StoreError::StoreError(std::vector<std::int64_t> jobs, const std::string& cause)
    : std::runtime_error(describe(jobs) + ": " + cause), jobs_(std::move(jobs)), cause_(cause) {}

JobDatabase::JobDatabase(const std::filesystem::path& dir, std::int64_t max_disk_bytes)
    : dir_(dir), max_disk_bytes_(max_disk_bytes) {
  try {
    open();
  } catch (const StoreError& e) {
    // Named by the directory, the one thing the operator can act on; nothing was changed.
    throw StoreError({}, "cannot open the data directory " + dir_.string() + ": " + e.cause());
  }
}

void JobDatabase::open() {
  guarded({}, [&] {
    std::filesystem::create_directories(dir_ / "bundles");
    std::filesystem::create_directories(dir_ / "images");
    std::filesystem::create_directories(dir_ / "results");
    db_ = std::make_unique<sqlite::Connection>((dir_ / "tessera.db").string());
    // A write-protected file is opened read-only without a word; the first write would fail
    // later, inside a job.
    if (db_->read_only())
      throw StoreError({}, (dir_ / "tessera.db").string() + " is read-only to this process");
    // auto_vacuum only takes effect before the first table exists: set it before the schema,
    // so that pruned jobs give their pages back to the file system (incremental_vacuum).
    db_->exec("PRAGMA auto_vacuum = INCREMENTAL");
    {
      sqlite::Statement wal(*db_, "PRAGMA journal_mode = WAL");
      if (!wal.step() || wal.column_text(0) != "wal")
        throw StoreError({}, dir_.string() + "/tessera.db: cannot use WAL mode");
    }
    // In WAL mode NORMAL loses no committed transaction when the process dies, only at a
    // power cut (the last commits before it).
    db_->exec("PRAGMA synchronous = NORMAL; PRAGMA foreign_keys = ON");

    std::int64_t application = db_->query_int("PRAGMA application_id");
    std::int64_t version = db_->query_int("PRAGMA user_version");
    std::string file = (dir_ / "tessera.db").string();
    if (application == 0 && version == 0) {
      if (db_->query_int("SELECT count(*) FROM sqlite_schema") != 0)
        throw StoreError({}, file + " is a SQLite database of another application");
      sqlite::Transaction transaction(*db_);
      db_->exec(kSchemaVersion1);
      db_->exec("PRAGMA application_id = " + std::to_string(kApplicationId) +
                "; PRAGMA user_version = 1");
      transaction.commit();
      version = 1;
    } else if (application != kApplicationId) {
      throw StoreError({}, file + " is a SQLite database of another application");
    } else if (version < 1 || version > kSchemaVersion) {
      throw StoreError({}, file + " has schema version " + std::to_string(version) +
                               "; this coordinator reads versions 1 to " +
                               std::to_string(kSchemaVersion));
    }
    for (const Migration& migration : kMigrations) {
      if (migration.to <= version) continue;
      sqlite::Transaction transaction(*db_);
      db_->exec(migration.sql);
      db_->exec("PRAGMA user_version = " + std::to_string(migration.to));
      transaction.commit();
    }
    if (max_disk_bytes_ != kUnlimited) {
      // SQLite itself refuses to grow the file past the budget (SQLITE_FULL), so one huge
      // transaction fails before it is written rather than at the check after it.
      std::int64_t page = db_->query_int("PRAGMA page_size");
      db_->exec("PRAGMA max_page_count = " +
                std::to_string(std::max<std::int64_t>(max_disk_bytes_ / page, 1)));
    }
    sweep_orphans();
  });
  flush_thread_ = std::make_unique<FlushThread>([this] {
    try {
      flush();
    } catch (const StoreError& e) {
      std::lock_guard queue(queue_mutex_);
      failures_.push_back(e);
    }
  });
}

JobDatabase::~JobDatabase() = default;

std::filesystem::path JobDatabase::bundle_path(const std::string& hash) const {
  return dir_ / "bundles" / hash;
}

std::filesystem::path JobDatabase::result_file(std::int64_t job) const {
  return dir_ / "results" / std::to_string(job);
}

std::filesystem::path JobDatabase::image_path(std::int64_t job, const std::string& name) const {
  return dir_ / "images" / std::to_string(job) / name;
}

// Files a crash left behind: temporaries, bundles written before their job's row committed,
// images and result files of jobs deleted before their files were, and result payloads written
// after the last rows that committed.
void JobDatabase::sweep_orphans() {
  std::map<std::string, bool> bundles;
  {
    sqlite::Statement statement(*db_, "SELECT hash FROM bundles");
    while (statement.step()) bundles[statement.column_text(0)] = true;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir_ / "bundles"))
    if (!bundles.count(entry.path().filename().string())) std::filesystem::remove_all(entry);
  std::map<std::string, bool> jobs_with_images;
  {
    sqlite::Statement statement(*db_, "SELECT DISTINCT job_id FROM images");
    while (statement.step()) jobs_with_images[std::to_string(statement.column_int(0))] = true;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir_ / "images"))
    if (!jobs_with_images.count(entry.path().filename().string()))
      std::filesystem::remove_all(entry);
  std::map<std::string, std::int64_t> result_file_bytes;  // by file name, the job's id
  {
    sqlite::Statement statement(*db_, "SELECT id, result_file_bytes FROM jobs");
    while (statement.step())
      result_file_bytes[std::to_string(statement.column_int(0))] = statement.column_int(1);
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir_ / "results")) {
    auto job = result_file_bytes.find(entry.path().filename().string());
    if (job == result_file_bytes.end())
      std::filesystem::remove_all(entry);
    else
      truncate_payloads(entry.path(), job->second);
  }
}

std::int64_t JobDatabase::size_locked() {
  return (db_->query_int("PRAGMA page_count") - db_->query_int("PRAGMA freelist_count")) *
             db_->query_int("PRAGMA page_size") +
         db_->query_int("SELECT COALESCE(SUM(bytes), 0) FROM bundles") +
         db_->query_int("SELECT COALESCE(SUM(bytes), 0) FROM images") +
         db_->query_int("SELECT COALESCE(SUM(result_file_bytes), 0) FROM jobs");
}

std::int64_t JobDatabase::size_bytes() {
  std::lock_guard lock(mutex_);
  return guarded({}, [&] { return size_locked(); });
}

// Inside a write transaction: the size it would leave, against the budget.
void JobDatabase::check_budget(const std::vector<std::int64_t>& jobs) {
  std::int64_t size = size_locked();
  if (size > max_disk_bytes_)
    throw StoreError(jobs, "the store would hold " + std::to_string(size) +
                               " bytes, over its limit of " + std::to_string(max_disk_bytes_));
}

std::int64_t JobDatabase::add_job(const StoredRequest& request, WallClock::time_point created) {
  std::lock_guard lock(mutex_);
  std::string hash = content_hash(request.bundle);
  std::filesystem::path file = bundle_path(hash);
  bool wrote_file = false;
  try {
    return guarded({}, [&] {
      sqlite::Statement known(*db_, "SELECT bytes FROM bundles WHERE hash = ?");
      known.bind(1, hash);
      std::int64_t bundle_bytes = 0;
      if (known.step()) {
        bundle_bytes = known.column_int(0);
        known.reset();
      } else {
        std::string bytes = serialize_bundle(request.bundle);
        write_file_atomically(file, bytes);
        wrote_file = true;
        bundle_bytes = static_cast<std::int64_t>(bytes.size());
      }
      sqlite::Transaction transaction(*db_);
      sqlite::Statement(*db_, "INSERT OR IGNORE INTO bundles (hash, bytes) VALUES (?, ?)")
          .bind(1, hash)
          .bind(2, bundle_bytes)
          .run();
      sqlite::Statement insert(*db_, R"sql(
        INSERT INTO jobs (bundle_hash, spec, width, height, passes, progressive, unit_order,
          preview, unit_pixels, priority, effects, warnings, seconds_per_pixel_pass,
          uncalibrated_prediction, predicted_seconds, prediction_threads, state, error,
          created_us, camera, viewpoints)
        VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, 'queued', '', ?, ?, ?))sql");
      const PlanOptions& plan = request.plan;
      insert.bind(1, hash)
          .bind(2, to_json(request.spec).dump())
          .bind(3, std::int64_t{plan.width})
          .bind(4, std::int64_t{plan.height})
          .bind(5, std::int64_t{plan.passes})
          .bind(6, std::int64_t{plan.progressive})
          .bind(7, std::string_view(to_string(plan.order)))
          .bind(8, std::string_view(to_string(plan.preview)))
          .bind(9, std::int64_t{plan.unit_pixels})
          .bind(10, std::int64_t{request.priority})
          .bind(11, nlohmann::json(request.effects).dump())
          .bind(12, nlohmann::json(request.warnings).dump())
          .bind(13, request.seconds_per_pixel_pass)
          .bind(14, request.uncalibrated_prediction)
          .bind(15, request.predicted_seconds)
          .bind(16, std::int64_t{request.prediction_threads})
          .bind(17, to_micros(created))
          .bind(19, viewpoints_record(request.viewpoints));
      if (request.camera) insert.bind(18, camera_record(*request.camera).dump());  // else NULL
      insert.run();
      std::int64_t id = db_->last_insert_rowid();
      check_budget({});
      transaction.commit();
      std::lock_guard queue(queue_mutex_);
      next_sequence_[id] = 0;
      return id;
    });
  } catch (const StoreError& e) {
    // The row never committed: the bundle file written for it has no job.
    if (wrote_file) std::filesystem::remove(file);
    throw StoreError({}, "cannot store a new job (bundle " + hash + "): " + e.cause());
  }
}

void JobDatabase::set_state(std::int64_t job, const std::string& state, const std::string& error) {
  std::lock_guard lock(mutex_);
  guarded({job}, [&] {
    sqlite::Statement(*db_, "UPDATE jobs SET state = ?, error = ? WHERE id = ?")
        .bind(1, state)
        .bind(2, error)
        .bind(3, job)
        .run();
    if (db_->changes() == 0) throw StoreError({job}, "no such job");
  });
}

std::int64_t JobDatabase::append_result(std::int64_t job, int unit, FloatValues values,
                                        const RenderStats& stats, const std::string& worker) {
  // Taken over, not copied: this runs for every merged unit.
  QueuedResult result{.job = job,
                      .sequence = 0,
                      .unit = unit,
                      .payload = std::move(values),
                      .stats = stats,
                      .worker = worker};
  {
    std::lock_guard queue(queue_mutex_);
    if (auto next = next_sequence_.find(job); next != next_sequence_.end()) {
      const std::int64_t sequence = result.sequence = next->second++;
      queue_.push_back(std::move(result));
      return sequence;
    }
  }
  // First result since open or since a failed flush: continue after what is stored, once a
  // flush under way has stored what it writes.
  std::lock_guard lock(mutex_);
  std::int64_t stored = guarded({job}, [&] {
    sqlite::Statement statement(
        *db_,
        "SELECT (SELECT COUNT(*) FROM jobs WHERE id = ?1), "
        "(SELECT COALESCE(MAX(sequence) + 1, 0) FROM results WHERE job_id = ?1)");
    statement.bind(1, job).step();
    if (statement.column_int(0) == 0) throw StoreError({job}, "no such job");
    return statement.column_int(1);
  });
  std::lock_guard queue(queue_mutex_);
  const std::int64_t sequence = result.sequence =
      next_sequence_.try_emplace(job, stored).first->second++;
  queue_.push_back(std::move(result));
  return sequence;
}

std::size_t JobDatabase::queued() const {
  std::lock_guard queue(queue_mutex_);
  return queue_.size();
}

void JobDatabase::flush() {
  std::lock_guard lock(mutex_);
  flush_locked();
}

void JobDatabase::flush_soon() { flush_thread_->request(); }

std::vector<StoreError> JobDatabase::take_failures() {
  std::lock_guard queue(queue_mutex_);
  return std::exchange(failures_, {});
}

long long JobDatabase::background_flushes() const { return flush_thread_->runs(); }

void JobDatabase::flush_locked() {
  std::vector<QueuedResult> batch;
  {
    std::lock_guard queue(queue_mutex_);
    batch.swap(queue_);
  }
  if (batch.empty()) return;
  // Each job's payloads go to its file from the end of its committed ones on.
  struct JobPayloads {
    std::int64_t job = 0, start = 0, end = 0;
    std::vector<std::span<const std::byte>> payloads;
    bool written = false;  // bytes from `start` on may be in the file
  };
  std::vector<JobPayloads> files;
  std::vector<std::int64_t> jobs;
  auto file_of = [&](std::int64_t job) {
    return std::find_if(files.begin(), files.end(),
                        [&](const JobPayloads& file) { return file.job == job; });
  };
  for (const QueuedResult& result : batch)
    if (file_of(result.job) == files.end()) {
      files.emplace_back().job = result.job;
      jobs.push_back(result.job);
    }
  try {
    guarded(jobs, [&] {
      sqlite::Transaction transaction(*db_);
      sqlite::Statement file_end(*db_, "SELECT result_file_bytes FROM jobs WHERE id = ?");
      for (JobPayloads& file : files) {
        if (!file_end.bind(1, file.job).step())
          throw StoreError(jobs, "job " + std::to_string(file.job) + " is not stored");
        file.start = file.end = file_end.column_int(0);
        file_end.reset();
      }
      sqlite::Statement insert(*db_,
                               "INSERT INTO results (job_id, sequence, unit, payload, stats, "
                               "worker, payload_offset, payload_bytes, payload_check) "
                               "VALUES (?, ?, ?, x'', ?, ?, ?, ?, ?)");
      for (const QueuedResult& result : batch) {
        JobPayloads& file = *file_of(result.job);
        const std::span<const std::byte> payload = std::as_bytes(std::span(result.payload));
        const auto bytes = static_cast<std::int64_t>(payload.size());
        insert.bind(1, result.job)
            .bind(2, result.sequence)
            .bind(3, std::int64_t{result.unit})
            .bind(4, to_json(result.stats).dump())
            .bind(5, result.worker)
            .bind(6, file.end)
            .bind(7, bytes)
            .bind(8, std::bit_cast<std::int64_t>(payload_checksum(payload)))
            .run();
        file.payloads.push_back(payload);
        file.end += bytes;
      }
      sqlite::Statement grow(*db_, "UPDATE jobs SET result_file_bytes = ? WHERE id = ?");
      for (const JobPayloads& file : files) grow.bind(1, file.end).bind(2, file.job).run();
      // Before the files grow: a write over the budget never reaches the disk.
      check_budget(jobs);
      for (JobPayloads& file : files) {
        file.written = true;
        append_payloads(result_file(file.job), file.start, file.payloads);
      }
      transaction.commit();
    });
  } catch (const StoreError&) {
    // What was written belongs to no committed row: cut it off now rather than at the next
    // open, so that the files hold what the budget counts.
    for (const JobPayloads& file : files) {
      if (!file.written) continue;
      try {
        truncate_payloads(result_file(file.job), file.start);
      } catch (const std::system_error&) {
        // The next open cuts it off; no row points at it meanwhile.
      }
    }
    // The dropped results leave gaps in the sequence: start again after what is stored. What
    // the jobs merged since the batch was taken goes too (they fail), so no sequence repeats.
    for (std::int64_t job : jobs) drop_queued(job);
    throw;
  }
}

void JobDatabase::finish_job(std::int64_t job, const std::string& state, const std::string& error,
                             WallClock::time_point finished,
                             const std::vector<StoredImage>& images) {
  std::lock_guard lock(mutex_);
  for (const StoredImage& image : images)
    if (!is_plain_file_name(image.name))
      throw std::invalid_argument("not a plain image file name: " + image.name);
  drop_queued(job);
  flush_locked();
  std::filesystem::path folder = dir_ / "images" / std::to_string(job);
  try {
    guarded({job}, [&] {
      sqlite::Statement current(*db_, "SELECT finished_us IS NOT NULL FROM jobs WHERE id = ?");
      current.bind(1, job);
      if (!current.step()) throw StoreError({job}, "no such job");
      if (current.column_int(0)) throw StoreError({job}, "already finished");
      current.reset();
      if (!images.empty()) std::filesystem::create_directories(folder);
      for (const StoredImage& image : images)
        write_file_atomically(folder / image.name, image.bytes);
      sqlite::Transaction transaction(*db_);
      sqlite::Statement(*db_, "UPDATE jobs SET state = ?, error = ?, finished_us = ? WHERE id = ?")
          .bind(1, state)
          .bind(2, error)
          .bind(3, to_micros(finished))
          .bind(4, job)
          .run();
      sqlite::Statement insert(*db_, "INSERT INTO images (job_id, name, bytes) VALUES (?, ?, ?)");
      for (const StoredImage& image : images)
        insert.bind(1, job)
            .bind(2, image.name)
            .bind(3, static_cast<std::int64_t>(image.bytes.size()))
            .run();
      check_budget({job});
      transaction.commit();
    });
  } catch (const StoreError&) {
    // A job that was not finished has no images: whatever is in its folder is from this call.
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
    throw;
  }
  drop_queued(job);
}

std::vector<StoredJob> JobDatabase::load_all() {
  std::lock_guard lock(mutex_);
  return guarded({}, [&] {
    std::vector<StoredJob> jobs;
    std::map<std::string, Bundle> bundles;
    sqlite::Statement select(*db_, R"sql(
    SELECT id, bundle_hash, spec, width, height, passes, progressive, unit_order, preview,
      unit_pixels, priority, effects, warnings, seconds_per_pixel_pass, uncalibrated_prediction,
      predicted_seconds, prediction_threads, state, error, created_us, finished_us, camera,
      viewpoints
    FROM jobs ORDER BY id)sql");
    sqlite::Statement results(*db_,
                              "SELECT sequence, unit, payload, stats, worker, payload_offset, "
                              "payload_bytes, payload_check FROM results "
                              "WHERE job_id = ? ORDER BY sequence");
    sqlite::Statement images(*db_, "SELECT name FROM images WHERE job_id = ? ORDER BY name");
    while (select.step()) {
      StoredJob job;
      job.id = select.column_int(0);
      try {
        std::string hash = select.column_text(1);
        auto bundle = bundles.find(hash);
        if (bundle == bundles.end()) {
          Bundle parsed = parse_bundle(read_whole_file(bundle_path(hash)));
          if (content_hash(parsed) != hash)
            throw std::runtime_error("its content does not match its hash");
          bundle = bundles.emplace(hash, std::move(parsed)).first;
        }
        StoredRequest& request = job.request;
        request.bundle = bundle->second;
        request.spec = job_spec_from_json(nlohmann::json::parse(select.column_text(2)));
        request.plan.width = static_cast<int>(select.column_int(3));
        request.plan.height = static_cast<int>(select.column_int(4));
        request.plan.passes = static_cast<int>(select.column_int(5));
        request.plan.progressive = select.column_int(6) != 0;
        request.plan.order = parse_unit_order(select.column_text(7));
        request.plan.preview = parse_preview_mode(select.column_text(8));
        request.plan.unit_pixels = select.column_int(9);
        // The region travels with the settings, so a stored job restores its plan.
        request.plan.region = request.spec.settings.region;
        request.priority = static_cast<int>(select.column_int(10));
        request.effects =
            nlohmann::json::parse(select.column_text(11)).get<std::vector<std::string>>();
        request.warnings =
            nlohmann::json::parse(select.column_text(12)).get<std::vector<std::string>>();
        request.seconds_per_pixel_pass = select.column_double(13);
        if (!select.is_null(14)) request.uncalibrated_prediction = select.column_double(14);
        if (!select.is_null(15)) request.predicted_seconds = select.column_double(15);
        request.prediction_threads = static_cast<int>(select.column_int(16));
        job.state = select.column_text(17);
        job.error = select.column_text(18);
        job.created = from_micros(select.column_int(19));
        if (!select.is_null(20)) job.finished = from_micros(select.column_int(20));
        if (!select.is_null(21))
          request.camera = camera_from_record(nlohmann::json::parse(select.column_text(21)));
        request.viewpoints = viewpoints_from_record(select.column_text(22));

        std::optional<PayloadReader> payloads;  // opened at the first row that points into it
        std::vector<std::int64_t> unreadable;
        results.bind(1, job.id);
        while (results.step()) {
          StoredResult& result = job.results.emplace_back();
          result.sequence = results.column_int(0);
          result.unit = static_cast<int>(results.column_int(1));
          if (results.is_null(5)) {  // stored inline, before schema version 3
            std::span<const std::byte> payload = results.column_blob(2);
            if (payload.size() % sizeof(float) != 0)
              throw std::runtime_error("result " + std::to_string(result.sequence) +
                                       " has a payload of " + std::to_string(payload.size()) +
                                       " bytes, not whole floats");
            result.values.resize(payload.size() / sizeof(float));
            if (!payload.empty()) std::memcpy(result.values.data(), payload.data(), payload.size());
          } else {
            if (!payloads) payloads.emplace(result_file(job.id));
            if (!payloads->read(results.column_int(5), results.column_int(6),
                                std::bit_cast<std::uint64_t>(results.column_int(7)),
                                result.values)) {
              unreadable.push_back(result.sequence);
              job.results.pop_back();
              continue;
            }
          }
          result.stats = stats_from_json(nlohmann::json::parse(results.column_text(3)));
          result.worker = results.column_text(4);
        }
        results.reset();
        // Only damage from outside (the file cut, deleted or overwritten) leaves these: the
        // units are rendered again rather than the job or the coordinator failing.
        if (!unreadable.empty())
          spdlog::warn(
              "job {}: {} stored results' payloads are missing or damaged in {} (the "
              "first is result {}); their units will be rendered again",
              job.id, unreadable.size(), result_file(job.id).string(), unreadable[0]);
        images.bind(1, job.id);
        while (images.step()) job.images.push_back(images.column_text(0));
        images.reset();
      } catch (const StoreError&) {
        throw;
      } catch (const std::exception& e) {
        throw StoreError({job.id}, std::string("cannot be read back: ") + e.what());
      }
      jobs.push_back(std::move(job));
    }
    return jobs;
  });
}

std::vector<JobListing> JobDatabase::list(int limit, std::int64_t after_id) {
  std::lock_guard lock(mutex_);
  return guarded({}, [&] {
    std::vector<JobListing> out;
    sqlite::Statement select(*db_, R"sql(
      SELECT id, state, error, created_us, finished_us,
        (SELECT COUNT(*) FROM results WHERE job_id = jobs.id)
      FROM jobs WHERE id > ? ORDER BY id LIMIT ?)sql");
    select.bind(1, after_id).bind(2, std::int64_t{limit});
    while (select.step()) {
      JobListing& row = out.emplace_back();
      row.id = select.column_int(0);
      row.state = select.column_text(1);
      row.error = select.column_text(2);
      row.created = from_micros(select.column_int(3));
      if (!select.is_null(4)) row.finished = from_micros(select.column_int(4));
      row.results = select.column_int(5);
    }
    return out;
  });
}

// Deletes a job's rows, and its bundle's row when no other job shares it, in one transaction;
// then the files, which a crash between the two leaves as orphans for the next open.
void JobDatabase::delete_job_locked(std::int64_t job) {
  std::vector<std::string> unused_bundles;
  guarded({job}, [&] {
    sqlite::Transaction transaction(*db_);
    sqlite::Statement(*db_, "DELETE FROM jobs WHERE id = ?").bind(1, job).run();
    sqlite::Statement orphans(
        *db_,
        "DELETE FROM bundles WHERE hash NOT IN (SELECT bundle_hash FROM jobs) RETURNING hash");
    while (orphans.step()) unused_bundles.push_back(orphans.column_text(0));
    transaction.commit();
  });
  std::error_code ignored;
  std::filesystem::remove_all(dir_ / "images" / std::to_string(job), ignored);
  std::filesystem::remove(result_file(job), ignored);
  for (const std::string& hash : unused_bundles)
    std::filesystem::remove(bundle_path(hash), ignored);
  drop_queued(job);
}

void JobDatabase::drop_queued(std::int64_t job) {
  std::lock_guard queue(queue_mutex_);
  next_sequence_.erase(job);
  std::erase_if(queue_, [&](const QueuedResult& result) { return result.job == job; });
}

std::vector<std::int64_t> JobDatabase::prune(WallClock::time_point now,
                                             std::chrono::seconds keep_finished,
                                             std::int64_t max_disk_bytes) {
  std::lock_guard lock(mutex_);
  std::vector<std::int64_t> deleted;
  guarded({}, [&] {
    std::vector<std::int64_t> expired;
    {
      sqlite::Statement select(
          *db_, "SELECT id FROM jobs WHERE finished_us < ? ORDER BY finished_us, id");
      select.bind(1, to_micros(now - keep_finished));
      while (select.step()) expired.push_back(select.column_int(0));
    }
    for (std::int64_t job : expired) {
      delete_job_locked(job);
      deleted.push_back(job);
    }
    sqlite::Statement oldest(
        *db_, "SELECT id FROM jobs WHERE finished_us IS NOT NULL ORDER BY finished_us, id LIMIT 1");
    while (size_locked() > max_disk_bytes) {
      if (!oldest.step()) break;  // only unfinished jobs are left
      std::int64_t job = oldest.column_int(0);
      oldest.reset();
      delete_job_locked(job);
      deleted.push_back(job);
    }
    if (!deleted.empty()) db_->exec("PRAGMA incremental_vacuum");
  });
  return deleted;
}

}  // namespace tessera
