#include "coordinator/http/api.h"

#include <cctype>
#include <fstream>
#include <sstream>

#include "coordinator/http/image_codec.h"
#include "coordinator/http/job_json.h"
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

HttpResponse error_response(const ApiError& e) { return json_response(e.status(), e.body()); }

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

HttpResponse Api::handle(const HttpRequest& request) {
  const auto target = request.target();
  auto [path, query] = split_target(std::string_view(target.data(), target.size()));
  try {
    return route(request, path, query);
  } catch (const ApiError& e) {
    return error_response(e);
  }
}

HttpResponse Api::route(const HttpRequest& request, const std::string& path,
                        const std::map<std::string, std::string>& query) {
  const auto method = request.method();
  const auto now = Clock::now();
  if (!path.starts_with("/api/")) {
    if (method != http::verb::get && method != http::verb::head)
      throw ApiError(405, "method_not_allowed", "the page only answers GET");
    return static_file(path == "/" ? "index.html" : path.substr(1));
  }
  if (path == "/api/workers") {
    if (method != http::verb::get) throw ApiError(405, "method_not_allowed", "GET /api/workers");
    return json_response(200, scheduler_.workers_json());
  }
  if (path == "/api/predict") {
    if (method != http::verb::post) throw ApiError(405, "method_not_allowed", "POST /api/predict");
    return predict(request, query);
  }
  if (path == "/api/jobs") {
    if (method == http::verb::post) return create_job(request, query);
    if (method != http::verb::get)
      throw ApiError(405, "method_not_allowed", "GET or POST /api/jobs");
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [id, job] : jobs_.all()) list.push_back(job_summary_json(*job, now));
    return json_response(200, list);
  }
  const std::string prefix = "/api/jobs/";
  if (path.starts_with(prefix)) {
    const std::string rest = path.substr(prefix.size());
    const auto slash = rest.find('/');
    const auto id = parse_id(rest.substr(0, slash));
    Job* job = id ? jobs_.find(*id) : nullptr;
    if (!job) throw ApiError(404, "not_found", "no job " + rest.substr(0, slash));
    const std::string sub = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (sub.empty() && method == http::verb::get)
      return json_response(200, job_status_json(*job, now));
    if (sub.empty() && method == http::verb::delete_) {
      scheduler_.cancel(job->id);
      return json_response(200, job_status_json(*job, now));
    }
    if (sub == "image" && method == http::verb::get) return job_image(request, *job, query);
    if (sub == "tiles" && method == http::verb::get) {
      std::size_t since = 0;
      if (auto it = query.find("since"); it != query.end()) {
        const auto n = parse_id(it->second);
        if (!n) throw ApiError(400, "bad_request", "since must be a count");
        since = static_cast<std::size_t>(*n);
      }
      return json_response(200, job_tiles_json(*job, since));
    }
    if (sub.empty() || sub == "image" || sub == "tiles")
      throw ApiError(405, "method_not_allowed", std::string(request.method_string()) + " " + path);
  }
  throw ApiError(404, "not_found", "no route " + path);
}

HttpResponse Api::create_job(const HttpRequest& request,
                             const std::map<std::string, std::string>& query) {
  const auto content_type = request[http::field::content_type];
  JobUpload upload{request.body(), std::string_view(content_type.data(), content_type.size()),
                   query};
  Job* job = jobs_.create(parse_job_request(upload, config_.limits, config_.scenes_dir));
  if (!job) throw ApiError(503, "busy", "too many unfinished jobs; cancel some or wait");
  const Prediction prediction =
      scheduler_.predict(job->seconds_per_pixel_pass, job->plan.total_cost);
  job->predicted_seconds = prediction.seconds;
  job->uncalibrated_prediction = prediction.uncalibrated;
  job->prediction_threads = prediction.threads;
  scheduler_.add_job(*job);
  HttpResponse res = json_response(201, job_status_json(*job, Clock::now()));
  res.set(http::field::location, "/api/jobs/" + std::to_string(job->id));
  return res;
}

HttpResponse Api::predict(const HttpRequest& request,
                          const std::map<std::string, std::string>& query) {
  const auto content_type = request[http::field::content_type];
  const JobRequest job = parse_job_request(
      {request.body(), std::string_view(content_type.data(), content_type.size()), query},
      config_.limits, config_.scenes_dir);
  const long long pixel_passes = make_plan(job.plan).total_cost;
  const Prediction p = scheduler_.predict(job.seconds_per_pixel_pass, pixel_passes);
  return json_response(200,
                       {{"predicted_seconds", p.seconds ? nlohmann::json(*p.seconds) : nullptr},
                        {"seconds_per_pixel_pass", job.seconds_per_pixel_pass},
                        {"pixel_passes", pixel_passes},
                        {"threads", p.threads},
                        {"calibration", p.factor},
                        {"overhead_seconds", p.overhead_seconds},
                        {"effects", job.effects}});
}

HttpResponse Api::job_image(const HttpRequest& request, const Job& job,
                            const std::map<std::string, std::string>& query) {
  std::string format = "png";
  if (auto it = query.find("format"); it != query.end()) format = it->second;
  if (format != "png" && format != "exr")
    throw ApiError(400, "bad_request", "format must be png or exr");
  // The version changes with every merged unit: an unchanged image is answered with 304.
  const std::string etag =
      "\"" + std::to_string(job.id) + "-" + std::to_string(job.version) + "-" + format + "\"";
  if (request[http::field::if_none_match] == etag) {
    HttpResponse res{http::status::not_modified, request.version()};
    res.set(http::field::etag, etag);
    return res;
  }
  HttpResponse res{http::status::ok, request.version()};
  res.set(http::field::content_type, format == "png" ? "image/png" : "image/x-exr");
  res.set(http::field::etag, etag);
  res.set(http::field::cache_control, "no-cache");
  if (format == "exr")
    res.set(http::field::content_disposition,
            "attachment; filename=\"tessera-" + std::to_string(job.id) + ".exr\"");
  EncodedImage& cached = encoded_[{job.id, format}];
  if (cached.bytes.empty() || cached.version != job.version) {
    cached = {job.version, encode_image(job.image(), format)};
    std::erase_if(encoded_, [&](const auto& entry) { return !jobs_.find(entry.first.first); });
  }
  res.body() = cached.bytes;
  return res;
}

HttpResponse Api::static_file(const std::string& name) {
  // Only plain file names directly in the web folder: no traversal, no hidden files.
  if (name.empty() || name.front() == '.' ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") !=
          std::string::npos)
    throw ApiError(404, "not_found", "no page " + name);
  std::ifstream in(config_.web_dir / name, std::ios::binary);
  if (!in) throw ApiError(404, "not_found", "no page " + name);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  HttpResponse res{http::status::ok, 11};
  res.set(http::field::content_type, content_type_of(name));
  res.set(http::field::cache_control, "no-cache");
  res.body() = bytes.str();
  return res;
}

}  // namespace tessera
