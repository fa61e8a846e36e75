#!/usr/bin/env bash
# Mutation check (issue 23, §1): applies known bugs one at a time, builds the affected target,
# runs the tests that claim to cover the feature, and expects them to FAIL. A mutation the
# tests let through is a hole in the tests. Not run by CI; docs/TESTING.md records the last run.
#
#   scripts/mutation-check.sh [BUILD_DIR] [NAME...]   default build/, every mutation
#
# Each mutation replaces one exact string in one file of this checkout (the script refuses a
# file with uncommitted changes), and the file is restored with `git checkout` afterwards, also
# on interruption, when the targets are rebuilt so the build matches the sources again.
# Needs a configured build (docs/SERVICE.md); the page mutations need node, chromium and
# `npm ci --prefix tests/service/e2e`.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
only=("$@")

service() { python3 tests/service/service_test.py --build "$build" --source . "$1"; }
gtest() { "$build/tests/$1" --gtest_filter="$2"; }

# name ~ file ~ exact text (\n for a line break) ~ replacement ~ targets to build ~ test command
mutations=(
  "auth_downgrade~worker/session/worker_session.cpp~if (!config_.secret.empty() && auth != \"hmac-sha256\")~if (!config_.secret.empty() && auth != \"hmac-sha256\" && auth != \"none\")~tessera-worker~python3 tests/service/worker_auth_test.py --build $build --source ."
  "welcome_proof_ignored~worker/session/worker_session.cpp~if (!constant_time_equal(frame.header.value(\"proof\", std::string()), expected))~if ((false))~tessera-worker~python3 tests/service/worker_auth_test.py --build $build --source ."
  "proof_nonce_order~common/protocol/handshake.cpp~\"|\" + worker_nonce + \"|\" + coordinator_nonce));~\"|\" + coordinator_nonce + \"|\" + worker_nonce));~test_protocol~gtest test_protocol Handshake*:ProtocolDoc*"
  "doc_proof_version~docs/PROTOCOL.md~\"tessera-worker|2|Nc|Nw\"~\"tessera-worker|1|Nc|Nw\"~test_protocol~gtest test_protocol ProtocolDoc*"
  "sha256_padding_55~common/protocol/sha256.cpp~rest + 9 <= 64 ? 64 : 128~rest + 9 < 64 ? 64 : 128~test_protocol~gtest test_protocol Sha256*"
  "marble_octaves~common/texture/solid_texture.cpp~constexpr int kMarbleOctaves = 6;~constexpr int kMarbleOctaves = 5;~test_texture~gtest test_texture SolidTexture.Marble*"
  "mesh_bounds_two_vertices~common/accel/mesh_accel.cpp~for (const std::uint32_t v : mesh.triangles[i].v) bounds[i].extend(mesh.positions.at(v));~for (int k = 0; k < 2; ++k) bounds[i].extend(mesh.positions.at(mesh.triangles[i].v[k]));~test_fuzz_regressions~$build/tests/fuzz/test_fuzz_regressions"
  "over_range_samples~common/render/render.cpp~constexpr double kMax = std::numeric_limits<float>::max();~constexpr double kMax = std::numeric_limits<double>::max();~test_fuzz_regressions~$build/tests/fuzz/test_fuzz_regressions"
  "frame_buffer_blue_from_green~common/render/frame_buffer.cpp~  sums_[3 * i + 2] += rgb[2];~  sums_[3 * i + 2] += rgb[1];~test_coordinator~gtest service/test_coordinator JobMerge*"
  "constant_etag~coordinator/http/api.cpp~std::to_string(job.version) + \"-\" + format~std::to_string(0) + \"-\" + format~tessera-coordinator tessera-worker~node tests/service/e2e/page_test.js $build ."
  "page_records_failed_loads~web/app.js~    img.src = url;\n  });~    img.src = url + (view.version % 2 ? \"broken\" : \"\");\n  }).then(() => true);~~node tests/service/e2e/page_test.js $build ."
)

built=()
restore() {
  if [ -n "${current:-}" ]; then git checkout -q -- "$current"; fi
  current=
}
# Restores the mutated file and rebuilds what was built with a mutation, however the run ends,
# so that no binary keeps a bug.
finish() {
  restore
  # shellcheck disable=SC2068
  if [ ${#built[@]} -gt 0 ]; then nice cmake --build "$build" -j2 --target ${built[@]} >/dev/null; fi
}
trap finish EXIT
trap 'exit 130' INT TERM

caught=0 missed=0
for entry in "${mutations[@]}"; do
  IFS='~' read -r name file text replacement targets command <<<"$entry"
  if [ ${#only[@]} -gt 0 ] && [[ ! " ${only[*]} " == *" $name "* ]]; then continue; fi
  if ! git diff --quiet -- "$file"; then
    echo "!! $name: $file has uncommitted changes; skipped" >&2
    continue
  fi
  current=$file
  python3 - "$file" "$text" "$replacement" <<'EOF'
import sys
path, text, replacement = sys.argv[1], sys.argv[2].replace("\\n", "\n"), sys.argv[3].replace("\\n", "\n")
source = open(path).read()
if source.count(text) != 1:
    sys.exit("%s: the text to mutate occurs %d times" % (path, source.count(text)))
open(path, "w").write(source.replace(text, replacement))
EOF
  if [ -n "$targets" ]; then
    built+=($targets)
    # shellcheck disable=SC2086
    if ! nice cmake --build "$build" -j2 --target $targets >"/tmp/mutation-$name.log" 2>&1; then
      echo "BROKEN  $name: does not build (log: /tmp/mutation-$name.log)"
      missed=$((missed + 1))
      restore
      continue
    fi
  fi
  if (eval "$command") >"/tmp/mutation-$name.log" 2>&1; then
    echo "MISSED  $name: the tests passed with the bug (log: /tmp/mutation-$name.log)"
    missed=$((missed + 1))
  else
    echo "caught  $name"
    caught=$((caught + 1))
  fi
  restore
done
echo "$caught caught, $missed missed"
[ "$missed" -eq 0 ]
