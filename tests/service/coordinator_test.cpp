// Unit tests of the coordinator's pure parts: request targets, job requests, the
// merge of unit results into the frame buffer and what is shown, what finished jobs keep, and who
// may submit.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "common/image/decoded_texture.h"
#include "common/settings/settings_schema.h"
#include "coordinator/http/api.h"
#include "coordinator/http/job_json.h"
#include "coordinator/http/multipart.h"
#include "coordinator/http/refusal_status.h"
#include "coordinator/http/submission.h"
#include "coordinator/http/submit_policy.h"
#include "coordinator/jobs/api_error.h"
#include "coordinator/jobs/job.h"
#include "coordinator/jobs/job_store.h"
#include "coordinator/options.h"
#include "coordinator/scheduler/scheduler.h"

namespace tessera {
namespace {

TEST(SplitTarget, DecodesQueries) {
  const auto [path, query] = split_target("/api/jobs/3/image?format=exr&main=a%2Fb.sdl&x=1+2&flag");
  EXPECT_EQ(path, "/api/jobs/3/image");
  EXPECT_EQ(query.at("format"), "exr");
  EXPECT_EQ(query.at("main"), "a/b.sdl");
  EXPECT_EQ(query.at("x"), "1 2");
  EXPECT_EQ(query.at("flag"), "");
}

TEST(ParseSettings, DefaultsFollowTheRenderer) {
  JobRequest r;
  parse_settings(nlohmann::json::object(), ServiceLimits{}, r);
  const RenderSettings defaults;
  EXPECT_EQ(r.spec.settings.width, defaults.width);
  EXPECT_EQ(r.spec.settings.aa_samples, defaults.aa_samples);
  EXPECT_EQ(r.spec.settings.shadows, ShadowMode::Hard);
  EXPECT_EQ(r.spec.settings.cone_samples, defaults.cone_samples);
  EXPECT_EQ(r.spec.settings.shadow_jitter, defaults.shadow_jitter);
  EXPECT_FALSE(r.spec.settings.normalize_colors);
  EXPECT_EQ(r.plan.order, UnitOrder::Centre);
  EXPECT_TRUE(r.plan.progressive);
  EXPECT_FALSE(r.spec.overrides.max_depth.has_value());
}

TEST(ParseSettings, ReadsTheShadingSettings) {
  JobRequest r;
  parse_settings(nlohmann::json::parse(R"({"shadows": "soft", "cone_samples": 5,
      "shadow_jitter": 0.5, "normalize": true, "brightness": 0.75})"),
                 ServiceLimits{}, r);
  EXPECT_EQ(r.spec.settings.shadows, ShadowMode::Soft);
  EXPECT_EQ(r.spec.settings.cone_samples, 5);
  EXPECT_EQ(r.spec.settings.shadow_jitter, 0.5);
  EXPECT_TRUE(r.spec.settings.normalize_colors);
  EXPECT_EQ(r.spec.settings.normalize_brightness, 0.75);
}

TEST(ParseSettings, RefusesWhatIsOutOfLimits) {
  const ServiceLimits limits;
  for (const char* bad :
       {R"({"aa": 3})", R"({"width": 0})", R"({"width": 5000, "height": 7000})",
        R"({"width": 8192, "height": 8192})", R"({"width": 16385})", R"({"passes": 1000})",
        R"({"seed": -2})", R"({"order": "spiral"})", R"({"bvh": 1})", R"({"unknown": 1})",
        R"({"max_depth": 40})", R"({"min_weight": 2})", R"({"shadows": "penumbral"})",
        R"({"shadows": 2})", R"({"cone_samples": 0})", R"({"cone_samples": 65})",
        R"({"shadow_jitter": -0.1})", R"({"normalize": "yes"})", R"({"brightness": -1})"}) {
    JobRequest r;
    EXPECT_THROW(parse_settings(nlohmann::json::parse(bad), limits, r), ApiError) << bad;
  }
}

TEST(ParseSettings, TakesEveryChoiceOfTheSchema) {
  for (const char* name : {"order", "preview", "shadows"})
    for (const std::string_view choice : find_setting(name)->choices) {
      JobRequest r;
      EXPECT_NO_THROW(parse_settings({{name, std::string(choice)}}, ServiceLimits{}, r))
          << name << choice;
    }
}

TEST(ParseSettings, ServiceLimitsNarrowTheSchemasRange) {
  ServiceLimits limits;
  limits.max_passes = 4096;  // the schema's own range
  JobRequest r;
  parse_settings({{"passes", 4096}}, limits, r);
  EXPECT_EQ(r.spec.settings.passes, 4096);
  limits.max_passes = 8;
  try {
    parse_settings({{"passes", 9}}, limits, r);
    FAIL() << "expected the service's limit";
  } catch (const ApiError& e) {
    EXPECT_EQ(e.body()["detail"], "settings.passes must be an integer in [1, 8]");
  }
}

// Jitter takes the same range as tessera-render's --jitter and the wire (issue 19 §2).
TEST(ParseSettings, JitterTakesTheSchemasRange) {
  JobRequest r;
  parse_settings({{"jitter", 16}}, ServiceLimits{}, r);
  EXPECT_EQ(r.spec.settings.jitter, 16.0);
  EXPECT_THROW(parse_settings({{"jitter", 16.5}}, ServiceLimits{}, r), ApiError);
}

// A region (issue 21 §4) sets the plan's area; outside the image it is a 400 naming it.
TEST(ParseSettings, ARegionSetsThePlansAreaInsideTheImage) {
  JobRequest r;
  parse_settings(nlohmann::json::parse(R"({"width": 64, "height": 48, "region": [8, 4, 64, 48]})"),
                 ServiceLimits{}, r);
  EXPECT_EQ(r.plan.region, (PixelRect{8, 4, 64, 48}));
  EXPECT_EQ(r.spec.settings.region, (PixelRect{8, 4, 64, 48}));
  try {
    parse_settings(nlohmann::json::parse(R"({"width": 64, "height": 48, "region": [0, 0, 65, 8]})"),
                   ServiceLimits{}, r);
    FAIL() << "expected a region outside the image to be refused";
  } catch (const ApiError& e) {
    EXPECT_EQ(http_status(e.refusal()), 400);
    EXPECT_EQ(e.body()["detail"],
              "settings.region [0, 0, 65, 8] must lie inside the 64x48 image (x1 <= width, y1 <= "
              "height)");
  }
  JobRequest whole;
  parse_settings(nlohmann::json::parse(R"({"width": 64})"), ServiceLimits{}, whole);
  EXPECT_EQ(whole.plan.region, std::nullopt);
}

TEST(ParseJobRequest, SceneErrorsNameLineAndColumn) {
  const std::string body = R"({"scene": "sphere\n  nosuchkeyword\n"})";
  try {
    parse_job_request({body, "application/json", {}}, ServiceLimits{}, std::nullopt);
    FAIL() << "expected a scene error";
  } catch (const ApiError& e) {
    EXPECT_EQ(http_status(e.refusal()), 400);
    EXPECT_EQ(e.body()["error"], "scene_error");
    EXPECT_EQ(e.body()["line"], 2);
    EXPECT_EQ(e.body()["column"], 3);
  }
}

TEST(ParseJobRequest, TheBundleHoldsWhatTheSceneRead) {
  const std::string body =
      R"({"scene": "include parts/p.sdl\n", "files": {"parts/p.sdl": "sphere", "unused.obj": ""}})";
  const JobRequest r =
      parse_job_request({body, "application/json", {}}, ServiceLimits{}, std::nullopt);
  EXPECT_EQ(r.bundle.main, "scene.sdl");
  EXPECT_EQ(r.bundle.files.size(), 2u);
  EXPECT_TRUE(r.bundle.files.count("parts/p.sdl"));
  EXPECT_THROW(parse_job_request({"{}", "text/plain", {}}, ServiceLimits{}, std::nullopt),
               ApiError);
}

// A field outside VRML97 is a warning by default and the job goes on; "strict": true makes
// it the scene error it was (issue 20 §3).
TEST(ParseJobRequest, StrictTurnsLoadWarningsIntoSceneErrors) {
  const std::string world =
      R"("#VRML V2.0 utf8\nShape { geometry Sphere { radius 2 shadows TRUE } }\n")";
  const JobRequest lenient =
      parse_job_request({R"({"format": "vrml", "scene": )" + world + "}", "application/json", {}},
                        ServiceLimits{}, std::nullopt);
  ASSERT_FALSE(lenient.warnings.empty());
  EXPECT_NE(lenient.warnings.front().find("shadows"), std::string::npos)
      << lenient.warnings.front();
  try {
    parse_job_request(
        {R"({"format": "vrml", "settings": {"strict": true}, "scene": )" + world + "}",
         "application/json",
         {}},
        ServiceLimits{}, std::nullopt);
    FAIL() << "expected a scene error";
  } catch (const ApiError& e) {
    EXPECT_EQ(http_status(e.refusal()), 400);
    EXPECT_EQ(e.body()["error"], "scene_error");
    EXPECT_EQ(e.body()["line"], 2);
  }
}

// An image texture's file travels with the job like a mesh file, so a worker with no files of
// its own renders it; the coordinator decodes it once to check it (ASCII PPM keeps the JSON
// body text).
TEST(ParseJobRequest, TheBundleHoldsTheImageTexture) {
  const std::string body = R"({"scene": "imageTexture tex/c.ppm 1 1 1\nsphere\n", "files": )"
                           R"({"tex/c.ppm": "P3\n2 1\n255\n255 0 0  0 0 255\n"}})";
  const JobRequest r =
      parse_job_request({body, "application/json", {}}, ServiceLimits{}, std::nullopt);
  EXPECT_EQ(r.bundle.files.size(), 2u);
  EXPECT_EQ(r.bundle.files.count("tex/c.ppm"), 1u);
  // Workers have no image library: the texture travels decoded (decoded_texture.h).
  EXPECT_TRUE(is_decoded_texture(r.bundle.files.at("tex/c.ppm")));
  EXPECT_NE(std::find(r.effects.begin(), r.effects.end(), "image_texture"), r.effects.end());
  const std::string broken =
      R"({"scene": "imageTexture c.ppm 1 1 1\nsphere\n", "files": {"c.ppm": "P3 junk"}})";
  try {
    parse_job_request({broken, "application/json", {}}, ServiceLimits{}, std::nullopt);
    FAIL() << "expected a scene error";
  } catch (const ApiError& e) {
    EXPECT_EQ(http_status(e.refusal()), 400);
    EXPECT_EQ(e.body()["error"], "scene_error");
    EXPECT_EQ(e.body()["line"], 1);
    EXPECT_EQ(e.body()["column"], 14);
  }
}

// A rerender (POST /api/jobs/{id}/rerender) builds on the job's settings as its status shows
// them: every setting of a job request reads back as it was given, and parses to the same job.
// Only "strict" is not kept: it decides only whether admission refuses load warnings, which
// the job's bundle passed already.
TEST(JobSettingsJson, EverySettingRoundTripsThroughTheStatus) {
  const nlohmann::json common = nlohmann::json::parse(R"({"width": 64, "height": 48, "aa": 5,
      "stochastic": true, "jitter": 0.375, "seed": 18446744073709551615, "passes": 3,
      "time_samples": 2, "bvh": false, "shadows": "soft", "cone_samples": 5,
      "shadow_jitter": 0.3, "max_depth": 3, "min_weight": 0.05, "progressive": false,
      "order": "scanline", "preview": "area", "priority": 7,
      "camera": {"eye": [1, 2.5, 7], "look_at": [0, 0.1, 0], "up": [0, 1, 0.2], "fov": 33.3}})");
  nlohmann::json normalized = common, region = common;
  normalized.update({{"normalize", true}, {"brightness", 0.5}});
  region.update({{"region", {3, 4, 60, 40}}, {"normalize", false}, {"brightness", 1.5}});
  std::set<std::string> given;
  for (const nlohmann::json& settings : {normalized, region}) {
    JobRequest first;
    parse_settings(settings, ServiceLimits{}, first);
    JobStore store(4);
    const Job* job = store.create(std::move(first));
    EXPECT_EQ(job_settings_json(*job), settings);
    JobRequest again;
    parse_settings(job_settings_json(*job), ServiceLimits{}, again);
    EXPECT_EQ(job_settings_json(*store.create(std::move(again))), settings);
    for (const auto& [key, value] : settings.items()) given.insert(key);
  }
  for (const SettingSpec& spec : settings_schema()) {
    if (spec.layers & kJobRequest && spec.name != "strict") {
      EXPECT_TRUE(given.count(std::string(spec.name))) << spec.name << " is not tested";
    }
  }
}

