// VRML's headlight (issue 20, item 7): a directional light along the view that lights what
// the camera sees head-on and casts no shadow. Traced shadows of a light along the view fall
// beside an off-centre object in a perspective view, as black fringes no browser shows.
#include <gtest/gtest.h>

#include "common/loaders/scene_source.h"
#include "common/loaders/vrml_loader.h"
#include "tests/render/scene_builder.h"

namespace tessera::test {
namespace {

TEST(VrmlHeadlight, CastsNoShadowBesideAnOffCentreObject) {
  // The quad [-2, 2]^2 at z = 0 fills the image from z = 5 (tan(fov / 2) = 2 / 5); a ball of
  // radius 0.5 at (1.5, 0, 2) in front of it. Pixel (31, 20) sees the quad at (1.15, -0.05):
  // its eye ray passes the ball, but a feeler along +z from there would hit it.
  MemorySource source;
  source.add("world.wrl",
             "#VRML V2.0 utf8\n"
             "Viewpoint { position 0 0 5 fieldOfView 0.7610127542247298 }\n"
             "Shape { appearance Appearance { material Material { diffuseColor 0.5 0.5 0.5 } }\n"
             "  geometry IndexedFaceSet { coord Coordinate { point [-2 -2 0, 2 -2 0, 2 2 0, "
             "-2 2 0] } coordIndex [0 1 2 3] } }\n"
             "Transform { translation 1.5 0 2 children Shape { appearance Appearance {\n"
             "  material Material {} } geometry Sphere { radius 0.5 } } }\n");
  const Image image = render(load_vrml(source, "world.wrl"), settings(40, 40));
  // Lit head-on: diffuse 0.5 x N.L 1; no ambient light.
  expect_rgb(image.get(31, 20), Rgb::gray(0.5));
}

}  // namespace
}  // namespace tessera::test
