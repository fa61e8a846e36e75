#!/usr/bin/env bash
# Compiles every target in the two configurations the test build does not cover, with warnings
# as errors: GCC Release (-O3, what packagers and users build) in build-release/, and Clang in
# build-clang/. Their tests are not run again: scripts/test.sh runs them on build/.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
scripts/configure.sh build-release -DCMAKE_BUILD_TYPE=Release
cmake --build build-release -j"$jobs"
scripts/configure.sh build-clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++
cmake --build build-clang -j"$jobs"
