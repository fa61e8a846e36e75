// What tessera-render prints around a render: warnings first, then the effect set and the
// statistics.
#pragma once

#include <string>

#include "common/render/prepared_scene.h"
#include "common/settings/render_settings.h"
#include "common/stats/render_stats.h"

namespace tessera {

void print_warnings(const Scene& scene, const PreparedScene& prepared);
// `cpu_seconds`: the process's CPU time over the render, all its threads (the "cpu:" line).
void print_report(const PreparedScene& prepared, const RenderSettings& settings,
                  const RenderStats& stats, double cpu_seconds, const std::string& output_path);

}  // namespace tessera