// The body's settings replace the job's, null drops one; the bundle is the job's as admitted,
// its texture decoded, and admits again to the same bundle.
TEST(ReadRerender, TheBodysSettingsGoOverTheJobsBundleAndSettings) {
  const std::string body = R"({"scene": "imageTexture tex/c.ppm 1 1 1\nsphere\n", "files": )"
                           R"({"tex/c.ppm": "P3\n2 1\n255\n255 0 0  0 0 255\n"},)"
                           R"("settings": {"width": 32, "aa": 5, "region": [0, 0, 8, 8]}})";
  JobStore store(4);
  const Job* job = store.create(
      parse_job_request({body, "application/json", {}}, ServiceLimits{}, std::nullopt));
  const Submission same = read_rerender("", *job->bundle, job_settings_json(*job));
  EXPECT_EQ(same.settings, job_settings_json(*job));
  const JobRequest again = admit_job(same, ServiceLimits{}, std::nullopt);
  EXPECT_EQ(again.bundle, *job->bundle);

  const Submission moved = read_rerender(
      R"({"settings": {"aa": 9, "region": null, "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0],
          "up": [0, 1, 0], "fov": 50}}})",
      *job->bundle, job_settings_json(*job));
  EXPECT_EQ(moved.settings["aa"], 9);
  EXPECT_EQ(moved.settings["width"], 32);
  EXPECT_FALSE(moved.settings.contains("region"));
  EXPECT_EQ(moved.settings["camera"]["fov"], 50);
  EXPECT_EQ(moved.main, "scene.sdl");
  EXPECT_EQ(moved.files, job->bundle->files);

  for (const char* bad : {"[]", R"({"scene": "sphere"})", R"({"settings": 3})",
                          R"({"settings": {"colour": null}})"}) {
    try {
      read_rerender(bad, *job->bundle, job_settings_json(*job));
      FAIL() << "expected " << bad << " to be refused";
    } catch (const ApiError& e) {
      EXPECT_EQ(http_status(e.refusal()), 400) << bad;
    }
  }
}

