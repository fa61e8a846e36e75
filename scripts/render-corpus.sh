#!/usr/bin/env bash
# Renders every scene file under DIR (.wrl, .wrl.gz, .wrz, .sdl, .dat) small, with a timeout,
# and prints a table: file, ok/warn/fail, reason (the first warning or the error), seconds.
# The last line counts each outcome. For a corpus of real-world worlds (docs/VRML.md).
#
#   scripts/render-corpus.sh DIR [--render PATH] [--timeout SECONDS] [-- tessera-render options]
set -uo pipefail

usage() { sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[[ $# -ge 1 ]] || usage
dir=$1; shift
render=build/worker/tessera-render
limit=60
while [[ $# -gt 0 ]]; do
  case $1 in
    --render) render=$2; shift 2 ;;
    --timeout) limit=$2; shift 2 ;;
    --) shift; break ;;
    *) usage ;;
  esac
done
[[ -d $dir ]] || { echo "render-corpus: no folder $dir" >&2; exit 2; }
[[ -x $render ]] || { echo "render-corpus: no $render (build tessera-render)" >&2; exit 2; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A count=([ok]=0 [warn]=0 [fail]=0)
printf '%-60s %-5s %7s  %s\n' file state seconds reason
while IFS= read -r -d '' file; do
  start=$EPOCHREALTIME
  # Not --quiet: that hides the warnings too.
  timeout --kill-after=5 "$limit" "$render" "$file" -o "$out/image.png" --width 64 --height 48 \
    "$@" >/dev/null 2>"$out/stderr"
  status=$?
  seconds=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }')
  if [[ $status -eq 0 ]] && ! grep -q '^warning: ' "$out/stderr"; then
    state=ok; reason=
  elif [[ $status -eq 0 ]]; then
    state=warn; reason=$(grep -m1 '^warning: ' "$out/stderr" | cut -c10-)
  elif [[ $status -ge 124 ]]; then
    state=fail; reason="timed out or killed after ${limit} s (status $status)"
  else
    state=fail; reason=$(grep -m1 . "$out/stderr" | sed 's/^tessera-render: //')
  fi
  count[$state]=$((count[$state] + 1))
  printf '%-60s %-5s %7s  %s\n' "${file#"$dir"/}" "$state" "$seconds" "${reason:0:160}"
done < <(find "$dir" -type f \( -iname '*.wrl' -o -iname '*.wrl.gz' -o -iname '*.wrz' \
                               -o -iname '*.sdl' -o -iname '*.dat' \) -print0 | sort -z)
total=$((count[ok] + count[warn] + count[fail]))
echo "total $total: ok ${count[ok]}, warn ${count[warn]}, fail ${count[fail]}"
