#include "common/settings/settings_schema.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "common/scene/motion.h"  // kMaxTimeSamples

namespace tessera {
namespace {

// ---- Fields as setting values, and back -------------------------------------------------

SettingValue widen(int v) { return std::int64_t{v}; }
SettingValue widen(double v) { return v; }
SettingValue widen(bool v) { return v; }
SettingValue widen(std::uint64_t v) { return v; }
SettingValue widen(const std::string& v) { return v; }
SettingValue widen(BvhMode v) { return v == BvhMode::Sah; }
SettingValue widen(ShadowMode v) { return std::string(to_string(v)); }
SettingValue widen(const Camera& v) { return v; }
SettingValue widen(const PixelRect& v) { return v; }
template <typename T>
SettingValue widen(const std::optional<T>& v) {
  return v ? widen(*v) : SettingValue();
}

void assign(int& field, const SettingValue& v) {
  field = static_cast<int>(std::get<std::int64_t>(v));
}
void assign(double& field, const SettingValue& v) { field = std::get<double>(v); }
void assign(bool& field, const SettingValue& v) { field = std::get<bool>(v); }
void assign(std::uint64_t& field, const SettingValue& v) { field = std::get<std::uint64_t>(v); }
void assign(std::string& field, const SettingValue& v) { field = std::get<std::string>(v); }
void assign(BvhMode& field, const SettingValue& v) {
  field = std::get<bool>(v) ? BvhMode::Sah : BvhMode::None;
}
void assign(Camera& field, const SettingValue& v) { field = std::get<Camera>(v); }
void assign(PixelRect& field, const SettingValue& v) { field = std::get<PixelRect>(v); }
void assign(ShadowMode& field, const SettingValue& v) {
  field = parse_shadow_mode(std::get<std::string>(v)).value_or(ShadowMode::Hard);
}
template <typename T>
void assign(std::optional<T>& field, const SettingValue& v) {
  if (std::holds_alternative<std::monostate>(v)) {
    field.reset();
  } else {
    T value{};
    assign(value, v);
    field = value;
  }
}

// The setting that is field `Field` of part `Part` of JobSettings.
template <auto Part, auto Field>
constexpr SettingAccess field = {
    [](const JobSettings& s) { return widen((s.*Part).*Field); },
    [](JobSettings& s, const SettingValue& v) { assign((s.*Part).*Field, v); }};

constexpr auto kRender = &JobSettings::render;
constexpr auto kOverrides = &JobSettings::overrides;
constexpr auto kSchedule = &JobSettings::schedule;
constexpr auto kLoad = &JobSettings::load;
constexpr unsigned kEverywhere = kJobRequest | kWire | kRenderCli;
constexpr unsigned kJobs = kJobRequest | kWire;  // the service's, not tessera-render's

constexpr std::int64_t kAaCounts[] = {1, 5, 9};
constexpr std::string_view kShadowModes[] = {"none", "hard", "soft"};
// "center" and "central" (the seeds' word) are the same order, as parse_unit_order reads them.
constexpr std::string_view kUnitOrders[] = {"centre", "scanline", "center", "central"};
constexpr std::string_view kPreviewModes[] = {"anchor", "area"};

// ---- The table ----------------------------------------------------------------------------

const SettingSpec kSchema[] = {
    {.name = "width",
     .type = SettingType::Integer,
     .min = 1,
     .max = 16384,
     .layers = kEverywhere,
     .cap = ServiceCap::Side,
     .help = "image width in pixels",
     .access = field<kRender, &RenderSettings::width>},
    {.name = "height",
     .type = SettingType::Integer,
     .min = 1,
     .max = 16384,
     .layers = kEverywhere,
     .cap = ServiceCap::Side,
     .help = "image height in pixels",
     .access = field<kRender, &RenderSettings::height>},
    {.name = "aa",
     .type = SettingType::Integer,
     .min = 1,
     .max = 9,
     .only = kAaCounts,
     .layers = kEverywhere,
     .help = "samples per pixel (per block) per pass: the centre, its corners, its edge midpoints "
             "(§4.4)",
     .access = field<kRender, &RenderSettings::aa_samples>},
    {.name = "stochastic",
     .type = SettingType::Boolean,
     .layers = kEverywhere,
     .help = "jitter the sample positions (§4.4.2)",
     .access = field<kRender, &RenderSettings::stochastic>},
    {.name = "jitter",
     .type = SettingType::Number,
     .min = 0,
     .max = 16,
     .layers = kEverywhere,
     .help = "jitter strength: stochastic samples move by up to ±jitter/2 pixels; motion-blur "
             "times by up to ±min(jitter, 1)/2 of their stretch of the shutter",
     .access = field<kRender, &RenderSettings::jitter>},
    {.name = "seed",
     .type = SettingType::Seed,
     .layers = kEverywhere,
     .help = "keys every random number",
     .access = field<kRender, &RenderSettings::seed>},
    {.name = "passes",
     .type = SettingType::Integer,
     .min = 1,
     .max = 4096,
     .layers = kEverywhere,
     .cap = ServiceCap::Passes,
     .help = "sample passes, averaged",
     .access = field<kRender, &RenderSettings::passes>},
    {.name = "time_samples",
     .type = SettingType::Integer,
     .min = 0,
     .max = kMaxTimeSamples,
     .layers = kEverywhere,
     .help = "motion-blur times per sample; 0: the scene's motionBlur count",
     .access = field<kRender, &RenderSettings::time_samples>},
    {.name = "bvh",
     .type = SettingType::Boolean,
     .layers = kEverywhere,
     .help = "accelerate with the bounding volume hierarchy (off for comparison)",
     .access = field<kRender, &RenderSettings::bvh>},
    {.name = "shadows",
     .type = SettingType::Choice,
     .choices = kShadowModes,
     .layers = kEverywhere,
     .help = "the shadow mode (§4.2.1): no shadow feelers, one per light, or a cone of them",
     .access = field<kRender, &RenderSettings::shadows>},
    {.name = "cone_samples",
     .type = SettingType::Integer,
     .min = 1,
     .max = 64,
     .layers = kEverywhere,
     .cap = ServiceCap::ConeSamples,
     .help = "rays per gloss, translucency and soft-shadow cone, the central one included "
             "(nrOfConeSamples)",
     .access = field<kRender, &RenderSettings::cone_samples>},
    {.name = "shadow_jitter",
     .type = SettingType::Number,
     .min = 0,
     .max = 2,
     .layers = kEverywhere,
     .help = "soft-shadow cone diameter one unit from the point (shadowFeelerJitterStrength, "
             "eq. 4.25)",
     .access = field<kRender, &RenderSettings::shadow_jitter>},
    {.name = "normalize",
     .type = SettingType::Boolean,
     .layers = kEverywhere,
     .help = "post-normalize (§4.6): scale the image so its highest component is 1 when it "
             "exceeds 1, then multiply by brightness",
     .access = field<kRender, &RenderSettings::normalize_colors>},
    {.name = "brightness",
     .type = SettingType::Number,
     .min = 0,
     .max = 16,
     .layers = kEverywhere,
     .help = "multiplies the post-normalized image",
     .access = field<kRender, &RenderSettings::normalize_brightness>},
    {.name = "region",
     .type = SettingType::Region,
     .max = 16384,
     .layers = kEverywhere,
     .cap = ServiceCap::Side,
     .help = "[x0, y0, x1, y1]: render only the pixels x0 <= x < x1, y0 <= y < y1 (y = 0 at the "
             "top), each bit for bit as in the whole image, into a full-size frame whose other "
             "pixels are black; not with normalize",
     .access = field<kRender, &RenderSettings::region>},
    {.name = "max_depth",
     .type = SettingType::Integer,
     .min = 0,
     .max = 16,
     .layers = kJobs,
     .cap = ServiceCap::Depth,
     .help = "overrides the scene's maxRecursionDepth",
     .access = field<kOverrides, &SceneOverrides::max_depth>},
    {.name = "min_weight",
     .type = SettingType::Number,
     .min = 0,
     .max = 1,
     .layers = kJobs,
     .help = "overrides minReflectivity and minTransparency",
     .access = field<kOverrides, &SceneOverrides::min_weight>},
    {.name = "camera",
     .type = SettingType::Camera,
     .min = 0,
     .max = 180,
     .layers = kEverywhere,
     .help = "replaces the scene's camera: eye, look-at point, up direction and field of view in "
             "degrees, the format's own angle (SDL's vertical viewAngle, VRML's fieldOfView "
             "across the image's smaller side)",
     .access = field<kOverrides, &SceneOverrides::camera>},
    {.name = "progressive",
     .type = SettingType::Boolean,
     .layers = kJobRequest,
     .help = "false renders pass 0 directly, without levels",
     .access = field<kSchedule, &ScheduleSettings::progressive>},
    {.name = "order",
     .type = SettingType::Choice,
     .choices = kUnitOrders,
     .layers = kJobRequest,
     .help = "the order units go out in",
     .access = field<kSchedule, &ScheduleSettings::order>},
    {.name = "preview",
     .type = SettingType::Choice,
     .choices = kPreviewModes,
     .layers = kJobRequest,
     .help = "area: the seeds' previews, every block of every level traced at its centre (about "
             "a third more work); the final image is the same",
     .access = field<kSchedule, &ScheduleSettings::preview>},
    {.name = "priority",
     .type = SettingType::Integer,
     .min = 1,
     .max = 100,
     .layers = kJobRequest,
     .help = "share of the workers while several jobs run",
     .access = field<kSchedule, &ScheduleSettings::priority>},
    {.name = "strict",
     .type = SettingType::Boolean,
     .layers = kJobRequest | kRenderCli,
     .help = "a missing texture, an unknown node or field, an unsupported url is an error, not a "
             "warning",
     .access = field<kLoad, &LoadSettings::strict>},
};

// ---- Text -------------------------------------------------------------------------------

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// "a, b or c", each quoted with `quote`.
template <typename T, typename Format>
std::string one_of(std::span<const T> values, Format format) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) text += i + 1 == values.size() ? " or " : ", ";
    text += format(values[i]);
  }
  return text;
}

