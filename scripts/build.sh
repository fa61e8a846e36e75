#!/usr/bin/env bash
# Configures and builds Tessera in build/ (optimized, with debug info). Usage: scripts/build.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/configure.sh build -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build -j"$(nproc)"