TEST(Multipart, ReadsFieldsAndFiles) {
  const std::string body =
      "preamble\r\n--XyZ\r\nContent-Disposition: form-data; name=\"scene\"\r\n\r\n"
      "include parts/p.sdl\r\n--XyZ\r\nContent-Disposition: form-data; name=\"file\"; "
      "filename=\"parts/p.sdl\"\r\nContent-Type: text/plain\r\n\r\nsphere\r\n--XyZ\r\n"
      "Content-Disposition: form-data; name=\"settings\"\r\n\r\n{\"width\": 8}\r\n--XyZ--\r\n";
  const auto boundary = multipart_boundary("multipart/form-data; boundary=XyZ");
  ASSERT_EQ(boundary, "XyZ");
  const auto parts = parse_multipart(body, *boundary);
  ASSERT_EQ(parts.size(), 3u);
  EXPECT_EQ(parts[1].name, "file");
  EXPECT_EQ(parts[1].filename, "parts/p.sdl");
  EXPECT_EQ(parts[1].data, "sphere");
  const JobRequest r = parse_job_request({body, "multipart/form-data; boundary=XyZ", {}},
                                         ServiceLimits{}, std::nullopt);
  EXPECT_EQ(r.spec.settings.width, 8);
  EXPECT_EQ(r.bundle.files.size(), 2u);
  EXPECT_THROW(parse_multipart("--XyZ\r\nno end", "XyZ"), std::runtime_error);
  EXPECT_FALSE(multipart_boundary("text/plain; boundary=x"));
}

