#!/usr/bin/env bash
# Fuzzes the SDL loader, the mesh loaders and the VRML loader with libFuzzer (clang, from
# Debian), seeded with the sample scenes, meshes and worlds (.wrl.gz too), and the coordinator's
# job-request path (JSON, multipart, tar) and its decoding and validation of worker frames,
# seeded by tests/fuzz/service_seeds.py, after replaying every regression input in
# tests/fuzz/regressions. Past survival the targets check invariants (tests/fuzz/fuzz_checks.h:
# finite pixels, bounds, the BVH against brute force; tests/fuzz/service_fuzz_checks.h: limits,
# bundle paths, refusals, frame limits, accepted results).
#   scripts/fuzz.sh [SECONDS]   run each target for SECONDS (default 20; scripts/test.sh runs 15
#                               each); longer runs: scripts/fuzz.sh 3600, or in CPU time
#                               on a shared machine: scripts/fuzz-cpu.sh
# Crashes are written to build-fuzz/artifacts/; each one found becomes a file in
# tests/fuzz/regressions/<target>/, which test_fuzz_regressions replays in every build through
# the same checks.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
scripts/configure.sh build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DTESSERA_FUZZ=ON
cmake --build build-fuzz -j"$(nproc)" --target fuzz_sdl fuzz_mesh fuzz_vrml \
  fuzz_job_request fuzz_worker_frames

corpus=build-fuzz/corpus
mkdir -p "$corpus/sdl" "$corpus/mesh" "$corpus/vrml" build-fuzz/artifacts
find scenes -name '*.sdl' -exec cp {} "$corpus/sdl/" \;
# Plain and gzip-compressed worlds alike (the target inflates what starts with gzip's magic).
find scenes \( -name '*.wrl' -o -name '*.wrl.gz' -o -name '*.wrz' \) -exec cp {} "$corpus/vrml/" \;
# The mesh target's first byte picks the format: 0 OBJ, 1 3VN, 2 3DV, 3 3DM.
for f in $(find scenes -path '*meshes/*' -type f); do
  case "$f" in
    *.obj) prefix='\x00' ;; *.3vn) prefix='\x01' ;; *.3dv) prefix='\x02' ;; *.3dm) prefix='\x03' ;;
    *) continue ;;
  esac
  { printf "$prefix"; cat "$f"; } >"$corpus/mesh/$(basename "$f")"
done
# A JSON job, a form, a tar made from scenes/features; a stream of heartbeats and results.
tests/fuzz/service_seeds.py "$corpus"

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
# The frame target's limit is 4 KB a frame (tests/fuzz/service_fuzz_checks.h): an allocation
# of a megabyte means the decoder trusted a length it should have refused; inputs up to 16 KB
# reach frames over the limit.
declare -A extra=([worker_frames]="-malloc_limit_mb=1 -max_len=16384")
for target in sdl mesh vrml job_request worker_frames; do
  regressions=tests/fuzz/regressions/$target
  if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
    echo "== fuzz_$target: regression inputs"
    build-fuzz/tests/fuzz/fuzz_$target "$regressions"/*
  fi
  echo "== fuzz_$target: ${seconds}s"
  log=build-fuzz/fuzz_$target.log
  status=0
  build-fuzz/tests/fuzz/fuzz_$target "$corpus/$target" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 ${extra[$target]:-} -artifact_prefix=build-fuzz/artifacts/ \
    -print_final_stats=1 >"$log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then
    tail -60 "$log"
    exit "$status"
  fi
  grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)' "$log" || true
done
