#include "worker/render_cli/setting_flags.h"

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace tessera {
namespace {

// What CLI11 shows after a flag that takes a value.
std::string value_name(const SettingSpec& spec) {
  switch (spec.type) {
    case SettingType::Integer:
      return "INT";
    case SettingType::Number:
      return "NUMBER";
    case SettingType::Seed:
      return "UINT";
    case SettingType::Choice: {
      std::string names;
      for (const std::string_view choice : spec.choices)
        names += (names.empty() ? "" : "|") + std::string(choice);
      return names;
    }
    case SettingType::Region:
      return "INT";  // CLI11 adds " x 4"
    case SettingType::Camera:
      return "EX EY EZ LX LY LZ UX UY UZ FOV";
    case SettingType::Boolean:
      break;
  }
  return {};
}

// How many values the flag takes.
int value_count(const SettingSpec& spec) {
  switch (spec.type) {
    case SettingType::Region:
      return 4;
    case SettingType::Camera:
      return 10;
    default:
      return 1;
  }
}

// "bad value '0': must be an integer in [1, 16384]", or empty when `text` is a good value.
std::string value_error(const SettingSpec& spec, const std::string& text) {
  const std::optional<SettingValue> value = setting_from_text(spec, text);
  const std::optional<std::string> error = value ? setting_error(spec, *value)
                                           : spec.type == SettingType::Camera
                                               ? "must be ten numbers, " + value_name(spec)
                                               : "must be " + describe_values(spec);
  return error ? "bad value '" + text + "': " + *error : std::string();
}

// The setting as a flag: a Boolean sets the opposite of its default; a region takes four
// values and a camera ten, checked once all are read; any other takes one. Values are checked
// against the schema ("--width: bad value '0': must be an integer in [1, 16384]").
void add_setting(CLI::App& app, const SettingSpec& spec, JobSettings& settings) {
  const std::string help(spec.help);
  const std::string with_default = help + " (default " + default_text(spec) + ")";
  if (spec.type == SettingType::Boolean) {
    const bool set_to = !std::get<bool>(spec.default_value());
    app.add_flag_callback(
        cli_flag(spec), [&spec, &settings, set_to] { spec.access.set(settings, set_to); },
        set_to ? help : "turns off: " + help);
    return;
  }
  if (const int count = value_count(spec); count > 1) {
    app.add_option_function<std::vector<std::string>>(
           cli_flag(spec),
           [&spec, &settings](const std::vector<std::string>& values) {
             std::string text;
             for (const std::string& v : values) text += (text.empty() ? "" : " ") + v;
             if (const std::string error = value_error(spec, text); !error.empty())
               throw CLI::ValidationError(cli_flag(spec), error);
             spec.access.set(settings, *setting_from_text(spec, text));
           },
           with_default)
        ->expected(count)
        ->type_name(value_name(spec));
    return;
  }
  app.add_option_function<std::string>(
         cli_flag(spec),
         [&spec, &settings](const std::string& text) {
           spec.access.set(settings, *setting_from_text(spec, text));
         },
         with_default)
      ->type_name(value_name(spec))
      ->check(CLI::Validator([&spec](std::string& text) { return value_error(spec, text); },
                             describe_values(spec)));
}

}  // namespace

void add_setting_flags(CLI::App& app, JobSettings& settings, unsigned layers) {
  for (const SettingSpec& spec : settings_schema())
    if (spec.layers & layers) add_setting(app, spec, settings);
}

}  // namespace tessera
