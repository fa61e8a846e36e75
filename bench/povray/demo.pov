// POV-Ray 3.7 translation of scenes/demo.sdl, for scripts/compare-povray.sh.
//
// A glass ball, a mirror ball and a matte cone on a reflective floor, lit by a point light and
// a spotlight. Every number below is the SDL scene's own, in SDL's (right-handed) coordinates:
// the camera's `right` vector points along -x, which is POV-Ray's documented way to render a
// right-handed scene, so positions, rotations (POV's `rotate` matrix equals SDL's Rodrigues
// rotation numerically) and the picture all come out as Tessera draws them.
//
// Render with assumed_gamma 1 (below) and File_Gamma=1.0 on the command line: Tessera writes its
// linear intensities clamped to [0, 1] into the PNG with no gamma curve, and so does this.
//
// How Tessera's lighting model (docs/ARCHITECTURE.md "Lighting model decisions",
// common/render/tracer.cpp) is mapped, and what cannot match exactly:
//
//  - Colours: SDL gives every material separate ambient and diffuse colours; POV has one pigment
//    that both multiply. The pigment is the SDL diffuse colour with `diffuse 1`, and `ambient`
//    is the colour ambient / diffuse, so that pigment * ambient * ambient_light equals SDL's
//    ambient * globalAmbient. (Exact.)
//  - Diffuse: SDL diffuse * light * max(N.L, 0); POV's `diffuse 1`, brilliance 1. (Exact for
//    surfaces facing the eye; see back faces below.)
//  - Specular: SDL's Blinn term specular * light * (N.H)^exponent with H = normalize(L - V) is
//    POV's `specular` with `roughness 1/exponent` (POV's specular is the Blinn halfway-vector
//    highlight, not `phong`, which is the mirrored-ray Phong lobe). The SDL specular colours
//    here are all grey, so POV's scalar `specular` (highlight in the light's colour) is exact.
//    Differences: Tessera adds a highlight wherever N.H > 0 even where N.L <= 0 (a sliver at the
//    terminator); POV skips highlights when the light is behind the surface.
//  - Transparency: Tessera scales ambient, diffuse and specular by (1 - transparency) and adds
//    transparency * refracted colour. POV's `transmit 0.9` scales ambient and diffuse by
//    (1 - 0.9) and the refracted colour by 0.9, but never scales highlights, so the glass's
//    `specular` is given here pre-multiplied: 1 * (1 - 0.9) = 0.1. (Exact.)
//  - Refraction: ior = 1 / speedOfLight = 1 / 0.667, no Fresnel, no fade. On total internal
//    reflection Tessera still multiplies the internally reflected ray by the transparency (0.9);
//    POV adds it unattenuated. Rare in this scene (grazing rays inside the glass ball).
//  - Reflection: SDL adds reflectivity * reflected colour on top of the local colour, as POV's
//    plain `reflection` does (no conserve_energy, no fresnel, no metallic). (Exact.)
//  - Reflected rays that hit nothing: Tessera returns black (eq. 4.2 of the SDL manual: the
//    background is only seen by camera and refracted rays). POV would return the background, so
//    a black, unlit sphere around the scene marked `no_image` (invisible to camera rays) and
//    `no_shadow` is what reflected rays see. POV has no flag that also hides it from refracted
//    rays, so a refracted ray leaving the glass ball towards the sky sees black here where
//    Tessera shows the background colour; from this camera such rays are few.
//  - Back faces: POV turns every normal towards the incoming ray and lights a surface only when
//    the light is on that side. Tessera keeps the outward normal (§4.1.3, no lightBackFaces).
//    The two differ only where a ray inside the glass ball shades its inner surface: POV lights
//    the inside of the ball's bottom from the lights above (through the glass), Tessera lights
//    the inside where the light is outside that part of the surface. The glass's diffuse and
//    specular are small (scaled by 0.1); the visible trace is a faint glow low in the ball.
//  - Shadows through the glass ball: Tessera multiplies the shadow feeler by the transparency of
//    each object once (eq. 4.24): 0.9. POV multiplies by the transmit at each surface crossed:
//    0.9 * 0.9 = 0.81. The glass ball's shadow is a little darker here.
//  - Spotlight: SDL's cut-off angle and exponent give 0 outside the cone and cos(alpha)^exponent
//    inside. POV's spotlight with radius = falloff = cut-off has no soft edge (its smoothstep
//    between falloff and radius degenerates to a step) and `tightness` is the same
//    cos(alpha)^tightness. (Exact.)
//  - Recursion: Tessera traces a reflected or refracted ray while depth < maxRecursionDepth (6),
//    the camera ray being depth 0: up to 6 bounces. POV counts the camera ray as level 1 and
//    traces while level <= max_trace_level, so max_trace_level 7 gives the same 6 bounces.
//    Tessera's minReflectivity / minTransparency (0.01 by default) are POV's adc_bailout 0.01.
//  - Shapes: SDL's cube is [-1, 1]^3, its sphere the unit sphere, and its tapered cylinder runs
//    along z from 0 (radius 1) to 1 (radius = small radius) with both end discs (no top disc for
//    a cone): POV's capped `cone`. (Exact.)
//  - Camera: SDL's viewAngle is the vertical field of view; POV's `angle` is the horizontal one,
//    so it is computed from the image's aspect ratio: 2 atan(tan(40 / 2) * width / height).
//    Ray epsilons differ (Tessera offsets secondary rays by a bound on the hit point's rounding
//    error; POV ignores hits nearer than a fixed tolerance); this is invisible here.
//  - Anti-aliasing is chosen on the command line (see scripts/compare-povray.sh).

