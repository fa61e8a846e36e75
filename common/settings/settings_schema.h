// The one table of a render's and a job's settings (issue 19 §2): each setting's name, type,
// range, default, help and the layers that take it. The job request's parser
// (coordinator/jobs/job_request.cpp), the wire codec (common/protocol/job_spec.cpp),
// tessera-render's options and help (worker/render_cli/options.cpp) and the table of settings in
// docs/SERVICE.md (tests/settings/settings_schema_test.cpp) are all read from it: a new setting is
// one row in settings_schema.cpp and the field it sets.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "common/settings/render_settings.h"

namespace tessera {

// How the coordinator schedules a job: settings of a job request alone.
struct ScheduleSettings {
  int priority = 1;                // share of the workers while several jobs run
  bool progressive = true;         // false renders pass 0 directly, without levels
  std::string order = "centre";    // parse_unit_order (common/progressive/plan.h)
  std::string preview = "anchor";  // parse_preview_mode
};

// How the scene is loaded (common/loaders/load_budget.h): settings of a job request and of
// tessera-render, not of the wire (workers load what the coordinator accepted, leniently).
struct LoadSettings {
  bool strict = false;  // what lenient loading warns about is an error
};

// Everything a setting sets.
struct JobSettings {
  RenderSettings render;
  SceneOverrides overrides;
  ScheduleSettings schedule;
  LoadSettings load;
};

// Camera: {"eye": [x, y, z], "look_at": [x, y, z], "up": [x, y, z], "fov": degrees} in a job,
// ten numbers on the command line. Region: [x0, y0, x1, y1], four numbers on the command line.
enum class SettingType { Integer, Number, Boolean, Choice, Seed, Camera, Region };

// A setting's value, in the alternative of its type (Integer: int64_t, Seed: uint64_t, Choice:
// the choice's name, Region: PixelRect); monostate for an override left unset, which keeps
// the scene's value, and for no region, the whole image.
using SettingValue = std::variant<std::monostate, std::int64_t, double, bool, std::string,
                                  std::uint64_t, Camera, PixelRect>;

// The layers that take a setting.
enum SettingLayer : unsigned {
  kJobRequest = 1u,  // the settings of POST /api/jobs (docs/SERVICE.md)
  kWire = 2u,        // the job message to workers (docs/PROTOCOL.md)
  kRenderCli = 4u,   // tessera-render's command line (README.md), flag named by cli_flag()
};

// A limit of the service (coordinator/jobs/limits.h) that may narrow a setting's range in a job
// request.
enum class ServiceCap { None, Side, Passes, ConeSamples, Depth };

struct SettingAccess {
  SettingValue (*get)(const JobSettings&);
  void (*set)(JobSettings&, const SettingValue&);  // the value is in range
};

struct SettingSpec {
  std::string_view name;  // the key in a job request and on the wire
  SettingType type;
  double min = 0, max = 0;                         // Integer and Number
  std::span<const std::int64_t> only = {};         // Integer: the only values, when not empty
  std::span<const std::string_view> choices = {};  // Choice
  unsigned layers = 0;                             // SettingLayer bits
  ServiceCap cap = ServiceCap::None;
  std::string_view help;
  SettingAccess access;

  // The value of a default JobSettings.
  SettingValue default_value() const { return access.get(JobSettings{}); }
};

// Every setting, in the order the docs list them.
std::span<const SettingSpec> settings_schema();
const SettingSpec* find_setting(std::string_view name);

// tessera-render's flag: "--time-samples"; a flag that is on by default is turned off with
// "--no-bvh". A Boolean flag takes no value and sets the opposite of the default.
std::string cli_flag(const SettingSpec& spec);

// What the setting takes, for messages: "an integer in [1, 16384]", "1, 5 or 9", "true or
// false"; `max` narrows the range (a ServiceCap).
std::string describe_values(const SettingSpec& spec, double max);
std::string describe_values(const SettingSpec& spec);
// "must be an integer in [1, 16384]" when the value is of another type or out of range.
std::optional<std::string> setting_error(const SettingSpec& spec, const SettingValue& value,
                                         double max);
std::optional<std::string> setting_error(const SettingSpec& spec, const SettingValue& value);

// What no single setting's range can say: the region lies inside the image and is not
// post-normalized (that scales by the whole image's highest value). Names the setting.
std::optional<std::string> settings_error(const RenderSettings& settings);

// A command-line value in the setting's type ("1e-1", "12", "soft"; a camera's ten numbers,
// separated by spaces or commas; a region's "0 0 64 32"); nullopt when it does not read as
// one. The range is setting_error's to check.
std::optional<SettingValue> setting_from_text(const SettingSpec& spec, std::string_view text);
// A value as the docs and the help show it: "640", "0.2", "true", "hard", "[0, 0, 64, 32]".
std::string to_text(const SettingValue& value);
// The setting's default as the docs and the help show it: "the scene's" for an override, "the
// whole image" for the region.
std::string default_text(const SettingSpec& spec);

// The docs' table of the job request's settings (docs/SERVICE.md), one row per setting.
std::string settings_table_markdown();

}  // namespace tessera
