#include "common/settings/render_settings.h"

namespace tessera {

const char* to_string(ShadowMode mode) {
  switch (mode) {
    case ShadowMode::None:
      return "none";
    case ShadowMode::Hard:
      return "hard";
    case ShadowMode::Soft:
      return "soft";
  }
  return "hard";
}

std::optional<ShadowMode> parse_shadow_mode(std::string_view name) {
  for (const ShadowMode mode : {ShadowMode::None, ShadowMode::Hard, ShadowMode::Soft})
    if (name == to_string(mode)) return mode;
  return std::nullopt;
}

}  // namespace tessera
