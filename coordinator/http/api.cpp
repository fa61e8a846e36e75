#include "coordinator/http/api.h"

#include <cctype>
#include <fstream>
#include <sstream>

#include <spdlog/spdlog.h>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>

#include "common/image/image.h"
#include "coordinator/http/gzip.h"
#include "coordinator/http/job_json.h"
#include "coordinator/http/refusal_status.h"
#include "coordinator/http/submission.h"
#include "coordinator/http/tile_deltas.h"
#include "coordinator/http/worker_json.h"
#include "coordinator/jobs/api_error.h"

namespace tessera {

namespace http = boost::beast::http;

namespace {

std::string percent_decode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out.push_back(' ');
    } else if (s[i] == '%' && i + 2 < s.size()) {
      const std::string hex(s.substr(i + 1, 2));
      if (std::isxdigit(static_cast<unsigned char>(hex[0])) &&
          std::isxdigit(static_cast<unsigned char>(hex[1]))) {
        out.push_back(static_cast<char>(std::stoi(hex, nullptr, 16)));
        i += 2;
      } else {
        out.push_back('%');
      }
    } else {
      out.push_back(s[i]);
    }
  }
  return out;
}

HttpResponse error_response(const ApiError& e) {
  return json_response(http_status(e.refusal()), e.body());
}

ApiError busy() {
  return ApiError(Refusal::busy, "busy",
                  "the coordinator is busy with other submissions; try again soon");
}

