#!/usr/bin/env bash
# Configures and builds Tessera in build/ (optimized, with debug info). Usage: scripts/build.sh
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$jobs"
