// The settings schema (common/settings/settings_schema.h): its table agrees with itself, with the
// structs it sets and with the docs' table of settings in docs/SERVICE.md.
#include "common/settings/settings_schema.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <sstream>

namespace tessera {
namespace {

TEST(SettingsSchema, DefaultsAreInRangeAndReadBackFromText) {
  for (const SettingSpec& spec : settings_schema()) {
    const SettingValue value = spec.default_value();
    if (std::holds_alternative<std::monostate>(value)) continue;  // an override: the scene's
    EXPECT_EQ(setting_error(spec, value), std::nullopt) << spec.name;
    EXPECT_EQ(setting_from_text(spec, to_text(value)), value) << spec.name;
  }
}

TEST(SettingsSchema, EverySettingSetsItsOwnField) {
  for (const SettingSpec& spec : settings_schema()) {
    JobSettings settings;
    const SettingValue changed = [&]() -> SettingValue {
      switch (spec.type) {
        case SettingType::Integer:
          return spec.only.empty() ? static_cast<std::int64_t>(spec.max) : spec.only.back();
        case SettingType::Number:
          return spec.max;
        case SettingType::Boolean:
          return !std::get<bool>(spec.default_value());
        case SettingType::Choice:
          return std::string(spec.choices.back());
        case SettingType::Seed:
          return std::uint64_t{12345};
        case SettingType::Camera:
          return Camera{{1, 2, 3}, {0, 0, 0}, {0, 0, 1}, 30};
        case SettingType::Region:
          return PixelRect{1, 2, 3, 4};
      }
      return {};
    }();
    ASSERT_NE(changed, spec.default_value()) << spec.name;
    spec.access.set(settings, changed);
    EXPECT_EQ(spec.access.get(settings), changed) << spec.name;
    for (const SettingSpec& other : settings_schema()) {
      if (&other == &spec) continue;
      EXPECT_EQ(other.access.get(settings), other.default_value())
          << spec.name << " changed " << other.name;
    }
  }
}

// What tessera-render renders with must reach the workers, and what workers get must be
// something a job request can set: else the service and the command line differ.
TEST(SettingsSchema, LayersNest) {
  for (const SettingSpec& spec : settings_schema()) {
    // What tessera-render takes travels to workers, but for how the scene is loaded: workers
    // load what the coordinator accepted (LoadSettings).
    const bool load_setting = spec.name == "strict";
    EXPECT_TRUE(!(spec.layers & kRenderCli) || (spec.layers & kWire) || load_setting) << spec.name;
    EXPECT_TRUE(!(spec.layers & kWire) || (spec.layers & kJobRequest)) << spec.name;
    EXPECT_EQ(find_setting(spec.name), &spec);
  }
  EXPECT_EQ(find_setting("nosuchsetting"), nullptr);
  EXPECT_EQ(cli_flag(*find_setting("time_samples")), "--time-samples");
  EXPECT_EQ(cli_flag(*find_setting("bvh")), "--no-bvh");
  EXPECT_EQ(cli_flag(*find_setting("stochastic")), "--stochastic");
}

TEST(SettingsSchema, ValuesOfTheWrongTypeOrOutOfRangeAreRefused) {
  const SettingSpec& width = *find_setting("width");
  EXPECT_EQ(setting_error(width, std::int64_t{16384}), std::nullopt);
  EXPECT_EQ(setting_error(width, std::int64_t{16385}), "must be an integer in [1, 16384]");
  EXPECT_EQ(setting_error(width, std::int64_t{4097}, 4096), "must be an integer in [1, 4096]");
  EXPECT_EQ(setting_error(width, 12.0), "must be an integer in [1, 16384]");
  EXPECT_EQ(setting_error(*find_setting("aa"), std::int64_t{3}), "must be 1, 5 or 9");
  EXPECT_EQ(setting_error(*find_setting("jitter"), 16.5), "must be a number in [0, 16]");
  EXPECT_EQ(setting_error(*find_setting("seed"), std::int64_t{2}), "must be an integer >= 0");
  EXPECT_EQ(setting_from_text(width, "12px"), std::nullopt);
  const SettingSpec& region = *find_setting("region");
  EXPECT_EQ(setting_error(region, PixelRect{0, 0, 16384, 1}), std::nullopt);
  const std::string region_range =
      "must be [x0, y0, x1, y1], integers with 0 <= x0 < x1 <= 16384 and 0 <= y0 < y1 <= 16384";
  EXPECT_EQ(setting_error(region, PixelRect{5, 0, 5, 1}), region_range);  // empty
  EXPECT_EQ(setting_error(region, PixelRect{0, 3, 1, 2}), region_range);
  EXPECT_EQ(setting_error(region, PixelRect{-1, 0, 1, 1}), region_range);
  EXPECT_EQ(setting_error(region, PixelRect{0, 0, 1, 16385}), region_range);
  EXPECT_EQ(setting_error(region, std::int64_t{3}), region_range);
  EXPECT_EQ(setting_from_text(region, "1 2 3 4"), SettingValue(PixelRect{1, 2, 3, 4}));
  EXPECT_EQ(setting_from_text(region, "[1, 2, 3, 4]"), SettingValue(PixelRect{1, 2, 3, 4}));
  EXPECT_EQ(setting_from_text(region, "1 2 3"), std::nullopt);
  EXPECT_EQ(setting_from_text(region, "1 2 3 4 5"), std::nullopt);
  EXPECT_EQ(setting_from_text(region, "1 2 3 x"), std::nullopt);
}

// What one setting's range cannot say: the region lies inside the image, and a region is not
// post-normalized (the scale is the whole image's).
TEST(SettingsSchema, ARegionLiesInsideTheImageAndIsNotNormalized) {
  RenderSettings s;
  s.width = 64;
  s.height = 32;
  EXPECT_EQ(settings_error(s), std::nullopt);
  s.region = PixelRect{0, 0, 64, 32};
  EXPECT_EQ(settings_error(s), std::nullopt);
  s.region = PixelRect{0, 0, 65, 32};
  EXPECT_EQ(settings_error(s),
            "region [0, 0, 65, 32] must lie inside the 64x32 image (x1 <= width, y1 <= height)");
  s.region = PixelRect{0, 31, 1, 33};
  EXPECT_NE(settings_error(s), std::nullopt);
  s.region = PixelRect{0, 0, 1, 1};
  s.normalize_colors = true;
  EXPECT_NE(settings_error(s), std::nullopt);
  EXPECT_EQ(setting_from_text(*find_setting("seed"), "-1"), std::nullopt);
}

// The camera setting: ten numbers on the command line, checked as the loaders check a scene's
// camera (a view direction, an up across it) and for a field of view a pinhole can have.
TEST(SettingsSchema, TheCameraReadsTenNumbersAndMustGiveAView) {
  const SettingSpec& spec = *find_setting("camera");
  const Camera camera{{-2, 0.5, 6}, {0, -0.25, 0}, {0.1, 1, 0}, 33.5};
  EXPECT_EQ(setting_from_text(spec, "-2 0.5 6 0 -0.25 0 0.1 1 0 33.5"), SettingValue(camera));
  EXPECT_EQ(setting_from_text(spec, "-2,0.5,6, 0,-0.25,0, 0.1,1,0, 33.5"), SettingValue(camera));
  EXPECT_EQ(setting_from_text(spec, to_text(camera)), std::nullopt);  // words are not numbers
  EXPECT_EQ(setting_from_text(spec, "1 2 3 4 5 6 7 8 9"), std::nullopt);
  EXPECT_EQ(setting_from_text(spec, "1 2 3 4 5 6 7 8 9 10 11"), std::nullopt);
  EXPECT_EQ(setting_error(spec, camera), std::nullopt);
  const auto error = [&](auto change) {
    Camera c = camera;
    change(c);
    return setting_error(spec, c).value_or("(accepted)");
  };
  EXPECT_EQ(error([](Camera& c) { c.look_at = c.eye; }), "must have its eye apart from look_at");
  EXPECT_EQ(error([](Camera& c) { c.up = c.look_at - c.eye; }),
            "must have an up direction not along the view");
  EXPECT_EQ(error([](Camera& c) { c.up = {}; }), "must have an up direction not along the view");
  EXPECT_EQ(error([](Camera& c) { c.eye.y = std::numeric_limits<double>::infinity(); }),
            "must hold finite numbers");
  EXPECT_EQ(error([](Camera& c) { c.view_angle = std::numeric_limits<double>::quiet_NaN(); }),
            "must hold finite numbers");
  EXPECT_EQ(error([](Camera& c) { c.view_angle = 0; }), "must have a fov in (0, 180) degrees");
  EXPECT_EQ(error([](Camera& c) { c.view_angle = 180; }), "must have a fov in (0, 180) degrees");
  EXPECT_EQ(error([](Camera& c) { c.view_angle = 179.9; }), "(accepted)");
  EXPECT_NE(setting_error(spec, 45.0), std::nullopt);
}

// The table between the markers in docs/SERVICE.md is settings_table_markdown(); on a change
// of the schema, paste the table this test prints.
TEST(SettingsSchema, TheDocsTableIsTheSchemas) {
  std::ifstream in(std::string(TESSERA_SOURCE_DIR) + "/docs/SERVICE.md");
  ASSERT_TRUE(in);
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::string begin = "<!-- settings table: settings_table_markdown() -->\n";
  const std::string end = "<!-- end of settings table -->";
  const std::size_t from = doc.find(begin), to = doc.find(end);
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  EXPECT_EQ(doc.substr(from + begin.size(), to - from - begin.size()), settings_table_markdown())
      << "the table docs/SERVICE.md should hold:\n"
      << settings_table_markdown();
}

}  // namespace
}  // namespace tessera
