#include "common/texture/flat_texture.h"

#include <algorithm>
#include <cmath>

#include "common/texture/image_texture.h"

namespace tessera {

namespace {

double periodic(double u) { return u - std::floor(u); }

// Offset with a wrap-around, then clipped to [0, 1] (a NaN becomes 0).
double offset_and_clip(double s, double offset) {
  s += offset;
  if (s > 1) s -= 1;
  return s >= 0 ? std::min(s, 1.0) : 0.0;
}

struct Lookup {
  TexCoord uv;  // placed: repeats with period 1 unless clamped
  bool clamp_s = false, clamp_t = false;

  Rgb operator()(const ImagePattern& p) const {
    return bilinear_lookup(*p.image, uv.s, uv.t, clamp_s, clamp_t);
  }
  Rgb operator()(const FlatCheckerboard& c) const {
    const double cells =
        std::floor(periodic(uv.s) * c.tiles_s) + std::floor(periodic(uv.t) * c.tiles_t);
    const double v = std::fmod(cells, 2.0) == 0 ? 1 : 0;
    return {v, v, v};
  }
  Rgb operator()(const RadialColours& r) const {
    const double d =
        std::min(1.0, 2 * std::hypot(periodic(uv.s) - 0.5, periodic(uv.t) - 0.5));  // 1 at the edge
    return r.inside * (1 - d) + r.outside * d;
  }
};

}  // namespace

std::optional<PreparedFlatTexture> make_flat_texture(const FlatTexture& texture,
                                                     const Image* image) {
  PreparedFlatTexture out;
  const std::vector<double>& a = texture.params;
  switch (texture.kind) {
    case FlatTexture::Kind::None:
      return std::nullopt;
    case FlatTexture::Kind::Image:
      out.pattern = ImagePattern{image};
      break;
    case FlatTexture::Kind::Procedural:
      if (texture.procedural_type == 1)
        out.pattern = FlatCheckerboard{a.at(0), a.at(1)};
      else if (texture.procedural_type == 2)
        out.pattern = RadialColours{{a.at(0), a.at(1), a.at(2)}, {a.at(3), a.at(4), a.at(5)}};
      else
        return std::nullopt;
      break;
  }
  out.decal = texture.decal;
  out.tile_s = texture.tile_s;
  out.tile_t = texture.tile_t;
  out.offset_s = texture.offset_s;
  out.offset_t = texture.offset_t;
  out.transform = texture.transform;
  out.clamp_s = texture.clamp_s;
  out.clamp_t = texture.clamp_t;
  return out;
}

TexCoord place_on_texture(const PreparedFlatTexture& texture, TexCoord st) {
  if (const auto& m = texture.transform)
    return {(*m)[0] * st.s + (*m)[1] * st.t + (*m)[2], (*m)[3] * st.s + (*m)[4] * st.t + (*m)[5]};
  return {offset_and_clip(st.s, texture.offset_s) * texture.tile_s,
          offset_and_clip(st.t, texture.offset_t) * texture.tile_t};
}

Rgb flat_texture_colour(const PreparedFlatTexture& texture, TexCoord st) {
  return std::visit(Lookup{place_on_texture(texture, st), texture.clamp_s, texture.clamp_t},
                    texture.pattern);
}

}  // namespace tessera