template <typename T>
bool parse_all(std::string_view text, T& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// "EX EY EZ LX LY LZ UX UY UZ FOV", separated by spaces or commas.
std::optional<Camera> camera_from_text(std::string_view text) {
  double numbers[10];
  std::size_t count = 0;
  while (true) {
    const std::size_t start = text.find_first_not_of(" ,");
    if (start == std::string_view::npos) break;
    text.remove_prefix(start);
    const std::string_view number = text.substr(0, text.find_first_of(" ,"));
    if (count == 10 || !parse_all(number, numbers[count++])) return std::nullopt;
    text.remove_prefix(number.size());
  }
  if (count != 10) return std::nullopt;
  Camera camera;
  camera.eye = {numbers[0], numbers[1], numbers[2]};
  camera.look_at = {numbers[3], numbers[4], numbers[5]};
  camera.up = {numbers[6], numbers[7], numbers[8]};
  camera.view_angle = numbers[9];
  return camera;
}

// What makes a camera setting unusable, in the words of "must ...".
std::optional<std::string> camera_error(const Camera& camera, const SettingSpec& spec) {
  if (!is_finite(camera.eye) || !is_finite(camera.look_at) || !is_finite(camera.up) ||
      !std::isfinite(camera.view_angle))
    return "must hold finite numbers";
  const Vec3 view = view_direction(camera);
  if (view == Vec3{}) return "must have its eye apart from look_at";
  if (camera_right(camera, view) == Vec3{}) return "must have an up direction not along the view";
  if (!(camera.view_angle > spec.min && camera.view_angle < spec.max))
    return "must have a fov in (" + format_number(spec.min) + ", " + format_number(spec.max) +
           ") degrees";
  return std::nullopt;
}

// Four integers separated by spaces or commas, perhaps in brackets: "0 0 64 32", "0,0,64,32",
// "[0, 0, 64, 32]" (as to_text writes it).
std::optional<SettingValue> region_from_text(std::string_view text) {
  constexpr std::string_view kSeparators = " ,[]";
  int v[4];
  int count = 0;
  std::size_t i = 0;
  while (true) {
    i = std::min(text.find_first_not_of(kSeparators, i), text.size());
    if (i == text.size()) break;
    const std::size_t end = std::min(text.find_first_of(kSeparators, i), text.size());
    if (count == 4 || !parse_all(text.substr(i, end - i), v[count])) return std::nullopt;
    ++count;
    i = end;
  }
  if (count != 4) return std::nullopt;
  return PixelRect{v[0], v[1], v[2], v[3]};
}

}  // namespace