Job make_job(int w, int h, int passes) {
  JobSpec spec;
  spec.settings.width = w;
  spec.settings.height = h;
  spec.settings.passes = passes;
  PlanOptions plan{.width = w, .height = h, .passes = passes};
  return Job(1, Bundle{"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}}, spec, plan, 1);
}

// A distinct value per pixel and pass, as a worker would return it.
std::vector<float> values_for(const Job& job, int unit) {
  std::vector<float> v;
  const int pass = job.plan.stages[job.plan.units[unit].stage].pass;
  for (PixelCoord p : expand(job.plan.units[unit].pixels))
    for (int c = 0; c < 3; ++c) v.push_back(static_cast<float>(p.x + 100 * p.y + 0.25 * pass + c));
  return v;
}

TEST(JobMerge, CoarseBlocksShowTheirAnchorUntilFinerLevelsArrive) {
  Job job = make_job(5, 3, 1);  // levels of side 4, 2, 1
  job.record_dispatch(0, Clock::now());
  job.apply_result(0, values_for(job, 0), RenderStats{});
  const Image first = job.snapshot().image();
  EXPECT_EQ(first.get(3, 2).r, 0.0f);  // block of anchor (0, 0)
  EXPECT_EQ(first.get(4, 1).r, 4.0f);  // block of anchor (4, 0)
  // Finer results win regardless of arrival order.
  for (int u = static_cast<int>(job.plan.units.size()) - 1; u >= 1; --u)
    job.apply_result(u, values_for(job, u), RenderStats{});
  const Image shown = job.snapshot().image();
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) EXPECT_EQ(shown.get(x, y).r, x + 100.0 * y) << x << "," << y;
  EXPECT_EQ(job.done_cost(), job.plan.total_cost);
}

TEST(JobMerge, FinalImageIsTheFrameBufferMean) {
  Job job = make_job(6, 4, 3);
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u)
    job.apply_result(u, values_for(job, u), RenderStats{});
  const Image shown = job.snapshot().image();  // what is shown once every unit merged
  job.finish(JobState::Done, "", Clock::now());
  const ImageSnapshot final_snapshot = job.snapshot();
  ASSERT_TRUE(final_snapshot.final);
  const Image final_image = final_snapshot.image();
  // Pass p returned x + 100 y + 0.25 p + c for channel c: the mean of passes 0..2 adds 0.25.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      const Rgb expected{x + 100.0 * y + 0.25, x + 100.0 * y + 1.25, x + 100.0 * y + 2.25};
      EXPECT_EQ(final_image.get(x, y), expected) << x << "," << y;
    }
  EXPECT_EQ(final_image, shown);
}

