#!/usr/bin/env bash
# The main job: installs what is needed, builds, starts the coordinator with local workers,
# submits the demo scene and prints the URL to open. Ctrl-C stops everything.
#   scripts/run.sh [--port P] [--workers N] [--scene FILE]
set -euo pipefail
cd "$(dirname "$0")/.."

port=8080
workers=2
scene=scenes/demo.sdl
while [ $# -gt 0 ]; do
  case "$1" in
    --port) port="$2"; shift 2 ;;
    --workers) workers="$2"; shift 2 ;;
    --scene) scene="$2"; shift 2 ;;
    *) echo "usage: scripts/run.sh [--port P] [--workers N] [--scene FILE]" >&2; exit 2 ;;
  esac
done

scripts/install-deps.sh
scripts/build.sh

build/coordinator/tessera-coordinator --http-port "$port" --worker-port 0 \
  --local-workers "$workers" --scenes-dir scenes &
coordinator=$!
trap 'kill $coordinator 2>/dev/null; wait $coordinator 2>/dev/null' EXIT INT TERM

for _ in $(seq 100); do
  curl -sf "http://localhost:$port/api/workers" >/dev/null 2>&1 && break
  kill -0 $coordinator 2>/dev/null || { echo "the coordinator did not start" >&2; exit 1; }
  sleep 0.1
done

body=$(python3 -c 'import json,sys; print(json.dumps({"scene_file": sys.argv[1],
  "settings": {"width": 800, "height": 600, "aa": 5}}))' "${scene#scenes/}")
answer=$(curl -sS -H 'Content-Type: application/json' -d "$body" \
  "http://localhost:$port/api/jobs")
job=$(python3 -c 'import json,sys; print(json.load(sys.stdin)["id"])' <<<"$answer")

echo
echo "Tessera is running with $workers local workers; $scene is job $job."
echo "Open http://localhost:$port/#job=$job   (Ctrl-C stops the coordinator and its workers)"
wait $coordinator
