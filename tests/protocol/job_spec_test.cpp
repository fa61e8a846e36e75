#include "common/protocol/job_spec.h"

#include <gtest/gtest.h>

#include "common/protocol/frame.h"

namespace tessera {
namespace {

TEST(JobSpec, RoundTrips) {
  JobSpec spec;
  spec.settings = {.width = 33,
                   .height = 17,
                   .aa_samples = 9,
                   .stochastic = true,
                   .jitter = 0.5,
                   .seed = 1ull << 60,
                   .passes = 4,
                   .time_samples = 12,
                   .bvh = BvhMode::None};
  spec.overrides.max_depth = 2;
  const JobSpec back = job_spec_from_json(to_json(spec));
  EXPECT_EQ(back.settings.width, 33);
  EXPECT_EQ(back.settings.aa_samples, 9);
  EXPECT_TRUE(back.settings.stochastic);
  EXPECT_EQ(back.settings.jitter, 0.5);
  EXPECT_EQ(back.settings.seed, 1ull << 60);
  EXPECT_EQ(back.settings.passes, 4);
  EXPECT_EQ(back.settings.time_samples, 12);
  EXPECT_EQ(back.settings.bvh, BvhMode::None);
  EXPECT_EQ(back.overrides, spec.overrides);
}

// The camera travels to workers exactly (JSON numbers round-trip), in the request's form.
TEST(JobSpec, TheCameraRoundTripsBitForBit) {
  JobSpec spec;
  spec.overrides.camera =
      Camera{{0.1, -1e-300, 7}, {1.0 / 3, 2, 3}, {0, 1, 1e-17}, 28.64788975654116};
  const nlohmann::json j = to_json(spec);
  EXPECT_EQ(j["camera"]["look_at"][0], 1.0 / 3);
  EXPECT_EQ(j["camera"]["fov"], 28.64788975654116);
  EXPECT_EQ(job_spec_from_json(j).overrides, spec.overrides);
  EXPECT_FALSE(job_spec_from_json(to_json(JobSpec{})).overrides.camera);
  const SettingSpec& setting = *find_setting("camera");
  for (const char* bad :
       {R"({"eye": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0]})",
        R"({"eye": [0, 0], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 4})",
        R"({"eye": [0, 0, "1"], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 4})",
        R"({"eye": [0, 0, 1], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 4,
                              "roll": 0})",
        R"([0, 0, 1, 0, 0, 0, 0, 1, 0, 45])"})
    EXPECT_EQ(setting_from_json(setting, nlohmann::json::parse(bad)), std::nullopt) << bad;
  nlohmann::json degenerate = j;
  degenerate["camera"]["eye"] = degenerate["camera"]["look_at"];
  EXPECT_THROW(job_spec_from_json(degenerate), ProtocolError);
}

TEST(JobSpec, ShadingSettingsRoundTrip) {
  JobSpec spec;
  spec.settings.shadows = ShadowMode::Soft;
  spec.settings.cone_samples = 17;
  spec.settings.shadow_jitter = 0.375;
  spec.settings.normalize_colors = true;
  spec.settings.normalize_brightness = 1.25;
  const nlohmann::json j = to_json(spec);
  EXPECT_EQ(j.at("shadows"), "soft");
  const RenderSettings back = job_spec_from_json(j).settings;
  EXPECT_EQ(back.shadows, ShadowMode::Soft);
  EXPECT_EQ(back.cone_samples, 17);
  EXPECT_EQ(back.shadow_jitter, 0.375);
  EXPECT_TRUE(back.normalize_colors);
  EXPECT_EQ(back.normalize_brightness, 1.25);
  for (const ShadowMode mode : {ShadowMode::None, ShadowMode::Hard}) {
    spec.settings.shadows = mode;
    EXPECT_EQ(job_spec_from_json(to_json(spec)).settings.shadows, mode);
  }
}

TEST(JobSpec, UnknownShadowModeIsAProtocolError) {
  nlohmann::json j = to_json(JobSpec{});
  j["shadows"] = "penumbral";
  EXPECT_THROW(job_spec_from_json(j), ProtocolError);
}

TEST(JobSpec, MistypedFieldsAreProtocolErrors) {
  nlohmann::json j = to_json(JobSpec{});
  j["width"] = "wide";
  EXPECT_THROW(job_spec_from_json(j), ProtocolError);
  EXPECT_THROW(job_spec_from_json(nlohmann::json::object()), ProtocolError);
}

// The wire takes each setting's one range (common/settings/settings_schema.h), as the job request
// and tessera-render do; an unset override is left out of the message.
TEST(JobSpec, OutOfRangeSettingsAreProtocolErrors) {
  const nlohmann::json good = to_json(JobSpec{});
  EXPECT_FALSE(good.contains("max_depth"));
  for (const auto& [key, bad] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"aa", 3}, {"jitter", 16.5}, {"width", 0}, {"seed", -1}, {"max_depth", 17}}) {
    nlohmann::json j = good;
    j[key] = bad;
    EXPECT_THROW(job_spec_from_json(j), ProtocolError) << key;
  }
  nlohmann::json j = good;
  j["jitter"] = 16;
  EXPECT_EQ(job_spec_from_json(j).settings.jitter, 16.0);
}

// A region travels as [x0, y0, x1, y1] and must lie inside the image (issue 21 §4); no region
// is left out of the message.
TEST(JobSpec, ARegionRoundTripsAndLiesInsideTheImage) {
  EXPECT_FALSE(to_json(JobSpec{}).contains("region"));
  JobSpec spec;
  spec.settings.region = PixelRect{1, 2, 30, 40};
  const nlohmann::json j = to_json(spec);
  EXPECT_EQ(j["region"], nlohmann::json({1, 2, 30, 40}));
  EXPECT_EQ(job_spec_from_json(j).settings.region, spec.settings.region);
  for (const nlohmann::json& bad :
       {nlohmann::json({1, 2, 641, 40}), nlohmann::json({1, 2, 30}), nlohmann::json({3, 2, 3, 40}),
        nlohmann::json({1.5, 2, 30, 40}), nlohmann::json({-1, 2, 30, 40}),
        nlohmann::json("0 0 1 1"), nlohmann::json({0, 0, 4294967297LL, 1})}) {
    nlohmann::json k = j;
    k["region"] = bad;
    EXPECT_THROW(job_spec_from_json(k), ProtocolError) << bad;
  }
}

TEST(JobSpec, OverridesChangeTheSceneGlobals) {
  Scene scene;
  apply_overrides(scene, {.max_depth = 1, .min_weight = 0.05, .camera = std::nullopt});
  EXPECT_EQ(scene.globals.max_recursion_depth, 1);
  EXPECT_EQ(scene.globals.min_reflectivity, 0.05);
  EXPECT_EQ(scene.globals.min_transparency, 0.05);
}

TEST(Stats, RoundTrip) {
  RenderStats s;
  s.camera_rays = 5;
  s.intersections.bvh_nodes = 99;
  s.seconds = 1.5;
  const RenderStats back = stats_from_json(to_json(s));
  EXPECT_EQ(back.camera_rays, 5u);
  EXPECT_EQ(back.intersections.bvh_nodes, 99u);
  EXPECT_EQ(back.seconds, 1.5);
}

}  // namespace
}  // namespace tessera