void fill(Job& job) {
  for (int u = 0; u < static_cast<int>(job.plan.units.size()); ++u)
    job.apply_result(u, values_for(job, u), RenderStats{});
}

void expect_buffers_freed(const Job& job) {
  EXPECT_EQ(job.frame_buffer().width(), 0);
  EXPECT_EQ(job.frame_buffer().height(), 0);
}

TEST(JobMemory, ADoneJobKeepsOnlyItsFinalImage) {
  Job job = make_job(6, 4, 3);
  fill(job);
  const Image final_image = job.frame_buffer().resolve();
  int released = 0;
  job.on_released = [&](Job&) { ++released; };
  job.finish(JobState::Done, "", Clock::now());
  expect_buffers_freed(job);
  // The frame buffer moved, not copied, for the final image to be made off the io thread...
  const ImageSnapshot snapshot = job.snapshot();
  EXPECT_TRUE(snapshot.final);
  EXPECT_EQ(job.snapshot().pixels, snapshot.pixels);
  EXPECT_EQ(snapshot.image(), final_image);
  EXPECT_EQ(released, 1);
  // ... and freed once it is encoded.
  job.keep_encodings({{"png", std::make_shared<const std::string>("png bytes")}});
  EXPECT_EQ(snapshot.pixels.use_count(), 1);
}