#version 3.7;

global_settings {
  assumed_gamma 1.0
  ambient_light rgb <0.25, 0.25, 0.25>  // globalAmbient
  max_trace_level 7                     // maxRecursionDepth 6 (see above)
  adc_bailout 0.01                      // minReflectivity = minTransparency = 0.01 (defaults)
}

// eyePoint 0 3 9, viewPoint 0 0.6 0, upDirection 0 1 0, viewAngle 40 (vertical)
#declare Aspect = image_width / image_height;
camera {
  perspective
  location <0, 3, 9>
  sky <0, 1, 0>
  up y
  right -x * Aspect  // right-handed coordinates
  angle 2 * degrees(atan(tan(radians(40 / 2)) * Aspect))
  look_at <0, 0.6, 0>
}

background { rgb <0.12, 0.14, 0.2> }

// What reflected rays that miss every object see: black (see above).
sphere {
  <0, 0, 0>, 1000
  texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 } }
  no_image
  no_shadow
}

// light -6 8 6  0.9 0.9 0.85
light_source { <-6, 8, 6>, rgb <0.9, 0.9, 0.85> }

// spotlight 5 7 2  0.6 0.6 0.7  -0.6 -1 -0.3  35 4
light_source {
  <5, 7, 2>, rgb <0.6, 0.6, 0.7>
  spotlight
  point_at <5, 7, 2> + <-0.6, -1, -0.3>
  radius 35
  falloff 35
  tightness 4
}

// An SDL material. Colours are SDL's; Specular is the grey level of SDL's specular colour
// (already multiplied by 1 - transparency, see above).
#macro SdlTexture(Ambient, Diffuse, Specular, Exponent, Reflectivity, Transparency)
  texture {
    pigment { rgbt <Diffuse.x, Diffuse.y, Diffuse.z, Transparency> }
    finish {
      ambient rgb Ambient / Diffuse
      diffuse 1
      brilliance 1
      specular Specular
      roughness 1 / Exponent
      phong 0
      reflection { Reflectivity }
    }
  }
#end

// floor: a flat box, slightly reflective (SDL material defaults: no specular)
box {
  <-1, -1, -1>, <1, 1, 1>
  SdlTexture(<0.3, 0.3, 0.32>, <0.55, 0.55, 0.6>, 0, 1, 0.25, 0)
  scale <8, 0.05, 8>
  translate <0, -1, 0>
}

// mirror ball
sphere {
  <0, 0, 0>, 1
  SdlTexture(<0.05, 0.05, 0.05>, <0.1, 0.1, 0.12>, 0.9, 80, 0.85, 0)
  scale 1.2
  translate <-1.8, 0.2, -0.5>
}

// glass ball with a slower speed of light (index 1.5)
sphere {
  <0, 0, 0>, 1
  SdlTexture(<0, 0, 0>, <0.05, 0.07, 0.06>, 1 * (1 - 0.9), 120, 0.1, 0.9)
  interior { ior 1 / 0.667 }  // 1 / speedOfLight
  scale 0.9
  translate <0.9, -0.05, 1.6>
}

// a red cone standing on the floor (SDL tapered cylinders run along z: turn it upright)
cone {
  <0, 0, 0>, 1, <0, 0, 1>, 0
  SdlTexture(<0.3, 0.05, 0.05>, <0.8, 0.15, 0.1>, 0.4, 20, 0, 0)
  scale <0.8, 0.8, 1.8>
  rotate -90 * x
  translate <2.6, -0.95, -1.2>
}

// a blue tapered cylinder behind (taperedCylinder 0.5: top radius 0.5, both caps)
cone {
  <0, 0, 0>, 1, <0, 0, 1>, 0.5
  SdlTexture(<0.05, 0.1, 0.3>, <0.15, 0.3, 0.8>, 0, 1, 0, 0)
  scale <0.7, 0.7, 1.4>
  rotate -90 * x
  translate <0.2, -0.95, -3>
}
