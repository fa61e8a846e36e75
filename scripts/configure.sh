#!/usr/bin/env bash
# Configures one build folder the way the project's own scripts and CI build: Ninja, warnings
# as errors, and ccache when it is installed (so a second build of the same sources, in any
# folder or clone, compiles only what changed).
#   scripts/configure.sh DIR [CMAKE ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
shift
launcher=()
if command -v ccache >/dev/null; then
  # Paths under the clone are hashed relative to it, so clones in other folders share hits.
  launcher=("-DCMAKE_CXX_COMPILER_LAUNCHER=env;CCACHE_BASEDIR=$PWD;CCACHE_NOHASHDIR=1;ccache")
fi
cmake -S . -B "$dir" -G Ninja -DTESSERA_WERROR=ON "${launcher[@]}" "$@" >/dev/null
