#include "client/submit_job.h"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <thread>

#include "client/http_client.h"
#include "client/progress_line.h"
#include "client/scene_bundle.h"

namespace tessera {
namespace {

// How often the job's status is asked for: often enough for a smooth progress line, rarely
// enough to cost the coordinator nothing.
constexpr auto kPollInterval = std::chrono::milliseconds(100);

// Ctrl-C or SIGTERM while the job runs: the job is cancelled on the coordinator, not left
// running for nobody. The handler only sets the flag; the polling loop acts on it.
volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_interrupt(int) { interrupted = 1; }

// "the coordinator answered 400: settings.region ... (scene.sdl:3:7)" from an error answer's
// JSON (docs/SERVICE.md), or its raw text when it is not JSON.
std::string refusal(const std::string& what, const HttpReply& reply) {
  std::string text = what + ": the coordinator answered " + std::to_string(reply.status);
  const nlohmann::json j = nlohmann::json::parse(reply.body, nullptr, false);
  if (!j.is_object()) return text + ": " + reply.body.substr(0, 200);
  text += ": " + j.value("detail", j.value("error", std::string("no detail")));
  return text;
}

nlohmann::json json_of(const HttpReply& reply, const std::string& what) {
  nlohmann::json j = nlohmann::json::parse(reply.body, nullptr, false);
  if (reply.status != 200 && reply.status != 201) throw std::runtime_error(refusal(what, reply));
  if (!j.is_object()) throw std::runtime_error(what + ": the coordinator's answer is not JSON");
  return j;
}

}  // namespace

int submit_job(const SubmitOptions& o) {
  // From the start: the job may be running before the answer to its submission arrives.
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  try {
    const HttpClient http(o.coordinator, o.token, o.tls);
    const SceneBundle scene = bundle_scene(
        o.scene_path, o.root.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.root),
        o.settings.load.strict);
    if (!o.quiet)
      for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (interrupted) return 130;  // before anything was sent
    std::string boundary;
    std::string body = multipart_body(scene.bundle, settings_json(o.settings), boundary);
    const nlohmann::json created = json_of(
        http.post("/api/jobs", "multipart/form-data; boundary=" + boundary, std::move(body)),
        "submitting " + o.scene_path);
    const std::string job = "/api/jobs/" + std::to_string(created.at("id").get<long long>());
    if (!o.quiet)
      std::printf("submitted %s as %s%s\n", o.scene_path.c_str(), http.base().c_str(), job.c_str());

    ProgressLine progress(stdout, isatty(STDOUT_FILENO) != 0);
    nlohmann::json status = created;
    while (true) {
      if (!o.quiet) progress.show(status);
      const std::string state = status.value("state", "");
      if (state != "queued" && state != "running") break;
      if (interrupted) {
        progress.finish();
        const HttpReply cancelled = http.del(job);
        std::fprintf(
            stderr, "tessera-submit: interrupted: job %s %s\n", job.c_str(),
            cancelled.status == 200 ? "cancelled" : refusal("cancelling", cancelled).c_str());
        return 130;  // the shell's status for a command ended by SIGINT
      }
      std::this_thread::sleep_for(kPollInterval);
      if (interrupted) continue;
      status = json_of(http.get(job), "following " + job);
    }
    progress.finish();
    if (status.value("state", "") != "done") {
      std::fprintf(stderr, "tessera-submit: job %s ended %s%s%s\n", job.c_str(),
                   status.value("state", "?").c_str(), status.contains("error") ? ": " : "",
                   status.value("error", "").c_str());
      return 1;
    }
    if (o.output_path.empty()) return 0;
    const bool exr = o.output_path.ends_with(".exr");
    const HttpReply image = http.get(job + "/image" + (exr ? "?format=exr" : ""));
    if (image.status != 200) throw std::runtime_error(refusal("downloading the image", image));
    std::ofstream out(o.output_path, std::ios::binary);
    out.write(image.body.data(), static_cast<std::streamsize>(image.body.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + o.output_path);
    if (!o.quiet)
      std::printf("wrote %s (%s in %s)\n", o.output_path.c_str(), stage_text(status).c_str(),
                  seconds_text(status.value("elapsed_seconds", nlohmann::json())).c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tessera-submit: %s\n", e.what());
    return 1;
  }
}

}  // namespace tessera
