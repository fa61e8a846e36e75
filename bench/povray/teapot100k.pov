// POV-Ray 3.7 translation of bench/povray/teapot100k.sdl, for scripts/compare-povray.sh
// --scene teapot100k.
//
// The Utah teapot as a 102,080-triangle mesh on a floor. The mesh is teapot100k.inc, which the
// script writes from the same OBJ file Tessera reads (bench/povray/obj_to_mesh2.py), unitized as
// Tessera unitizes OBJ files, with the file's vertex normals interpolated as `mesh <file> 1`
// interpolates them. Camera, materials and lights map as demo.pov's header explains.

#version 3.7;

global_settings {
  assumed_gamma 1.0
  ambient_light rgb <0.2, 0.2, 0.2>  // globalAmbient
  max_trace_level 7
  adc_bailout 0.01
}

// eyePoint 0.6 1.6 3.6, viewPoint 0 -0.05 0, upDirection 0 1 0, viewAngle 40 (vertical)
#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0.6, 1.6, 3.6>
  sky <0, 1, 0>
  up y
  right -x * Aspect  // right-handed coordinates
  angle 2 * degrees(atan(tan(radians(40 / 2)) * Aspect))
  look_at <0, -0.05, 0>
}

background { rgb <0.15, 0.15, 0.2> }

light_source { <3, 5, 4>, rgb <1, 1, 1> }           // light 3 5 4  1 1 1
light_source { <-4, 2, 2>, rgb <0.3, 0.3, 0.4> }   // light -4 2 2  0.3 0.3 0.4

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

#include "teapot100k.inc"

// SDL's initial ambient 0.1; diffuse 0.8 0.3 0.2, specular 0.7, specularExponent 60
object {
  Teapot
  SdlTexture(<0.1, 0.1, 0.1>, <0.8, 0.3, 0.2>, 0.7, 60)
  rotate -20 * y
}

// floor: diffuse 0.6, no specular
box {
  <-1, -1, -1>, <1, 1, 1>
  SdlTexture(<0.1, 0.1, 0.1>, <0.6, 0.6, 0.6>, 0, 1)
  scale <3, 0.01, 3>
  translate <0, -0.5, 0>
}
