// tessera-render's command line: every flag scripts and docs use keeps its name and meaning,
// errors name the flag and the bad value, ranges and help come from the settings schema.
#include <gtest/gtest.h>

#include "common/settings/settings_schema.h"
#include "worker/render_cli/options.h"

namespace tessera {
namespace {

std::variant<RenderCliOptions, CliHelp, std::string> parse(const std::string& line) {
  std::vector<std::string> args;
  std::size_t start = 0;
  while (start < line.size()) {
    const std::size_t end = std::min(line.find(' ', start), line.size());
    args.push_back(line.substr(start, end - start));
    start = end + 1;
  }
  return parse_render_cli(args);
}

std::string error_of(const std::string& line) {
  const auto parsed = parse(line);
  const auto* error = std::get_if<std::string>(&parsed);
  return error ? *error : "(accepted)";
}

TEST(RenderCli, EveryFlagKeepsItsNameAndMeaning) {
  const auto parsed = parse(
      "scene.sdl -o out.exr --width 320 --height 240 --aa 5 --stochastic --jitter 0.5 "
      "--passes 3 --time-samples 4 --seed 18446744073709551615 --shadows soft --cone-samples 5 "
      "--shadow-jitter 0.25 --normalize --brightness 0.75 --threads 2 --no-bvh "
      "--debug-view cost --quiet");
  ASSERT_TRUE(std::holds_alternative<RenderCliOptions>(parsed)) << std::get<std::string>(parsed);
  const RenderCliOptions& o = std::get<RenderCliOptions>(parsed);
  EXPECT_EQ(o.scene_path, "scene.sdl");
  EXPECT_EQ(o.output_path, "out.exr");
  const RenderSettings& s = o.settings;
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 240);
  EXPECT_EQ(s.aa_samples, 5);
  EXPECT_TRUE(s.stochastic);
  EXPECT_EQ(s.jitter, 0.5);
  EXPECT_EQ(s.passes, 3);
  EXPECT_EQ(s.time_samples, 4);
  EXPECT_EQ(s.seed, 18446744073709551615ull);
  EXPECT_EQ(s.shadows, ShadowMode::Soft);
  EXPECT_EQ(s.cone_samples, 5);
  EXPECT_EQ(s.shadow_jitter, 0.25);
  EXPECT_TRUE(s.normalize_colors);
  EXPECT_EQ(s.normalize_brightness, 0.75);
  EXPECT_EQ(s.bvh, BvhMode::None);
  EXPECT_EQ(o.threads, 2);
  EXPECT_EQ(o.debug_view, DebugView::Cost);
  EXPECT_TRUE(o.quiet);
}

TEST(RenderCli, DefaultsAreTheRenderersAndTheOrderIsFree) {
  const auto parsed = parse("--quiet -o a.png scene.wrl");
  ASSERT_TRUE(std::holds_alternative<RenderCliOptions>(parsed));
  const RenderCliOptions& o = std::get<RenderCliOptions>(parsed);
  EXPECT_EQ(o.scene_path, "scene.wrl");
  const RenderSettings defaults;
  EXPECT_EQ(o.settings.width, defaults.width);
  EXPECT_EQ(o.settings.jitter, defaults.jitter);
  EXPECT_EQ(o.settings.bvh, BvhMode::Sah);
  EXPECT_EQ(o.settings.shadows, ShadowMode::Hard);
  EXPECT_EQ(o.debug_view, DebugView::None);
}

TEST(RenderCli, ErrorsNameTheFlagAndTheBadValue) {
  EXPECT_EQ(error_of("s.sdl -o o.png --width 0"),
            "--width: bad value '0': must be an integer in [1, 16384]");
  EXPECT_EQ(error_of("s.sdl -o o.png --aa 3"), "--aa: bad value '3': must be 1, 5 or 9");
  EXPECT_EQ(error_of("s.sdl -o o.png --jitter wide"),
            "--jitter: bad value 'wide': must be a number in [0, 16]");
  EXPECT_EQ(error_of("s.sdl -o o.png --shadows penumbral"),
            "--shadows: bad value 'penumbral': must be \"none\", \"hard\" or \"soft\"");
  EXPECT_NE(error_of("s.sdl -o o.png --debug-view depth").find("--debug-view"), std::string::npos);
  EXPECT_NE(error_of("s.sdl -o o.png --threads -1").find("--threads"), std::string::npos);
  EXPECT_NE(error_of("s.sdl -o o.png --nosuchflag").find("--nosuchflag"), std::string::npos);
  EXPECT_EQ(error_of("-o o.png"), "no scene file given");
  EXPECT_EQ(error_of("s.sdl"), "no output file given (-o OUT.png)");
  EXPECT_TRUE(std::holds_alternative<CliHelp>(parse("--help")));
}

// --region X0 Y0 X1 Y1 (issue 21 §4): four values, half open, inside the image.
TEST(RenderCli, RegionTakesFourValuesInsideTheImage) {
  const auto parsed = parse("s.sdl -o o.exr --width 64 --height 32 --region 8 4 64 32 --quiet");
  ASSERT_TRUE(std::holds_alternative<RenderCliOptions>(parsed)) << std::get<std::string>(parsed);
  EXPECT_EQ(std::get<RenderCliOptions>(parsed).settings.region, (PixelRect{8, 4, 64, 32}));
  EXPECT_EQ(std::get<RenderCliOptions>(parse("s.sdl -o o.exr")).settings.region, std::nullopt);
  EXPECT_EQ(error_of("s.sdl -o o.exr --width 64 --height 32 --region 0 0 65 32"),
            "--region [0, 0, 65, 32] must lie inside the 64x32 image (x1 <= width, y1 <= height)");
  EXPECT_NE(error_of("s.sdl -o o.exr --region 5 0 5 10").find("--region: bad value '5 0 5 10'"),
            std::string::npos);
  EXPECT_NE(error_of("s.sdl -o o.exr --region 0 0 10").find("--region"), std::string::npos);
  EXPECT_NE(error_of("s.sdl -o o.exr --region 0 0 4 4 --normalize").find("--region"),
            std::string::npos);
}

// The job request, the wire and this command line take a setting's one range (issue 19 §2):
// --jitter took only 0..1 here while a job took up to 16.
TEST(RenderCli, SettingsTakeTheSchemasRange) {
  EXPECT_EQ(error_of("s.sdl -o o.png --jitter 16 --time-samples 0"), "(accepted)");
  EXPECT_EQ(error_of("s.sdl -o o.png --jitter 16.5"),
            "--jitter: bad value '16.5': must be a number in [0, 16]");
  for (const SettingSpec& spec : settings_schema()) {
    if (!(spec.layers & kRenderCli) || spec.type != SettingType::Integer || !spec.only.empty())
      continue;
    const std::string flag = cli_flag(spec);
    const auto max = static_cast<long long>(spec.max);
    EXPECT_EQ(error_of("s.sdl -o o.png " + flag + " " + std::to_string(max)), "(accepted)");
    EXPECT_NE(error_of("s.sdl -o o.png " + flag + " " + std::to_string(max + 1)), "(accepted)")
        << flag;
  }
}

// Ten values, negative ones too; the last --camera counts, as for every flag.
TEST(RenderCli, TheCameraTakesTenNumbers) {
  const auto parsed = parse(
      "s.wrl -o o.png --camera 9 9 9 0 0 0 0 1 0 45 --camera -2 0.5 6 0 -0.25 0 0.1 1 0 33.5 "
      "--width 8");
  ASSERT_TRUE(std::holds_alternative<RenderCliOptions>(parsed)) << std::get<std::string>(parsed);
  const RenderCliOptions& o = std::get<RenderCliOptions>(parsed);
  EXPECT_EQ(o.camera, (Camera{{-2, 0.5, 6}, {0, -0.25, 0}, {0.1, 1, 0}, 33.5}));
  EXPECT_EQ(o.settings.width, 8);
  EXPECT_FALSE(std::get<RenderCliOptions>(parse("s.sdl -o o.png")).camera);
  EXPECT_EQ(error_of("s.sdl -o o.png --camera 0 0 1 0 0 1 0 1 0 45"),
            "--camera: bad value '0 0 1 0 0 1 0 1 0 45': must have its eye apart from look_at");
  EXPECT_EQ(error_of("s.sdl -o o.png --camera 0 0 1 0 0 0 0 1 0 x"),
            "--camera: bad value '0 0 1 0 0 0 0 1 0 x': must be ten numbers, EX EY EZ LX LY LZ UX "
            "UY UZ FOV");
  EXPECT_NE(error_of("s.sdl -o o.png --camera 0 0 1 0 0 0 0 1 0"), "(accepted)");
}

TEST(RenderCli, HelpShowsEverySettingWithItsValuesAndDefault) {
  const std::string help = render_cli_usage();
  for (const SettingSpec& spec : settings_schema()) {
    if (!(spec.layers & kRenderCli)) continue;
    EXPECT_NE(help.find(cli_flag(spec)), std::string::npos) << spec.name;
    EXPECT_NE(help.find(std::string(spec.help.substr(0, 20))), std::string::npos) << spec.name;
    if (spec.type == SettingType::Boolean) continue;  // a flag: on or off
    EXPECT_NE(help.find("(default " + default_text(spec) + ")"), std::string::npos) << spec.name;
  }
}

}  // namespace
}  // namespace tessera