// Parses "/api/jobs/{id}..." ids: digits only, so "/api/jobs/abc" is a 404 rather than a throw.
std::optional<std::int64_t> parse_id(const std::string& s) {
  if (s.empty() || s.size() > 15 || s.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  return std::stoll(s);
}

const char* content_type_of(const std::string& name) {
  if (name.ends_with(".html")) return "text/html; charset=utf-8";
  if (name.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (name.ends_with(".css")) return "text/css; charset=utf-8";
  if (name.ends_with(".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

}  // namespace

std::pair<std::string, std::map<std::string, std::string>> split_target(std::string_view target) {
  const auto q = target.find('?');
  std::map<std::string, std::string> query;
  if (q != std::string_view::npos) {
    std::string_view rest = target.substr(q + 1);
    while (!rest.empty()) {
      const auto amp = rest.find('&');
      const std::string_view pair = rest.substr(0, amp);
      const auto eq = pair.find('=');
      if (!pair.empty())
        query[percent_decode(pair.substr(0, eq))] =
            eq == std::string_view::npos ? "" : percent_decode(pair.substr(eq + 1));
      if (amp == std::string_view::npos) break;
      rest = rest.substr(amp + 1);
    }
  }
  return {std::string(target.substr(0, q)), query};
}

void Api::handle(HttpRequest request, const boost::asio::ip::tcp::endpoint& peer,
                 HttpRespond respond) {
  const auto target = request.target();
  auto [path, query] = split_target(std::string_view(target.data(), target.size()));
  metrics_.http_received_bytes.add(static_cast<double>(request.body().size()));
  respond = [this, route = route_label(path), inner = std::move(respond)](HttpResponse response) {
    metrics_.http_requests.with({route, std::to_string(response.result_int())}).add();
    metrics_.http_sent_bytes.add(static_cast<double>(response.body().size()));
    inner(std::move(response));
  };
  try {
    const auto method = request.method();
    if (method == http::verb::post || method == http::verb::delete_)
      check_submitter(config_.submit, request, peer.address());
    route(request, path, query, peer.address().to_string(), respond);
  } catch (const ApiError& e) {
    respond(error_response(e));
  }
}

// Throws ApiError before it hands `respond` on, never after.
void Api::route(HttpRequest& request, const std::string& path, const Query& query,
                const std::string& client, HttpRespond& respond) {
  const auto method = request.method();
  const auto now = Clock::now();
  if (path == "/metrics") {
    if (method != http::verb::get)
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed", "GET /metrics");
    HttpResponse res{http::status::ok, request.version()};
    res.set(http::field::content_type, "text/plain; version=0.0.4; charset=utf-8");
    res.set(http::field::cache_control, "no-store");
    res.body() = metrics_.registry.expose();
    return respond(std::move(res));
  }
  if (!path.starts_with("/api/")) {
    if (method != http::verb::get && method != http::verb::head)
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed",
                     "the page only answers GET");
    return respond(static_file(path == "/" ? "index.html" : path.substr(1)));
  }
  if (path == "/api/workers") {
    if (method != http::verb::get)
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed", "GET /api/workers");
    return respond(json_response(200, workers_json(scheduler_.workers())));
  }
  if (path == "/api/predict") {
    if (method != http::verb::post)
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed", "POST /api/predict");
    return predict(request, query, respond);
  }
  if (path == "/api/jobs") {
    if (method == http::verb::post) return create_job(request, query, client, respond);
    if (method != http::verb::get)
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed", "GET or POST /api/jobs");
    // Pages: ?limit=N (1..1000) jobs with ids above ?after=ID, by id.
    const auto number = [&](const char* name, long long lo, long long hi, long long fallback) {
      auto it = query.find(name);
      if (it == query.end()) return fallback;
      const auto value = parse_id(it->second);
      if (!value || *value < lo || *value > hi)
        throw ApiError(Refusal::bad_request, "bad_query",
                       std::string(name) + " takes a number in [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]");
      return static_cast<long long>(*value);
    };
    const long long limit = number("limit", 1, 1000, 1000000000);
    const long long after = number("after", 0, 999999999999999LL, 0);
    nlohmann::json list = nlohmann::json::array();
    for (auto it = jobs_.all().upper_bound(after);
         it != jobs_.all().end() && static_cast<long long>(list.size()) < limit; ++it)
      list.push_back(job_summary_json(*it->second, now));
    return respond(json_response(200, list));
  }
  const std::string prefix = "/api/jobs/";
  if (path.starts_with(prefix)) {
    const std::string rest = path.substr(prefix.size());
    const auto slash = rest.find('/');
    const auto id = parse_id(rest.substr(0, slash));
    Job* job = id ? jobs_.find(*id) : nullptr;
    if (!job) throw ApiError(Refusal::not_found, "not_found", "no job " + rest.substr(0, slash));
    const std::string sub = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (sub.empty() && method == http::verb::get)
      return respond(json_response(200, job_status_json(*job, now)));
    if (sub.empty() && method == http::verb::delete_) {
      scheduler_.cancel(job->id);
      return respond(json_response(200, job_status_json(*job, now)));
    }
    if (sub == "image" && method == http::verb::get)
      return job_image(request, *job, query, respond);
    if (sub == "tiles" && method == http::verb::get)
      return job_tiles(request, *job, query, respond);
    if (sub == "rerender" && method == http::verb::post)
      return rerender(request, *job, client, respond);
    if (sub.empty() || sub == "image" || sub == "tiles" || sub == "rerender")
      throw ApiError(Refusal::method_not_allowed, "method_not_allowed",
                     std::string(request.method_string()) + " " + path);
  }
  throw ApiError(Refusal::not_found, "not_found", "no route " + path);
}

void Api::offload(HttpRespond respond, std::function<Finish(const IntakeBudget&)> work) {
  struct Pending {
    Pending(HttpRespond r, boost::asio::io_context& io) : respond(std::move(r)), deadline(io) {}
    HttpRespond respond;
    boost::asio::steady_timer deadline;
    bool answered = false;  // by the work or by the deadline, whichever comes first
  };
  auto pending = std::make_shared<Pending>(std::move(respond), io_);
  const IntakeBudget budget = IntakeBudget::starting_now(config_.max_intake_seconds);
  const bool queued = pool_.submit([pending, budget, work = std::move(work)] {
    Finish finish;
    try {
      budget.check("waiting for an intake thread");
      finish = work(budget);
    } catch (const ApiError& e) {
      finish = [e] { return error_response(e); };
    } catch (const std::bad_alloc&) {
      finish = [] {
        return json_response(413, {{"error", "over_budget"},
                                   {"detail", "the request needs more memory than is available"},
                                   {"limit", "memory"}});
      };
    } catch (const std::exception& e) {
      finish = [what = std::string(e.what())] {
        return json_response(500, {{"error", "internal"}, {"detail", what}});
      };
    }
    // On the io thread: the only place jobs and the scheduler are touched.
    return [pending, finish = std::move(finish)] {
      if (pending->answered) return;
      pending->answered = true;
      pending->deadline.cancel();
      try {
        pending->respond(finish());
      } catch (const ApiError& e) {
        pending->respond(error_response(e));
      }
    };
  });
  if (!queued) return pending->respond(error_response(busy()));
  pending->deadline.expires_at(budget.deadline);
  pending->deadline.async_wait([pending, budget](boost::system::error_code ec) {
    if (ec || pending->answered) return;
    pending->answered = true;
    pending->respond(error_response(budget.over_time("the deadline")));
  });
}

void Api::create_job(HttpRequest& request, const Query& query, const std::string& client,
                     HttpRespond& respond) {
  auto upload = std::make_shared<const HttpRequest>(std::move(request));
  submit_job(client, respond, [upload, query, scenes = config_.scenes_dir] {
    const auto type = (*upload)[http::field::content_type];
    return read_submission({upload->body(), std::string_view(type.data(), type.size()), query},
                           scenes);
  });
}

void Api::rerender(HttpRequest& request, const Job& job, const std::string& client,
                   HttpRespond& respond) {
  auto upload = std::make_shared<const HttpRequest>(std::move(request));
  // The bundle is shared, not copied here: the intake thread copies what admission needs.
  submit_job(client, respond, [upload, bundle = job.bundle, settings = job_settings_json(job)] {
    return read_rerender(upload->body(), *bundle, settings);
  });
}

void Api::submit_job(const std::string& client, HttpRespond& respond,
                     std::function<Submission()> read) {
  const auto over_cap = [this, &client] {
    return jobs_.unfinished_of(client) >= config_.max_jobs_per_client;
  };
  const ApiError too_many(
      Refusal::too_many_jobs, "too_many_jobs",
      "this client has " + std::to_string(config_.max_jobs_per_client) +
          " unfinished jobs, the limit; cancel some or wait",
      {{"limit", "max_jobs_per_client"}, {"value", config_.max_jobs_per_client}});
  if (over_cap()) throw too_many;
  offload(std::move(respond),
          [this, read = std::move(read), client, over_cap, too_many, limits = config_.limits,
           scenes = config_.scenes_dir](const IntakeBudget& budget) -> Finish {
            auto parsed = std::make_shared<JobRequest>(admit_job(read(), limits, scenes, budget));
            return [this, parsed, client, over_cap, too_many] {
              if (over_cap())
                throw too_many;  // other submissions of this client finished meanwhile
              fit_units_to_threads(*parsed, scheduler_.worker_totals().threads);
              std::function<std::int64_t(const JobRequest&)> store;
              if (config_.persistence)
                store = [p = config_.persistence](const JobRequest& r) {
                  try {
                    return p->admit(r);
                  } catch (const StoreError& e) {
                    throw ApiError(Refusal::cannot_store, "store_failed",
                                   "the job cannot be stored: " + e.cause());
                  }
                };
              Job* job = jobs_.create(std::move(*parsed), client, store);
              if (!job)
                throw ApiError(Refusal::busy, "busy",
                               "too many unfinished jobs; cancel some or wait");
              watch(*job);
              const Prediction prediction =
                  scheduler_.predict(job->seconds_per_pixel_pass, job->plan.total_cost);
              job->predicted_seconds = prediction.seconds;
              job->uncalibrated_prediction = prediction.uncalibrated;
              job->prediction_threads = prediction.threads;
              scheduler_.add_job(*job);
              HttpResponse res = json_response(201, job_status_json(*job, Clock::now()));
              res.set(http::field::location, "/api/jobs/" + std::to_string(job->id));
              return res;
            };
          });
}

void Api::predict(HttpRequest& request, const Query& query, HttpRespond& respond) {
  auto upload = std::make_shared<const HttpRequest>(std::move(request));
  offload(std::move(respond),
          [this, upload, query, limits = config_.limits,
           scenes = config_.scenes_dir](const IntakeBudget& budget) -> Finish {
            const auto type = (*upload)[http::field::content_type];
            auto job = std::make_shared<const JobRequest>(parse_job_request(
                {upload->body(), std::string_view(type.data(), type.size()), query}, limits, scenes,
                budget));
            const long long pixel_passes = make_plan(job->plan).total_cost;
            return [this, job, pixel_passes] {
              const Prediction p = scheduler_.predict(job->seconds_per_pixel_pass, pixel_passes);
              return json_response(
                  200, {{"predicted_seconds", p.seconds ? nlohmann::json(*p.seconds) : nullptr},
                        {"seconds_per_pixel_pass", job->seconds_per_pixel_pass},
                        {"lower_bound", job->probe_cut_short},
                        {"pixel_passes", pixel_passes},
                        {"threads", p.threads},
                        {"calibration", p.factor},
                        {"overhead_seconds", p.overhead_seconds},
                        {"effects", job->effects}});
            };
          });
}

void Api::job_image(const HttpRequest& request, Job& job, const Query& query,
                    HttpRespond& respond) {
  std::string format = "png";
  if (auto it = query.find("format"); it != query.end()) format = it->second;
  if (format != "png" && format != "exr")
    throw ApiError(Refusal::bad_request, "bad_request", "format must be png or exr");
  if (job.state() == JobState::Cancelled || job.state() == JobState::Failed)
    throw ApiError(Refusal::not_found, "no_image",
                   "job " + std::to_string(job.id) + " is " + to_string(job.state()) +
                       ": its image is not kept");
  // The version changes with every merged unit: an unchanged image is answered with 304.
  const auto etag_of = [id = job.id, format](std::uint64_t version) {
    return "\"" + std::to_string(id) + "-" + std::to_string(version) + "-" + format + "\"";
  };
  if (request[http::field::if_none_match] == etag_of(job.version())) {
    HttpResponse res{http::status::not_modified, request.version()};
    res.set(http::field::etag, etag_of(job.version()));
    return respond(std::move(res));
  }
  const auto reply = [etag_of, format, id = job.id](std::shared_ptr<const std::string> bytes,
                                                    std::uint64_t version) {
    if (!bytes)
      return json_response(404, {{"error", "no_image"},
                                 {"detail", "the image of job " + std::to_string(id) +
                                                " could not be encoded or was freed"}});
    HttpResponse res{http::status::ok, 11};
    res.set(http::field::content_type, format == "png" ? "image/png" : "image/x-exr");
    res.set(http::field::etag, etag_of(version));
    res.set(http::field::cache_control, "no-cache");
    if (format == "exr")
      res.set(http::field::content_disposition,
              "attachment; filename=\"tessera-" + std::to_string(id) + ".exr\"");
    res.body() = bytes;  // shared with the job, not copied
    return res;
  };
  if (auto it = job.final_encoded().find(format); it != job.final_encoded().end())
    return respond(reply(it->second, job.version()));
  const std::pair key{job.id, format};
  Encoding& cached = encoded_[key];
  if (cached.version == job.version() && cached.bytes)
    return respond(reply(cached.bytes, job.version()));
  auto waiter = [respond, reply](std::shared_ptr<const std::string> bytes, std::uint64_t version) {
    respond(reply(std::move(bytes), version));
  };
  // A done job's final image being made (on_released) is such a version too.
  const bool encoding = cached.encoding;
  if (encoding && cached.version == job.version()) return cached.waiting.push_back(waiter);
  // A new version: its frame buffer shared or copied here, its image made and encoded on the
  // pool. Requests waiting for an older version's encoding get this newer one.
  const std::uint64_t version = job.version();
  const bool queued = pool_.submit([this, key, version, snapshot = job.snapshot()] {
    std::shared_ptr<const std::string> bytes;
    try {
      bytes = std::make_shared<const std::string>(encode_image(snapshot.image(), key.second));
    } catch (const std::exception& e) {
      spdlog::error("encoding job {} as {}: {}", key.first, key.second, e.what());
    }
    return [this, key, version, bytes] { encoded(key, version, bytes, true); };
  });
  if (!queued) {
    if (!encoding) encoded_.erase(key);
    throw busy();
  }
  cached.version = version;
  cached.encoding = true;
  cached.bytes.reset();
  cached.waiting.push_back(waiter);
  std::erase_if(encoded_, [&](const auto& entry) {
    return !entry.second.encoding && !jobs_.find(entry.first.first);
  });
}

void Api::encoded(const std::pair<std::int64_t, std::string>& key, std::uint64_t version,
                  std::shared_ptr<const std::string> bytes, bool keep) {
  auto it = encoded_.find(key);
  if (it == encoded_.end() || it->second.version != version) return;  // superseded
  auto waiting = std::move(it->second.waiting);
  if (bytes && keep) {
    it->second.encoding = false;
    it->second.bytes = bytes;
    it->second.waiting.clear();
  } else {
    encoded_.erase(it);
  }
  for (auto& w : waiting) w(bytes, version);
}

namespace {

// A done job's image is encoded in both once (on_released) and kept with the job.
constexpr const char* kFinalFormats[] = {"png", "exr"};

// The longest a /tiles request may be held (?wait=): well under the HTTP read timeout.
constexpr long long kMaxTilesWaitMs = 20000;
// How long a done job keeps its last tile records for pages catching up with its end.
constexpr auto kDoneTilesKept = std::chrono::seconds(30);

HttpResponse tiles_response(const Job& job, std::size_t since, bool gzip_it) {
  HttpResponse res{http::status::ok, 11};
  res.set(http::field::content_type, "application/octet-stream");
  res.set(http::field::cache_control, "no-store");
  std::string body = encode_tiles(job, since);
  if (gzip_it) {
    res.set(http::field::content_encoding, "gzip");
    body = gzip(body);
  }
  res.body() = std::move(body);
  return res;
}

}  // namespace

void Api::job_tiles(const HttpRequest& request, Job& job, const Query& query,
                    HttpRespond& respond) {
  const auto count = [&](const char* name, long long most) -> long long {
    auto it = query.find(name);
    if (it == query.end()) return 0;
    const auto n = parse_id(it->second);
    if (!n || *n > most)
      throw ApiError(Refusal::bad_request, "bad_request",
                     std::string(name) + " must be a count up to " + std::to_string(most));
    return *n;
  };
  const auto since = static_cast<std::size_t>(count("since", 0xffffffffLL));
  const long long wait_ms = count("wait", kMaxTilesWaitMs);
  const auto encoding = request[http::field::accept_encoding];
  const bool gzip_it = accepts_gzip(std::string_view(encoding.data(), encoding.size()));
  if (wait_ms == 0 || since < job.tiles_next() || job.finished_state())
    return respond(tiles_response(job, since, gzip_it));
  auto waiter = std::make_shared<TilesWaiter>();
  waiter->since = since;
  waiter->gzip = gzip_it;
  waiter->respond = std::move(respond);
  waiter->timer = std::make_unique<boost::asio::steady_timer>(io_);
  waiter->timer->expires_after(std::chrono::milliseconds(wait_ms));
  waiter->timer->async_wait(
      [this, id = job.id, weak = std::weak_ptr(waiter)](boost::system::error_code ec) {
        auto w = weak.lock();
        if (ec || !w) return;  // answered by a merge first
        auto held = tile_waiters_.find(id);
        if (held == tile_waiters_.end() || std::erase(held->second, w) == 0) return;
        if (held->second.empty()) tile_waiters_.erase(held);
        if (Job* still = jobs_.find(id))
          return w->respond(tiles_response(*still, w->since, w->gzip));
        w->respond(json_response(404, {{"error", "not_found"}, {"detail", "the job is gone"}}));
      });
  tile_waiters_[job.id].push_back(std::move(waiter));
}

void Api::watch(Job& job) {
  job.on_released = [this](Job& released) { on_released(released); };
  job.on_changed = [this](Job& changed) { on_changed(changed); };
}

void Api::on_changed(Job& job) {
  if (!tile_waiters_.count(job.id)) return;
  boost::asio::post(io_, [this, id = job.id] { answer_tile_waiters(id); });
}

void Api::answer_tile_waiters(std::int64_t job_id) {
  auto it = tile_waiters_.find(job_id);
  if (it == tile_waiters_.end()) return;
  auto waiters = std::move(it->second);
  tile_waiters_.erase(it);
  Job* job = jobs_.find(job_id);
  for (auto& w : waiters) {
    w->timer->cancel();
    if (job)
      w->respond(tiles_response(*job, w->since, w->gzip));
    else
      w->respond(json_response(404, {{"error", "not_found"}, {"detail", "the job is gone"}}));
  }
}

void Api::on_released(Job& job) {
  const std::int64_t id = job.id;
  if (job.state() != JobState::Done) {
    // Cancelled or failed: its cached encodings go, and requests waiting for one get a 404.
    for (auto it = encoded_.begin(); it != encoded_.end();) {
      if (it->first.first != id) {
        ++it;
        continue;
      }
      auto waiting = std::move(it->second.waiting);
      const std::uint64_t version = it->second.version;
      it = encoded_.erase(it);
      for (auto& w : waiting) w(nullptr, version);
    }
    return;
  }
  // Pages still painting the last merges get them for a while; then only the images stay.
  auto keep = std::make_shared<boost::asio::steady_timer>(io_, kDoneTilesKept);
  keep->async_wait([this, id, keep](boost::system::error_code ec) {
    if (Job* done = jobs_.find(id); done && !ec) done->free_buffers();
  });
  // Made from the shared frame buffer and encoded on the pool, even when it is full: the
  // service owes every done job its image. Requests for it meanwhile wait for this encoding
  // (never served an older version's), as do those already waiting for a preview.
  const std::uint64_t version = job.version();
  for (const char* format : kFinalFormats) {
    Encoding& final_encoding = encoded_[{id, format}];
    final_encoding.version = version;
    final_encoding.encoding = true;
    final_encoding.bytes.reset();
  }
  pool_.submit(
      [this, id, version, snapshot = job.snapshot(), record = JobPersistence::DoneJob(job)] {
        Job::Encodings encodings;
        try {
          const Image image = snapshot.image();
          for (const char* format : kFinalFormats) {
            auto bytes = std::make_shared<const std::string>(encode_image(image, format));
            encodings[format] = bytes;
            // Requests for this format (the page's PNG) need not wait for the next one.
            boost::asio::post(io_, [this, id, version, format, bytes] {
              encoded({id, format}, version, bytes, true);
            });
          }
        } catch (const std::exception& e) {
          // Its frame buffer stays: later requests make and encode it again (job_image).
          spdlog::error("the final image of job {}: {}", id, e.what());
          encodings.clear();
        }
        // Stored here, off the io thread (store_images).
        std::optional<StoreError> unstored;
        if (config_.persistence && !encodings.empty())
          unstored = config_.persistence->store_images(record, encodings);
        return std::function<void()>([this, id, version, encodings, unstored] {
          Job* done = jobs_.find(id);  // gone if deleted meanwhile (its write failed or undone)
          if (done && !encodings.empty()) {
            done->keep_encodings(encodings);
            if (unstored) config_.persistence->fail_unstored(*done, *unstored);
          }
          // The job keeps them now (one that could not store them failed: no image), not
          // this cache; requests still waiting (for a format that failed) get a 404.
          const bool kept = done && !encodings.empty() && done->state() == JobState::Done;
          for (const char* format : kFinalFormats)
            encoded({id, format}, version, kept ? encodings.at(format) : nullptr, false);
        });
      },
      true);
}

HttpResponse Api::static_file(const std::string& name) {
  // Only plain file names directly in the web folder: no traversal, no hidden files.
  if (name.empty() || name.front() == '.' ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") !=
          std::string::npos)
    throw ApiError(Refusal::not_found, "not_found", "no page " + name);
  std::ifstream in(config_.web_dir / name, std::ios::binary);
  if (!in) throw ApiError(Refusal::not_found, "not_found", "no page " + name);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  HttpResponse res{http::status::ok, 11};
  res.set(http::field::content_type, content_type_of(name));
  res.set(http::field::cache_control, "no-cache");
  res.body() = bytes.str();
  return res;
}

}  // namespace tessera