TEST(JobMemory, CancellingThroughTheSchedulerFreesEverything) {
  JobStore store(4);
  Scheduler scheduler({});
  JobRequest r;
  r.bundle = {"scene.sdl", "sdl", {{"scene.sdl", "sphere"}}};
  r.spec.settings.width = r.plan.width = 64;
  r.spec.settings.height = r.plan.height = 32;
  Job* job = store.create(std::move(r), "10.0.0.7");
  scheduler.add_job(*job);
  EXPECT_EQ(job->frame_buffer().width(), 64);
  EXPECT_EQ(store.unfinished_of("10.0.0.7"), 1);
  EXPECT_TRUE(scheduler.cancel(job->id));
  EXPECT_EQ(job->state(), JobState::Cancelled);
  expect_buffers_freed(*job);
  EXPECT_EQ(job->snapshot().pixels->width(), 0);
  EXPECT_TRUE(job->tiles().empty());
  EXPECT_EQ(store.unfinished_of("10.0.0.7"), 0);
}

HttpRequest state_change(const std::string& host, const std::string& origin = "",
                         const std::string& authorization = "") {
  HttpRequest r{boost::beast::http::verb::post, "/api/jobs", 11};
  r.set(boost::beast::http::field::host, host);
  if (!origin.empty()) r.set(boost::beast::http::field::origin, origin);
  if (!authorization.empty()) r.set(boost::beast::http::field::authorization, authorization);
  return r;
}

int refusal(const SubmitPolicy& policy, const HttpRequest& request, const std::string& peer) {
  try {
    check_submitter(policy, request, boost::asio::ip::make_address(peer));
    return 0;
  } catch (const ApiError& e) {
    return http_status(e.refusal());
  }
}

TEST(SubmitPolicy, WithoutATokenOnlyLoopbackMaySubmit) {
  const SubmitPolicy closed;
  EXPECT_EQ(refusal(closed, state_change("h:8080"), "127.0.0.1"), 0);
  EXPECT_EQ(refusal(closed, state_change("h:8080"), "::1"), 0);
  EXPECT_EQ(refusal(closed, state_change("h:8080"), "::ffff:127.0.0.1"), 0);
  EXPECT_EQ(refusal(closed, state_change("h:8080"), "192.168.1.9"), 403);
  SubmitPolicy open;
  open.open_submit = true;
  EXPECT_EQ(refusal(open, state_change("h:8080"), "192.168.1.9"), 0);
}

TEST(SubmitPolicy, ATokenIsNeededFromEveryPeer) {
  SubmitPolicy policy;
  policy.api_token = "s3cret";
  EXPECT_EQ(refusal(policy, state_change("h"), "127.0.0.1"), 401);
  EXPECT_EQ(refusal(policy, state_change("h", "", "Bearer s3cre"), "127.0.0.1"), 401);
  EXPECT_EQ(refusal(policy, state_change("h", "", "Bearer s3cret!"), "10.1.1.1"), 401);
  EXPECT_EQ(refusal(policy, state_change("h", "", "Basic s3cret"), "10.1.1.1"), 401);
  EXPECT_EQ(refusal(policy, state_change("h", "", "Bearer s3cret"), "10.1.1.1"), 0);
  EXPECT_TRUE(token_matches("abc", "abc"));
  EXPECT_FALSE(token_matches("abd", "abc"));
  EXPECT_FALSE(token_matches("", "abc"));
}

