#!/usr/bin/env bash
# Builds the images, starts docker/compose.yaml (a coordinator and two workers in containers),
# renders the demo scene through it and checks the image is bit-identical to tessera-render on
# the host; checks both containers' health, that they run as a non-root user, and that the
# worker's image is under 150 MB.
#   scripts/test-images.sh      (needs root or sudo; about 6 minutes the first time)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
scripts/build-images.sh >/dev/null
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
compose=($sudo podman-compose --podman-args="--runtime runc" -f docker/compose.yaml)
export TESSERA_SECRET TESSERA_API_TOKEN
TESSERA_SECRET=$(head -c 18 /dev/urandom | base64)
TESSERA_API_TOKEN=$(head -c 18 /dev/urandom | base64)
cleanup() { "${compose[@]}" down >/dev/null 2>&1 || true; }
trap cleanup EXIT
# A network made before the dnsname plugin was installed has no name resolution: start afresh.
cleanup
$sudo podman network rm -f docker_default >/dev/null 2>&1 || true
"${compose[@]}" up -d >/dev/null 2>&1

api=http://localhost:8080/api
for _ in $(seq 100); do
  [ "$(curl -sf "$api/workers" | python3 -c 'import json,sys; print(len(json.load(sys.stdin)))' 2>/dev/null)" = 2 ] && break
  sleep 0.2
done
settings='{"width": 320, "height": 240, "aa": 5, "stochastic": true, "passes": 2}'
job=$(curl -sf -H 'Content-Type: application/json' -H "Authorization: Bearer $TESSERA_API_TOKEN" \
  -d "{\"scene_file\": \"demo.sdl\", \"settings\": $settings}" "$api/jobs" |
  python3 -c 'import json,sys; print(json.load(sys.stdin)["id"])')
for _ in $(seq 300); do
  state=$(curl -sf "$api/jobs/$job" | python3 -c 'import json,sys; print(json.load(sys.stdin)["state"])')
  [ "$state" = running ] || [ "$state" = queued ] || break
  sleep 0.1
done
[ "$state" = done ] || { echo "FAIL: job $job is $state"; exit 1; }
tmp=$(mktemp -d)
curl -sf "$api/jobs/$job/image?format=exr" -o "$tmp/containers.exr"
build/worker/tessera-render scenes/demo.sdl -o "$tmp/host.exr" --width 320 --height 240 --aa 5 \
  --stochastic --passes 2 --quiet
build/tests/service/exr_equal "$tmp/containers.exr" "$tmp/host.exr"
rm -rf "$tmp"
echo "ok: the image rendered by two worker containers is bit-identical to tessera-render"
# The worker's image is the program and what it loads (docker/collect-root.sh): under 150 MB.
worker_bytes=$($sudo podman image inspect localhost/tessera-worker --format '{{.Size}}')
[ "$worker_bytes" -lt 150000000 ] || { echo "FAIL: the worker's image is $worker_bytes bytes"; exit 1; }
echo "ok: the worker's image is $((worker_bytes / 1000000)) MB"
for c in docker_coordinator_1 docker_worker_1; do
  $sudo podman healthcheck run "$c" 2>/dev/null || { echo "FAIL: $c is not healthy"; exit 1; }
  # The main process's user as podman sees it (the worker's image has no `id` to run inside).
  user=$($sudo podman top "$c" user | awk 'NR == 2 { print $1 }')
  [ "$user" != root ] || { echo "FAIL: $c runs as root"; exit 1; }
  echo "ok: $c is healthy and runs as $user"
done
