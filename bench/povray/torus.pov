// POV-Ray 3.7 translation of scenes/features/torus.sdl, for scripts/compare-povray.sh --scene torus.
//
// A ring, a horn and a spindle torus on a matte floor, two point lights. The mapping of SDL's
// camera, materials and lighting onto POV-Ray's is the one demo.pov's header explains (right-
// handed coordinates through `right -x`, SDL ambient colour = pigment * ambient, Blinn specular
// as `specular` with roughness 1 / exponent, vertical view angle turned into POV's horizontal
// one). Specific to this scene:
//
//  - SDL's `torus <tube-radius> <torus-radius>` lies in its XY-plane (axis z); POV's
//    `torus { major, minor }` lies in its XZ-plane (axis y), so each torus is first turned
//    90 degrees about x. The spindle torus (tube larger than the ring) is the same quartic in
//    both; its inner "lemon" is hidden inside, so only the outer surface shows.
//  - POV-Ray solves the quartic with its default (non-Sturm) solver, its fastest; Tessera's
//    solver moves the frame close to the torus, polishes every root with Newton and brackets
//    where the closed form is ill-conditioned (docs/STABILITY.md). Both draw these tori clean.
//  - No reflective or transparent surface: the background behind the scene is seen only by
//    camera rays in both renderers.

#version 3.7;

global_settings {
  assumed_gamma 1.0
  ambient_light rgb <0.3, 0.3, 0.3>  // globalAmbient
  max_trace_level 7                  // maxRecursionDepth (default 6, see demo.pov)
  adc_bailout 0.01
}

// eyePoint 0 3 12, viewPoint 0 0 0, upDirection 0 1 0, viewAngle 40 (vertical)
#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0, 3, 12>
  sky <0, 1, 0>
  up y
  right -x * Aspect  // right-handed coordinates
  angle 2 * degrees(atan(tan(radians(40 / 2)) * Aspect))
  look_at <0, 0, 0>
}

background { rgb <0.15, 0.18, 0.25> }

light_source { <6, 8, 10>, rgb <1, 1, 1> }        // light 6 8 10  1 1 1
light_source { <-8, 4, 6>, rgb <0.4, 0.4, 0.4> }  // light -8 4 6  0.4 0.4 0.4

// An SDL material without reflection or transparency (see demo.pov's SdlTexture).
#macro SdlTexture(Ambient, Diffuse, Specular, Exponent)
  texture {
    pigment { rgb Diffuse }
    finish {
      ambient rgb Ambient / Diffuse
      diffuse 1
      brilliance 1
      specular Specular
      roughness 1 / Exponent
      phong 0
    }
  }
#end

// floor: SDL's initial material (ambient 0.1, no specular) with diffuse 0.6
box {
  <-1, -1, -1>, <1, 1, 1>
  SdlTexture(<0.1, 0.1, 0.1>, <0.6, 0.6, 0.6>, 0, 1)
  scale <8, 0.05, 4>
  translate <0, -2, 0>
}

// defaultMaterials  specular 0.6 0.6 0.6  specularExponent 40, then each torus's diffuse
#macro SdlTorus(TubeRadius, TorusRadius, Diffuse, X)
  torus {
    TorusRadius, TubeRadius
    SdlTexture(<0.1, 0.1, 0.1>, Diffuse, 0.6, 40)
    rotate 90 * x   // POV's XZ-plane to SDL's XY-plane
    rotate -60 * x  // rotate -60 1 0 0
    translate <X, 0, 0>
  }
#end

SdlTorus(0.4, 1.1, <0.9, 0.35, 0.2>, -3.6)   // ring
SdlTorus(0.75, 0.75, <0.3, 0.8, 0.3>, 0)     // horn
SdlTorus(0.9, 0.5, <0.3, 0.45, 0.95>, 3.6)   // spindle