TEST(SubmitPolicy, ForeignOriginsAreRefusedUnlessAllowed) {
  SubmitPolicy policy;
  EXPECT_EQ(refusal(policy, state_change("localhost:8080", "http://localhost:8080"), "::1"), 0);
  EXPECT_EQ(refusal(policy, state_change("LocalHost:8080", "http://localhost:8080"), "::1"), 0);
  EXPECT_EQ(refusal(policy, state_change("localhost:8080", "http://localhost:9090"), "::1"), 403);
  EXPECT_EQ(refusal(policy, state_change("localhost:8080", "https://evil.example"), "::1"), 403);
  EXPECT_EQ(refusal(policy, state_change("localhost:8080", "null"), "::1"), 403);
  policy.allowed_origins = {"https://render.example"};
  EXPECT_EQ(refusal(policy, state_change("localhost:8080", "https://render.example"), "::1"), 0);
  // The origin is checked before the token: a foreign page is refused even with it.
  policy.api_token = "t";
  EXPECT_EQ(refusal(policy, state_change("h", "https://evil.example", "Bearer t"), "::1"), 403);
}

// --keep-finished and --max-disk (issue 17 §2): units scale exactly; anything else is refused.
TEST(CoordinatorOptions, DurationsAndSizesTakeTheirUnits) {
  EXPECT_EQ(parse_duration("--keep-finished", "3600s").count(), 3600);
  EXPECT_EQ(parse_duration("--keep-finished", "90m").count(), 5400);
  EXPECT_EQ(parse_duration("--keep-finished", "12h").count(), 43200);
  EXPECT_EQ(parse_duration("--keep-finished", "7d").count(), 604800);
  EXPECT_EQ(parse_duration("--keep-finished", "45").count(), 45);
  EXPECT_EQ(parse_bytes("--max-disk", "512K"), 512LL << 10);
  EXPECT_EQ(parse_bytes("--max-disk", "512M"), 512LL << 20);
  EXPECT_EQ(parse_bytes("--max-disk", "2G"), 2LL << 30);
  EXPECT_EQ(parse_bytes("--max-disk", "1000"), 1000);
  for (const char* bad : {"", "d", "7x", "7dd", "-1d", "0s", "1.5h", "99999999999999999d"})
    EXPECT_THROW(parse_duration("--keep-finished", bad), std::invalid_argument) << bad;
  for (const char* bad : {"", "M", "2T", "0", "2 G", "9999999999999G"})
    EXPECT_THROW(parse_bytes("--max-disk", bad), std::invalid_argument) << bad;
}

std::variant<CoordinatorOptions, CoordinatorHelp, std::string> parse_options(
    std::vector<std::string> args) {
  return parse_coordinator_options(args);
}

std::string options_error(std::vector<std::string> args) {
  const auto parsed = parse_coordinator_options(args);
  const auto* error = std::get_if<std::string>(&parsed);
  return error ? *error : "(accepted)";
}

