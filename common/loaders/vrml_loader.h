// The VRML 2.0 loader (ISO/IEC 14772-1, VRML97): a .wrl or .wrl.gz world to the same Scene the
// SDL loader produces, so that the tracer and the service treat both alike. docs/VRML.md
// lists the nodes and how each maps to the tracer.
#pragma once

#include <optional>
#include <string>

#include "common/loaders/load_budget.h"
#include "common/loaders/scene_source.h"
#include "common/scene/scene.h"

namespace tessera {

// Parses the world at root-relative `path` of `source`, with its Inlines (each file parsed once
// and shared). Throws SceneError naming file, line, column and what was expected;
// LoadBudgetExceeded when the world goes over `budget`. A `camera` (view_angle: fieldOfView in
// degrees) is bound in place of the world's Viewpoint: Billboards turn to it and the headlight
// follows it, as for a Viewpoint of that camera.
Scene load_vrml(const SceneSource& source, const std::string& path, const LoadBudget& budget = {},
                const std::optional<Camera>& camera = std::nullopt);

}  // namespace tessera
