#!/usr/bin/env bash
# Fuzzes the SDL loader, the mesh loaders and the VRML loader with libFuzzer (clang, from
# Debian), seeded with the sample scenes, meshes and worlds, after replaying every regression
# input in tests/fuzz/regressions.
#   scripts/fuzz.sh [SECONDS]   run each target for SECONDS (default 20; scripts/test.sh uses
#                               that); longer runs: scripts/fuzz.sh 3600
# Crashes are written to build-fuzz/artifacts/; each one found becomes a file in
# tests/fuzz/regressions/<target>/ (and a unit test when the cause is understood).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
scripts/configure.sh build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTESSERA_FUZZ=ON
cmake --build build-fuzz -j"$(nproc)" --target fuzz_sdl fuzz_mesh fuzz_vrml

corpus=build-fuzz/corpus
mkdir -p "$corpus/sdl" "$corpus/mesh" "$corpus/vrml" build-fuzz/artifacts
find scenes -name '*.sdl' -exec cp {} "$corpus/sdl/" \;
find scenes -name '*.wrl' -exec cp {} "$corpus/vrml/" \;
# The mesh target's first byte picks the format: 0 OBJ, 1 3VN, 2 3DV, 3 3DM.
for f in $(find scenes -path '*meshes/*' -type f); do
  case "$f" in
    *.obj) prefix='\x00' ;; *.3vn) prefix='\x01' ;; *.3dv) prefix='\x02' ;; *.3dm) prefix='\x03' ;;
    *) continue ;;
  esac
  { printf "$prefix"; cat "$f"; } >"$corpus/mesh/$(basename "$f")"
done

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
for target in sdl mesh vrml; do
  regressions=tests/fuzz/regressions/$target
  if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
    echo "== fuzz_$target: regression inputs"
    build-fuzz/tests/fuzz/fuzz_$target "$regressions"/*
  fi
  echo "== fuzz_$target: ${seconds}s"
  log=build-fuzz/fuzz_$target.log
  status=0
  build-fuzz/tests/fuzz/fuzz_$target "$corpus/$target" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 >"$log" 2>&1 ||
    status=$?
  if [ "$status" -ne 0 ]; then
    tail -60 "$log"
    exit "$status"
  fi
  grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units)' "$log" || true
done
