#include "worker/render_cli/options.h"

#include <charconv>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace tessera {

const char* const kRenderCliUsage =
    "usage: tessera-render SCENE.{sdl,wrl,wrl.gz,wrz} -o OUT.{png,exr} [options]\n"
    "  --width W        image width in pixels (default 640)\n"
    "  --height H       image height in pixels (default 480)\n"
    "  --aa 1|5|9       samples per pixel per pass (default 1)\n"
    "  --stochastic     jitter the sample positions\n"
    "  --jitter J       jitter strength in pixels, 0..1 (default 1)\n"
    "  --passes P       sample passes, averaged (default 1)\n"
    "  --time-samples N motion-blur times per sample, 1..256 (default: the scene's motionBlur)\n"
    "  --seed S         seed of every random number (default 0)\n"
    "  --shadows none|hard|soft\n"
    "                   shadow mode (default hard): no shadow feelers, one per light, or a\n"
    "                   cone of them (soft)\n"
    "  --cone-samples N rays per gloss, translucency and soft-shadow cone, 1..64 (default 9)\n"
    "  --shadow-jitter S\n"
    "                   soft-shadow cone diameter one unit from the point, 0..2 (default 0.2)\n"
    "  --normalize      post-normalize: scale the image so its highest value is at most 1\n"
    "  --brightness B   multiply the post-normalized image by B, 0..16 (default 1)\n"
    "  --threads T      threads (default: all cores)\n"
    "  --no-bvh         trace without the bounding volume hierarchy (for comparison)\n"
    "  --debug-view V   writes a debug view instead of the render: normals (the first hit's\n"
    "                   shading normal as colour) or cost (intersection tests per pixel)\n"
    "  --quiet          no progress or statistics\n"
    "  --strict         a missing texture, an unknown node or field, an unsupported url is an\n"
    "                   error, not a warning\n"
    "  --root DIR       the files the scene names must lie inside DIR (default: any file,\n"
    "                   relative paths against the naming file's folder)\n";

namespace {

template <typename T>
bool parse_number(const std::string& text, T& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

}  // namespace

std::variant<RenderCliOptions, CliHelp, std::string> parse_render_cli(
    const std::vector<std::string>& args) {
  RenderCliOptions o;
  std::string error;
  // Options with a value: name -> how to store it (returns false when the value is bad).
  const std::map<std::string, std::function<bool(const std::string&)>> valued{
      {"-o",
       [&](const std::string& v) {
         o.output_path = v;
         return !v.empty();
       }},
      {"--root",
       [&](const std::string& v) {
         o.root = v;
         return !v.empty();
       }},
      {"--width",
       [&](const std::string& v) {
         return parse_number(v, o.settings.width) && o.settings.width >= 1 &&
                o.settings.width <= 16384;
       }},
      {"--height",
       [&](const std::string& v) {
         return parse_number(v, o.settings.height) && o.settings.height >= 1 &&
                o.settings.height <= 16384;
       }},
      {"--aa",
       [&](const std::string& v) {
         return parse_number(v, o.settings.aa_samples) &&
                (o.settings.aa_samples == 1 || o.settings.aa_samples == 5 ||
                 o.settings.aa_samples == 9);
       }},
      {"--jitter",
       [&](const std::string& v) {
         return parse_number(v, o.settings.jitter) && o.settings.jitter >= 0 &&
                o.settings.jitter <= 1;
       }},
      {"--passes",
       [&](const std::string& v) {
         return parse_number(v, o.settings.passes) && o.settings.passes >= 1 &&
                o.settings.passes <= 4096;
       }},
      {"--time-samples",
       [&](const std::string& v) {
         return parse_number(v, o.settings.time_samples) && o.settings.time_samples >= 1 &&
                o.settings.time_samples <= kMaxTimeSamples;
       }},
      {"--seed", [&](const std::string& v) { return parse_number(v, o.settings.seed); }},
      {"--debug-view",
       [&](const std::string& v) {
         o.debug_view = v == "normals" ? DebugView::Normals
                        : v == "cost"  ? DebugView::Cost
                                       : DebugView::None;
         return o.debug_view != DebugView::None;
       }},
      {"--shadows",
       [&](const std::string& v) {
         const std::optional<ShadowMode> mode = parse_shadow_mode(v);
         if (mode) o.settings.shadows = *mode;
         return mode.has_value();
       }},
      {"--cone-samples",
       [&](const std::string& v) {
         return parse_number(v, o.settings.cone_samples) && o.settings.cone_samples >= 1 &&
                o.settings.cone_samples <= 64;
       }},
      {"--shadow-jitter",
       [&](const std::string& v) {
         return parse_number(v, o.settings.shadow_jitter) && o.settings.shadow_jitter >= 0 &&
                o.settings.shadow_jitter <= 2;
       }},
      {"--brightness",
       [&](const std::string& v) {
         return parse_number(v, o.settings.normalize_brightness) &&
                o.settings.normalize_brightness >= 0 && o.settings.normalize_brightness <= 16;
       }},
      {"--threads",
       [&](const std::string& v) {
         return parse_number(v, o.threads) && o.threads >= 0 && o.threads <= 1024;
       }},
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-h" || a == "--help") return CliHelp{};
    if (a == "--stochastic") {
      o.settings.stochastic = true;
    } else if (a == "--normalize") {
      o.settings.normalize_colors = true;
    } else if (a == "--no-bvh") {
      o.settings.bvh = BvhMode::None;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--strict") {
      o.strict = true;
    } else if (auto it = valued.find(a); it != valued.end()) {
      if (i + 1 >= args.size()) return "option " + a + " needs a value";
      if (!it->second(args[++i])) return "bad value '" + args[i] + "' for " + a;
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option " + a;
    } else if (o.scene_path.empty()) {
      o.scene_path = a;
    } else {
      return "unexpected argument '" + a + "' (the scene is " + o.scene_path + ")";
    }
  }
  if (o.scene_path.empty()) return std::string("no scene file given");
  if (o.output_path.empty()) return std::string("no output file given (-o OUT.png)");
  return o;
}

}  // namespace tessera
