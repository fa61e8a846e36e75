#!/usr/bin/env bash
# Long fuzzing runs measured in CPU time rather than wall time, so that a run on a shared
# machine still gets its full budget: each TARGET (e.g. job_request worker_frames) runs niced,
# side by side with the others, and is interrupted once its process has used SECONDS of CPU;
# libFuzzer then prints its final statistics. Run scripts/fuzz.sh first: it builds the targets in
# build-fuzz/ and seeds their corpora, which these runs grow.
#   scripts/fuzz-cpu.sh SECONDS TARGET...      e.g. scripts/fuzz-cpu.sh 3600 job_request worker_frames
# Logs: build-fuzz/fuzz_TARGET.cpu.log; crashes: build-fuzz/artifacts/. Exits non-zero if a
# target stopped by itself (a crash, a leak, a broken invariant).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=$1
shift
ticks=$(getconf CLK_TCK)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
declare -A extra=([worker_frames]="-malloc_limit_mb=1 -max_len=16384")
declare -A pids
for target in "$@"; do
  nice -n 19 build-fuzz/tests/fuzz/fuzz_"$target" build-fuzz/corpus/"$target" -timeout=10 \
    -rss_limit_mb=2048 ${extra[$target]:-} -artifact_prefix=build-fuzz/artifacts/ \
    -print_final_stats=1 >build-fuzz/fuzz_"$target".cpu.log 2>&1 &
  pids[$target]=$!
done

cpu_seconds() {  # utime + stime of a process, fields 14 and 15 of /proc/PID/stat
  awk -v t="$ticks" '{ sub(/^.*\) /, ""); print int(($12 + $13) / t) }' "/proc/$1/stat" 2>/dev/null
}

status=0
while [ ${#pids[@]} -gt 0 ]; do
  sleep 10
  for target in "${!pids[@]}"; do
    pid=${pids[$target]}
    if ! kill -0 "$pid" 2>/dev/null; then
      wait "$pid" || true
      echo "fuzz_$target stopped by itself: see build-fuzz/fuzz_$target.cpu.log"
      status=1
      unset "pids[$target]"
    elif [ "$(cpu_seconds "$pid")" -ge "$seconds" ]; then
      kill -INT "$pid"
      wait "$pid" || true  # libFuzzer exits with its interrupt code after the final stats
      echo "== fuzz_$target: ${seconds} s of CPU"
      log=build-fuzz/fuzz_"$target".cpu.log
      grep -m1 -E '^#[0-9]+[[:space:]]+INITED' "$log" || true
      { grep -E '^#[0-9]+[[:space:]].*cov:' "$log" || true; } | tail -1
      grep -E '^stat::' "$log" || true
      unset "pids[$target]"
    fi
  done
done
exit "$status"