std::span<const SettingSpec> settings_schema() { return kSchema; }

const SettingSpec* find_setting(std::string_view name) {
  for (const SettingSpec& spec : kSchema)
    if (spec.name == name) return &spec;
  return nullptr;
}

std::string cli_flag(const SettingSpec& spec) {
  std::string dashed(spec.name);
  for (char& c : dashed)
    if (c == '_') c = '-';
  const bool on_by_default =
      spec.type == SettingType::Boolean && std::get<bool>(spec.default_value());
  return (on_by_default ? "--no-" : "--") + dashed;
}

std::string describe_values(const SettingSpec& spec, double max) {
  switch (spec.type) {
    case SettingType::Integer:
      if (!spec.only.empty())
        return one_of(spec.only, [](std::int64_t v) { return std::to_string(v); });
      return "an integer in [" + format_number(spec.min) + ", " + format_number(max) + "]";
    case SettingType::Number:
      return "a number in [" + format_number(spec.min) + ", " + format_number(max) + "]";
    case SettingType::Boolean:
      return "true or false";
    case SettingType::Choice:
      return one_of(spec.choices, [](std::string_view v) { return "\"" + std::string(v) + "\""; });
    case SettingType::Seed:
      return "an integer >= 0";
    case SettingType::Camera:
      return "{\"eye\": [x, y, z], \"look_at\": [x, y, z], \"up\": [x, y, z], \"fov\": "
             "degrees}: the eye apart from look_at, up not along the view, fov in (" +
             format_number(spec.min) + ", " + format_number(max) + ")";
    case SettingType::Region:
      return "[x0, y0, x1, y1], integers with 0 <= x0 < x1 <= " + format_number(max) +
             " and 0 <= y0 < y1 <= " + format_number(max);
  }
  return {};
}

