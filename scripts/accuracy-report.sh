#!/usr/bin/env bash
# Regenerates the accuracy reports behind docs/ACCURACY.md: tessera-accuracy on each sample
# scene below, into docs/accuracy/<scene>/ (report.md and its SVG plots).
#   scripts/accuracy-report.sh [--width W] [--height H] [--repeats N]
set -euo pipefail
cd "$(dirname "$0")/.."
size=(--width 320 --height 240 --repeats 3)
[ $# -gt 0 ] && size=("$@")
scripts/build.sh
for scene in demo features/shadows features/reflection features/refraction features/mesh \
  features/motion_blur features/gloss; do
  name=$(basename "$scene")
  echo "== $scene"
  build/bench/accuracy/tessera-accuracy "scenes/$scene.sdl" -o "docs/accuracy/$name" "${size[@]}"
done
echo "== features/soft_shadows (--shadows soft)"
build/bench/accuracy/tessera-accuracy scenes/features/soft_shadows.sdl \
  -o docs/accuracy/soft_shadows --shadows soft "${size[@]}"
