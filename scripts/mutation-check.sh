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
  "cancel_never_sent~coordinator/scheduler/scheduler.cpp~    w.connection->send(Frame{MessageType::Cancel, {{\"job\", job.id}}, {}});~    (void)0;~test_coordinator~gtest service/test_coordinator SchedulerTest.*"
  "cancel_ignored~worker/render_loop/render_loop.cpp~void RenderLoop::cancel_job(std::int64_t job) {~void RenderLoop::cancel_job(std::int64_t job) {\n  if (job >= 0) return;~test_worker~gtest test_worker RenderLoopCancel.*"
  "cancel_frame_ignored~worker/session/worker_session.cpp~          return loop_.cancel_job(frame.header.at(\"job\").get<std::int64_t>());~          return;~tessera-worker~python3 tests/service/worker_cancel_test.py --build $build --source ."
  "bundle_hash_unchecked~worker/session/worker_session.cpp~if (content_hash(*bundle) != hash)~if ((false))~tessera-worker~python3 tests/service/worker_cancel_test.py --build $build --source ."
  "bundles_never_reused~worker/render_loop/render_loop.cpp~  } else if (cached != bundles_.end()) {~  } else if ((false)) {~test_worker~gtest test_worker RenderLoopBundles.*"
  "bundle_cache_of_nine~worker/render_loop/render_loop.cpp~constexpr std::size_t kCachedBundles = 8;~constexpr std::size_t kCachedBundles = 9;~test_worker~gtest test_worker RenderLoopBundles.*"
  "speculation_at_once~coordinator/scheduler/scheduler.cpp~if (seconds_since(r.dispatched, now) < wait) continue;~if (seconds_since(r.dispatched, now) < 0 * wait) continue;~test_coordinator~gtest service/test_coordinator SpeculationDeadlineTest.*"
  "speculation_factor_ignored~coordinator/scheduler/scheduler.cpp~std::max(options_.speculation_factor * mean,~std::max(0 * mean,~test_coordinator~gtest service/test_coordinator SpeculationDeadlineTest.*"
  "speculation_to_busy_workers~coordinator/scheduler/scheduler.cpp~if (static_cast<int>(w.in_flight.size()) >= w.hello.threads) return false;~if ((false)) return false;~test_coordinator~gtest service/test_coordinator SchedulerTest.*"
  "calibration_inputs_swapped~coordinator/scheduler/scheduler.cpp~job.stats.seconds / job.prediction_threads,\n                         job.elapsed_seconds(*job.finished));~7 * job.elapsed_seconds(*job.finished),\n                         job.stats.seconds / job.prediction_threads);~test_coordinator~gtest service/test_coordinator SchedulerTest.Calibration*"
  "ran_alone_ignored~coordinator/scheduler/scheduler.cpp~state == JobState::Done && job.ran_alone &&~state == JobState::Done &&~test_coordinator~gtest service/test_coordinator SchedulerTest.*Calibrate*"
  "job_store_unbounded~coordinator/jobs/job_store.cpp~if (static_cast<int>(jobs_.size()) >= max_jobs_) return nullptr;~if ((false)) return nullptr;~tessera-coordinator~python3 tests/service/job_answers_test.py --build $build --source . full_store"
  "tiles_since_ignored~coordinator/http/job_json.cpp~for (std::size_t i = since; i < job.tiles.size(); ++i)~for (std::size_t i = 0 * since; i < job.tiles.size(); ++i)~tessera-coordinator~python3 tests/service/job_answers_test.py --build $build --source . tiles_since"
  "image_format_unchecked~coordinator/http/api.cpp~if (format != \"png\" && format != \"exr\")~if ((false))~tessera-coordinator~python3 tests/service/job_answers_test.py --build $build --source . image_format"
  "round_trip_in_centiseconds~coordinator/scheduler/scheduler.cpp~{\"round_trip_ms\", w.pipeline.round_trip_seconds() * 1e3},~{\"round_trip_ms\", w.pipeline.round_trip_seconds() * 1e2},~tessera-coordinator~python3 tests/multihost/multihost_test.py --build $build --source . identical"
  "rerender_route_missing~coordinator/http/api.cpp~if (sub == \"rerender\" && method == http::verb::post)~if ((false))~tessera-coordinator~python3 tests/service/rerender_test.py --build $build --source . answers"
  "rerender_settings_ignored~coordinator/http/submission.cpp~      if (!value.is_null())\n        settings[key] = value;~      if (!value.is_null())\n        (void)0;~tessera-coordinator~python3 tests/service/rerender_test.py --build $build --source . images"
  "status_settings_lose_preview~coordinator/http/job_json.cpp~  settings[\"preview\"] = to_string(job.plan_options.preview);\n~~test_coordinator~gtest service/test_coordinator JobSettingsJson.*"
  "page_moves_only_own_jobs~web/navigation.js~  if (view.job === null || !nav.camera) return;~  if (view.job === null || !nav.camera || !nav.own.has(view.job)) return;~~node tests/service/e2e/page_test.js $build ."
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