std::string describe_values(const SettingSpec& spec) { return describe_values(spec, spec.max); }

std::optional<std::string> setting_error(const SettingSpec& spec, const SettingValue& value,
                                         double max) {
  bool ok = false;
  switch (spec.type) {
    case SettingType::Integer:
      if (const auto* v = std::get_if<std::int64_t>(&value)) {
        const auto wide = static_cast<double>(*v);  // exact within any range the table holds
        ok = spec.only.empty()
                 ? wide >= spec.min && wide <= max
                 : std::find(spec.only.begin(), spec.only.end(), *v) != spec.only.end();
      }
      break;
    case SettingType::Number:
      if (const auto* v = std::get_if<double>(&value)) ok = *v >= spec.min && *v <= max;
      break;
    case SettingType::Boolean:
      ok = std::holds_alternative<bool>(value);
      break;
    case SettingType::Choice:
      if (const auto* v = std::get_if<std::string>(&value))
        ok = std::find(spec.choices.begin(), spec.choices.end(), *v) != spec.choices.end();
      break;
    case SettingType::Seed:
      ok = std::holds_alternative<std::uint64_t>(value);
      break;
    case SettingType::Camera:
      if (const auto* v = std::get_if<Camera>(&value)) return camera_error(*v, spec);
      break;
    case SettingType::Region:
      if (const auto* r = std::get_if<PixelRect>(&value))
        ok = r->x0 >= 0 && r->y0 >= 0 && r->x0 < r->x1 && r->y0 < r->y1 && r->x1 <= max &&
             r->y1 <= max;
      break;
  }
  if (ok) return std::nullopt;
  return "must be " + describe_values(spec, max);
}

