// The settings of common/settings/settings_schema.h as command-line flags (CLI11), shared by
// tessera-render and tessera-submit so both take each setting with the same name, range, help
// and default.
#pragma once

#include "common/settings/settings_schema.h"

namespace CLI {
class App;
}

namespace tessera {

// Adds a flag for every setting of the schema in one of `layers` (SettingLayer bits), writing
// into `settings` as it parses. A Boolean flag sets the opposite of its default; a region takes
// four values; any other one. Bad values are errors naming the flag ("--width: bad value '0':
// must be an integer in [1, 16384]"). `settings` must outlive the app.
void add_setting_flags(CLI::App& app, JobSettings& settings, unsigned layers);

}  // namespace tessera
