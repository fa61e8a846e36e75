#!/usr/bin/env bash
# Installs every Debian 12 package Tessera needs to build, run and test. Idempotent: packages
# already present are left alone, so the run and test commands can call it every time.
set -euo pipefail

packages=(
  # build
  cmake ninja-build g++ clang-format ccache
  # fuzzing (scripts/fuzz.sh): clang and its libFuzzer runtime
  clang libclang-rt-14-dev
  # libraries (docs/ARCHITECTURE.md, "Dependencies")
  libboost-dev nlohmann-json3-dev libopenimageio-dev libspdlog-dev zlib1g-dev libpng-dev libopenexr-dev
  libssl-dev        # SHA-256, HMAC (libcrypto)
  libarchive-dev    # tar bundles
  libcli11-dev      # command lines
  libsleef-dev      # elementary functions with the same bits on every CPU (common/math/portable_math.h)
  libsqlite3-dev    # the coordinator's job store
  libgtest-dev libgmock-dev libbenchmark-dev
  libembree-dev     # benchmark only: bench/embree_bench.cpp traces the same rays through Embree 3
  povray            # benchmark only: scripts/compare-povray.sh renders the same scenes
  # tools used by tests and benchmarks; chromium and node drive the web page's test
  openimageio-tools python3 curl chromium
  # network namespaces for the multi-host test (ip, tc)
  iproute2
  python3-yaml      # tests/deploy/compose_tls_test.py reads docker/compose*.yaml
  openssl           # the openssl command: test certificates, docker/make-tls-cert.sh
)
# Node from another source (NodeSource's nodejs bundles npm) conflicts with Debian's npm, so
# these two are asked for only when their commands are missing.
command -v node >/dev/null || packages+=(nodejs)
command -v npm >/dev/null || packages+=(npm)
# The Kubernetes manifests' test renders them with `kubectl kustomize` (Debian's kubectl 1.20;
# a newer kubectl from elsewhere owns /usr/bin/kubectl too, so only when it is missing).
command -v kubectl >/dev/null || packages+=(kubernetes-client)
# The Slurm batch script's test runs a one-node cluster (slurmctld, slurmd, munged).
packages+=(slurm-wlm munge)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Debian 12's OpenImageIO CMake config lists /usr/include/opencv4 as an include directory
# even when OpenCV is not installed; CMake refuses a missing one.
[ -d /usr/include/opencv4 ] || $sudo mkdir -p /usr/include/opencv4

# playwright-core for the page test, at the version pinned in package-lock.json (the machine
# may already have node and npm from elsewhere, so this runs whatever apt did).
e2e="$(dirname "$0")/../tests/service/e2e"
if [ ! -d "$e2e/node_modules/playwright-core" ]; then
  npm ci --prefix "$e2e" --no-audit --no-fund --loglevel=error
fi