std::optional<std::string> setting_error(const SettingSpec& spec, const SettingValue& value) {
  return setting_error(spec, value, spec.max);
}

std::optional<std::string> settings_error(const RenderSettings& settings) {
  if (!settings.region) return std::nullopt;
  const PixelRect& r = *settings.region;
  if (r.x1 > settings.width || r.y1 > settings.height)
    return "region " + to_text(r) + " must lie inside the " + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + " image (x1 <= width, y1 <= height)";
  if (settings.normalize_colors)
    return std::string(
        "region cannot be post-normalized: normalize scales by the whole image's "
        "highest value, which a region does not know");
  return std::nullopt;
}

std::optional<SettingValue> setting_from_text(const SettingSpec& spec, std::string_view text) {
  switch (spec.type) {
    case SettingType::Integer: {
      std::int64_t v = 0;
      if (parse_all(text, v)) return v;
      break;
    }
    case SettingType::Number: {
      double v = 0;
      if (parse_all(text, v)) return v;
      break;
    }
    case SettingType::Boolean:
      if (text == "true") return true;
      if (text == "false") return false;
      break;
    case SettingType::Choice:
      return std::string(text);
    case SettingType::Seed: {
      std::uint64_t v = 0;
      if (parse_all(text, v)) return v;
      break;
    }
    case SettingType::Camera:
      if (const std::optional<Camera> v = camera_from_text(text)) return *v;
      break;
    case SettingType::Region:
      return region_from_text(text);
  }
  return std::nullopt;
}

std::string to_text(const SettingValue& value) {
  struct Format {
    std::string operator()(std::monostate) const { return "the scene's"; }
    std::string operator()(std::int64_t v) const { return std::to_string(v); }
    std::string operator()(double v) const { return format_number(v); }
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(const std::string& v) const { return v; }
    std::string operator()(std::uint64_t v) const { return std::to_string(v); }
    std::string operator()(const Camera& v) const {
      const auto triple = [](const Vec3& p) {
        return "(" + format_number(p.x) + ", " + format_number(p.y) + ", " + format_number(p.z) +
               ")";
      };
      return "eye " + triple(v.eye) + ", look_at " + triple(v.look_at) + ", up " + triple(v.up) +
             ", fov " + format_number(v.view_angle);
    }
    std::string operator()(const PixelRect& r) const {
      return "[" + std::to_string(r.x0) + ", " + std::to_string(r.y0) + ", " +
             std::to_string(r.x1) + ", " + std::to_string(r.y1) + "]";
    }
  };
  return std::visit(Format{}, value);
}

std::string default_text(const SettingSpec& spec) {
  return spec.type == SettingType::Region ? "the whole image" : to_text(spec.default_value());
}

std::string settings_table_markdown() {
  std::string table =
      "| setting | values | default | meaning | `tessera-render` |\n"
      "| --- | --- | --- | --- | --- |\n";
  for (const SettingSpec& spec : kSchema) {
    if (!(spec.layers & kJobRequest)) continue;
    table += "| `" + std::string(spec.name) + "` | " + describe_values(spec) + " | " +
             default_text(spec) + " | " + std::string(spec.help) + " | " +
             (spec.layers & kRenderCli ? "`" + cli_flag(spec) + "`" : std::string("—")) + " |\n";
  }
  return table;
}

}  // namespace tessera
