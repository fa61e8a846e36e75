#!/usr/bin/env bash
# Renders a few scenes normally and with glibc's SSE2 variants of its elementary functions (as a
# host without FMA runs them) and asks for the same pixels: rotations, cones (gloss, soft
# shadows), textures, motion blur and spotlights all go through common/math/portable_math.h
# (issue 18 §3, docs/STABILITY.md "libm's results depend on the host CPU").
#   same_pixels_without_fma.sh TESSERA_RENDER SCENES_DIR OUT_DIR
set -euo pipefail
render=$1 scenes=$2 out=$3
mkdir -p "$out"
status=0
for scene in features/textures.sdl features/gloss.sdl features/soft_shadows.sdl \
  features/motion_blur.sdl features/spotlight.sdl features/polyhedra.sdl \
  vrml/texture_coordinates.wrl; do
  name=$(basename "$scene")
  "$render" "$scenes/$scene" --width 96 --height 72 --aa 9 --quiet -o "$out/$name.exr"
  GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA \
    "$render" "$scenes/$scene" --width 96 --height 72 --aa 9 --quiet -o "$out/$name-sse2.exr"
  if ! idiff -fail 0 -warn 0 "$out/$name.exr" "$out/$name-sse2.exr" >"$out/$name.idiff" 2>&1; then
    echo "$scene: other pixels with glibc's SSE2 variants"
    cat "$out/$name.idiff"
    status=1
  fi
done
exit $status