// Every flag the tests, scripts, docker/entrypoint.sh and docs/SERVICE.md use keeps its name
// and meaning under CLI11 (issue 19 §6); a flag given twice takes its last value, as before.
TEST(CoordinatorOptions, EveryFlagKeepsItsNameAndMeaning) {
  const auto parsed = parse_options({"--http-port",
                                     "0",
                                     "--worker-port",
                                     "7702",
                                     "--http-port",
                                     "8081",
                                     "--secret",
                                     "s",
                                     "--local-workers",
                                     "3",
                                     "--local-threads",
                                     "2",
                                     "--scenes-dir",
                                     "scenes",
                                     "--web-dir",
                                     "web",
                                     "--bind",
                                     "127.0.0.1",
                                     "--port-file",
                                     "ports.json",
                                     "--worker-binary",
                                     "w",
                                     "--max-job-seconds",
                                     "30",
                                     "--max-body-bytes",
                                     "2048",
                                     "--heartbeat-ms",
                                     "100",
                                     "--silence-ms",
                                     "500",
                                     "--intake-threads",
                                     "3",
                                     "--max-intake-seconds",
                                     "5",
                                     "--max-http-connections",
                                     "9",
                                     "--api-token",
                                     "t",
                                     "--open-submit",
                                     "--allow-origin",
                                     "https://a.example",
                                     "--allow-origin",
                                     "https://b.example",
                                     "--max-jobs-per-client",
                                     "4",
                                     "--tls-cert",
                                     "c.pem",
                                     "--tls-key",
                                     "k.pem",
                                     "--data-dir",
                                     "d",
                                     "--keep-finished",
                                     "90m",
                                     "--max-disk",
                                     "2G"});
  ASSERT_TRUE(std::holds_alternative<CoordinatorOptions>(parsed)) << std::get<std::string>(parsed);
  const CoordinatorOptions& o = std::get<CoordinatorOptions>(parsed);
  EXPECT_EQ(o.http_port, 8081);
  EXPECT_EQ(o.worker_port, 7702);
  EXPECT_EQ(o.secret, "s");
  EXPECT_EQ(o.local_workers, 3);
  EXPECT_EQ(o.local_threads, 2);
  EXPECT_EQ(o.scenes_dir, std::filesystem::path("scenes"));
  EXPECT_EQ(o.web_dir, std::filesystem::path("web"));
  EXPECT_EQ(o.bind, "127.0.0.1");
  EXPECT_EQ(o.port_file, std::filesystem::path("ports.json"));
  EXPECT_EQ(o.worker_binary, std::filesystem::path("w"));
  EXPECT_EQ(o.limits.max_job_seconds, 30.0);
  EXPECT_EQ(o.limits.max_body_bytes, 2048u);
  EXPECT_EQ(o.timing.heartbeat, std::chrono::milliseconds(100));
  EXPECT_EQ(o.timing.silence, std::chrono::milliseconds(500));
  EXPECT_EQ(o.intake_threads, 3);
  EXPECT_EQ(o.max_intake_seconds, 5);
  EXPECT_EQ(o.max_http_connections, 9);
  EXPECT_EQ(o.submit.api_token, "t");
  EXPECT_TRUE(o.submit.open_submit);
  EXPECT_EQ(o.submit.allowed_origins,
            (std::vector<std::string>{"https://a.example", "https://b.example"}));
  EXPECT_EQ(o.max_jobs_per_client, 4);
  EXPECT_EQ(o.tls_cert, std::filesystem::path("c.pem"));
  EXPECT_EQ(o.tls_key, std::filesystem::path("k.pem"));
  EXPECT_EQ(o.data_dir, std::filesystem::path("d"));
  EXPECT_EQ(o.keep_finished, std::chrono::minutes(90));
  EXPECT_EQ(o.max_disk_bytes, 2LL << 30);
  EXPECT_FALSE(o.insecure);
  const auto defaults = parse_options({"--insecure"});
  ASSERT_TRUE(std::holds_alternative<CoordinatorOptions>(defaults));
  EXPECT_EQ(std::get<CoordinatorOptions>(defaults).http_port, 8080);
  EXPECT_FALSE(std::get<CoordinatorOptions>(defaults).scenes_dir.has_value());
  EXPECT_TRUE(std::holds_alternative<CoordinatorHelp>(parse_options({"--help"})));
}

TEST(CoordinatorOptions, ErrorsNameTheFlagAndTheBadValue) {
  for (const auto& [flag, value] :
       std::vector<std::pair<std::string, std::string>>{{"--http-port", "70000"},
                                                        {"--http-port", "eighty"},
                                                        {"--local-workers", "65"},
                                                        {"--heartbeat-ms", "5"},
                                                        {"--keep-finished", "7x"},
                                                        {"--max-disk", "2T"}}) {
    const std::string error = options_error({flag, value});
    EXPECT_NE(error.find(flag), std::string::npos) << error;
    EXPECT_NE(error.find(value), std::string::npos) << error;
  }
  EXPECT_NE(options_error({"--nosuchflag"}).find("--nosuchflag"), std::string::npos);
  EXPECT_NE(options_error({"--http-port"}).find("--http-port"), std::string::npos);
  EXPECT_EQ(options_error({"--secret", "s", "--insecure"}),
            "--secret and --insecure exclude each other");
  EXPECT_EQ(options_error({"--tls-cert", "c.pem"}), "--tls-cert and --tls-key go together");
  EXPECT_EQ(options_error({"--heartbeat-ms", "500", "--silence-ms", "500"}),
            "--silence-ms must exceed --heartbeat-ms");
}

}  // namespace
}  // namespace tessera
