#include "common/texture/surface_texture.h"

#include "common/texture/mesh_corners.h"

namespace tessera {

namespace {

// Colour `k` modulating the ambient and diffuse colours, or, as a decal, replacing the ambient
// term with no light at all.
void apply(SurfaceColours& colours, const Rgb& k, bool decal) {
  if (decal) {
    colours.ambient_term = k;
    colours.lit = false;
  } else {
    colours.ambient_term = colours.ambient_term * k;
    colours.diffuse = colours.diffuse * k;
  }
}

}  // namespace

SurfaceColours textured_colours(const ObjectTexture& texture, const Instance& instance,
                                const WorldHit& hit, SurfaceColours colours) {
  if (texture.coloured_mesh)
    apply(colours, corner_colour(*texture.coloured_mesh, hit.part, hit.object_point),
          texture.colour_decal);
  if (texture.solid)
    apply(colours, solid_texture_colour(*texture.solid, hit.object_point), false);  // eq. 4.27
  if (texture.flat)
    apply(colours, flat_texture_colour(*texture.flat, texture_coordinates(instance, hit)),
          texture.flat->decal);
  return colours;
}

}  // namespace tessera
