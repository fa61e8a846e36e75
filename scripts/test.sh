#!/usr/bin/env bash
# The test command: installs what is needed, builds, and runs every test. Five builds, all with
# warnings as errors:
#   build/          optimized: unit, image and integration tests
#   build-asan/     AddressSanitizer + UndefinedBehaviorSanitizer: the unit tests
#   build-fuzz/     clang + libFuzzer: a short fuzz run of the SDL, mesh and VRML loaders (fuzz.sh)
#   build-release/, build-clang/  GCC Release and Clang: compiled, not run (build-configs.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
jobs=$(nproc)

scripts/build.sh
scripts/configure.sh build-asan -DCMAKE_BUILD_TYPE=Debug -DTESSERA_SANITIZE=ON \
  -DTESSERA_UNIT_TESTS_ONLY=ON
cmake --build build-asan -j"$jobs"

echo "== tests (optimized build)"
ctest --test-dir build --output-on-failure -j"$jobs"
echo "== unit tests under AddressSanitizer and UndefinedBehaviorSanitizer"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -L unit
echo "== fuzzing the loaders"
scripts/fuzz.sh 15
echo "== compiling the Release (GCC) and Clang configurations"
scripts/build-configs.sh
