#include "common/texture/surface_texture.h"

namespace tessera {

SurfaceColours textured_colours(const ObjectTexture& texture, const Instance& instance,
                                const WorldHit& hit, SurfaceColours colours) {
  if (texture.solid) {
    const Rgb k = solid_texture_colour(*texture.solid, hit.object_point);  // eq. 4.27
    colours.ambient_term = colours.ambient_term * k;
    colours.diffuse = colours.diffuse * k;
  }
  if (texture.flat) {
    const Rgb k = flat_texture_colour(*texture.flat, texture_coordinates(instance, hit));
    if (texture.flat->decal) {
      colours.ambient_term = k;
      colours.lit = false;
    } else {
      colours.ambient_term = colours.ambient_term * k;
      colours.diffuse = colours.diffuse * k;
    }
  }
  return colours;
}

}  // namespace tessera
