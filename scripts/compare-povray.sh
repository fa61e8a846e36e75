#!/usr/bin/env bash
# Renders scenes with Tessera and with POV-Ray 3.7 (their translations in bench/povray/) at the
# same size, anti-aliasing regime and thread count, repeats every render, interleaving the two
# renderers so that the load of a noisy machine falls on both, and prints the median wall times
# and their ratio.
#
# Usage: scripts/compare-povray.sh [--scenes "demo torus teapot100k"] [--width W] [--height H]
#                                  [--repeats N] [--threads "1 2"] [--tessera PATH] [--out DIR]
#
# --tessera: the tessera-render to time (default build/worker/tessera-render), for example
# another build of it to compare with the same POV-Ray runs. --out: where images, logs and
# times go (default out/povray). CTest runs it tiny (bench_smoke_compare_povray) when povray is
# installed, so that a change to either renderer's report cannot break it unnoticed.
#
# Scenes (SDL file, POV-Ray file):
#   demo        scenes/demo.sdl, bench/povray/demo.pov: glass, mirror, spotlight, reflections.
#   torus       scenes/features/torus.sdl, bench/povray/torus.pov: ring, horn and spindle tori.
#   teapot100k  bench/povray/teapot100k.{sdl,pov}: a 102,080-triangle Utah teapot, Phong
#               normals. The mesh is generated into out/povray/teapot100k/ on first use
#               (scripts/make_teapot.py --segments 40, then bench/povray/obj_to_mesh2.py).
#
# Regimes (the same number of camera rays per pixel, near enough, for both):
#   aa1: Tessera --aa 1 (one ray through the pixel centre)  vs  POV-Ray -A (no anti-aliasing,
#        one ray through the pixel centre).
#   aa9: Tessera --aa 9 (every pixel: a fixed 3x3 grid at the corners, edge midpoints and
#        centre, 9 rays, box-averaged)  vs  POV-Ray +AM1 +A0.0 +R3 -J. POV's method 1 compares
#        each pixel with its neighbours and supersamples it when they differ by >= the
#        threshold; with threshold 0 that is every pixel, so this is fixed supersampling: a 3x3
#        grid at +-1/3 pixel around the centre, averaged with the pixel's first centre ray
#        (10 rays a pixel, plus one ray for each pixel left of and above each 32x32 block,
#        about 6% more). -J turns off jitter. POV's method 2 (+AM2 +R2) would sample exactly
#        Tessera's grid but shares corner rays between pixels (about 4 rays a pixel) and weights
#        them as a tent filter, so it is less comparable in work.
#
# Times are the wall times of the whole process (start-up, parsing, rendering, writing the PNG),
# measured with date +%s.%N; the medians of the repeats are printed. A second table gives each
# renderer's own render time (Tessera's report "time:", POV-Ray's "Trace Time"), which leaves
# out start-up and parsing, and a third their render's CPU time over all threads (Tessera's
# "cpu:", POV-Ray's CPU-seconds after its Trace Time): on a shared machine the wall times also
# count the time other processes held the cores, the CPU times do not.
set -euo pipefail
cd "$(dirname "$0")/.."

scenes="demo torus teapot100k"
width=800
height=600
repeats=3
threads="1 2"
tessera=build/worker/tessera-render
out_root=out/povray
while (($#)); do
  case "$1" in
    --scenes) scenes=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --repeats) repeats=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --tessera) tessera=$2; shift 2 ;;
    --out) out_root=$2; shift 2 ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "compare-povray.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done


missing=0
if [[ ! -x $tessera ]]; then
  echo "compare-povray.sh: $tessera is missing; build it with scripts/build.sh" >&2
  missing=1
fi
if ! povray=$(command -v povray); then
  echo "compare-povray.sh: povray is not installed; install it with: sudo apt-get install povray" >&2
  missing=1
fi
((missing == 0)) || exit 1

# use_scene NAME: sets scene, pov_scene and out (this scene's folder of results), and writes
# generated inputs.
use_scene() {
  out=$out_root/$1
  mkdir -p "$out/logs"
  case "$1" in
    demo) scene=scenes/demo.sdl; pov_scene=bench/povray/demo.pov ;;
    torus) scene=scenes/features/torus.sdl; pov_scene=bench/povray/torus.pov ;;
    teapot100k)
      scene=$out/teapot100k.sdl
      pov_scene=$out/teapot100k.pov
      cp bench/povray/teapot100k.sdl bench/povray/teapot100k.pov "$out/"
      if [[ ! -s $out/teapot100k.inc ]]; then
        echo "writing the 102,080-triangle teapot to $out/ (about 15 s)"
        python3 scripts/make_teapot.py --segments 40 >"$out/teapot100k.obj"
        python3 bench/povray/obj_to_mesh2.py "$out/teapot100k.obj" Teapot >"$out/teapot100k.inc.tmp"
        mv "$out/teapot100k.inc.tmp" "$out/teapot100k.inc"
      fi
      ;;
    *) echo "compare-povray.sh: unknown scene $1 (demo, torus or teapot100k)" >&2; exit 2 ;;
  esac
}

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }

# log_field SED_SCRIPT LOG: the figure SED_SCRIPT prints from a renderer's log; a log without it
# (a renderer whose report changed) stops the script rather than leaving a blank in the tables.
log_field() {
  local value
  value=$(sed -n "$1" "$2")
  if [[ -z $value ]]; then
    echo "compare-povray.sh: $2 has no line that matches $1" >&2
    return 1
  fi
  echo "$value"
}

# run_tessera AA THREADS REPEAT
run_tessera() {
  local aa=$1 t=$2 rep=$3 log start end render cpu
  log=$out/logs/tessera-aa$aa-t$t-$rep.log
  start=$(now)
  # stderr is not a terminal, so there is no progress output; stdout is the report.
  "$tessera" "$scene" -o "$out/tessera-aa$aa-t$t.png" --width "$width" --height "$height" \
    --aa "$aa" --threads "$t" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
  end=$(now)
  render=$(log_field 's/^time: \([0-9.]*\) s$/\1/p' "$log")
  cpu=$(log_field 's/^cpu: \([0-9.]*\) s$/\1/p' "$log")
  printf 'tessera\t%s\t%s\t%s\t%s\t%s\t%s\n' "$aa" "$t" "$rep" "$(elapsed "$start" "$end")" \
    "$render" "$cpu" >>"$times"
}

# run_povray AA THREADS REPEAT
run_povray() {
  local aa=$1 t=$2 rep=$3 log start end render cpu aa_options
  log=$out/logs/povray-aa$aa-t$t-$rep.log
  if ((aa == 1)); then aa_options=(-A); else aa_options=(+A0.0 +AM1 +R3 -J); fi
  start=$(now)
  # File_Gamma=1.0 with the scene's assumed_gamma 1: linear values in the PNG, as Tessera's.
  # -D no display, -P no pause, -V no progress lines.
  # +L: includes are found beside the scene (teapot100k.inc).
  "$povray" +I"$pov_scene" +L"$(dirname "$pov_scene")" +O"$out/povray-aa$aa-t$t.png" \
    +W"$width" +H"$height" +FN File_Gamma=1.0 -D -P -V +WT"$t" "${aa_options[@]}" >"$log" 2>&1 || { cat "$log" >&2; exit 1; }
  end=$(now)
  render=$(log_field 's/^ *Trace Time:.*(\([0-9.]*\) seconds)$/\1/p' "$log")
  # The line after "Trace Time" gives the trace's CPU time over all threads.
  cpu=$(log_field '/Trace Time:/{n;s/.* with \([0-9.]*\) CPU-seconds total$/\1/p}' "$log")
  printf 'povray\t%s\t%s\t%s\t%s\t%s\t%s\n' "$aa" "$t" "$rep" "$(elapsed "$start" "$end")" \
    "$render" "$cpu" >>"$times"
}

# median COLUMN RENDERER AA THREADS
median() {
  awk -F'\t' -v col="$1" -v r="$2" -v aa="$3" -v t="$4" \
    'NR > 1 && $1 == r && $2 == aa && $3 == t && $col != "" { print $col }' "$times" |
    sort -g | awk '{ v[NR] = $1 } END {
      if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2];
      else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# table COLUMN TITLE
table() {
  echo
  echo "$2 (median of $repeats, seconds)"
  printf '%-28s %7s %10s %10s %15s\n' "anti-aliasing" threads Tessera POV-Ray Tessera/POV-Ray
  local aa t tes pov label
  for aa in 1 9; do
    if ((aa == 1)); then label="none (--aa 1 / -A)"; else label="3x3 (--aa 9 / +AM1 +R3)"; fi
    for t in $threads; do
      tes=$(median "$1" tessera "$aa" "$t")
      pov=$(median "$1" povray "$aa" "$t")
      printf '%-28s %7s %10.3f %10.3f %15.2f\n' "$label" "$t" "$tes" "$pov" \
        "$(awk -v a="$tes" -v b="$pov" 'BEGIN { print a / b }')"
    done
  done
}


# image_difference: how far apart the pictures of the current scene are (python3's standard
# library only; skipped without python3).
image_difference() {
  local first_t=${threads%% *}
  if command -v python3 >/dev/null; then
    echo
    echo "Image difference, Tessera vs POV-Ray (8-bit values; diff-aa*.png shows |difference| x 4)"
    for aa in 1 9; do
      printf '%-28s ' "$( ((aa == 1)) && echo "none" || echo "3x3")"
      python3 - "$out/tessera-aa$aa-t$first_t.png" "$out/povray-aa$aa-t$first_t.png" \
        "$out/diff-aa$aa.png" <<'PY'
import struct, sys, zlib

def chunks(data):
    pos = 8
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        yield kind, data[pos + 8:pos + 8 + n]
        pos += 12 + n

def load(path):  # 8-bit RGB or RGBA, non-interlaced: what both renderers write
    data = open(path, 'rb').read()
    idat = b''.join(body for kind, body in chunks(data) if kind == b'IDAT')
    w, h, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', next(chunks(data))[1])
    assert depth == 8 and ctype in (2, 6) and interlace == 0, f'{path}: unsupported PNG'
    bpp = 3 if ctype == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if bpp == 3 else bytes(v for i, v in enumerate(line) if i % 4 != 3))
        prev = line
    return w, h, rows

(w, h, a), (w2, h2, b) = load(sys.argv[1]), load(sys.argv[2])
assert (w, h) == (w2, h2), 'image sizes differ'
total = over2 = over16 = 0
worst = 0
diff_rows = []
for ra, rb in zip(a, b):
    d = bytes(abs(x - y) for x, y in zip(ra, rb))
    diff_rows.append(b'\0' + bytes(min(255, 4 * v) for v in d))
    total += sum(d)
    for i in range(0, len(d), 3):
        m = max(d[i:i + 3])
        over2 += m > 2
        over16 += m > 16
        worst = max(worst, m)
n = w * h
print(f'mean |diff| {total / (3 * n):.2f}, pixels off by > 2: {100 * over2 / n:.1f}%, '
      f'> 16: {100 * over16 / n:.1f}%, largest {worst}')

def chunk(kind, body):
    return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
with open(sys.argv[3], 'wb') as f:
    f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(b''.join(diff_rows))) + chunk(b'IEND', b''))
PY
    done
  fi
}

# compare NAME: every render of one scene, its tables and its image difference.
compare() {
  use_scene "$1"
  times=$out/times.tsv
  printf 'renderer\taa\tthreads\trepeat\twall_s\trender_s\tcpu_s\n' >"$times"
  echo
  echo "== $1: $scene vs $pov_scene"
  # One untimed warm-up of each, so that neither pays for a cold page cache.
  "$tessera" "$scene" -o "$out/warmup.png" --width 64 --height 48 --quiet
  "$povray" +I"$pov_scene" +L"$(dirname "$pov_scene")" +O"$out/warmup.png" +W64 +H48 +FN \
    -D -P -V +WT1 -A >"$out/logs/povray-warmup.log" 2>&1 || { cat "$out/logs/povray-warmup.log" >&2; exit 1; }
  rm -f "$out/warmup.png"

  for ((rep = 1; rep <= repeats; rep++)); do
    for aa in 1 9; do
      for t in $threads; do
        # Alternate which renderer goes first, so that neither always follows the other.
        if ((rep % 2)); then
          run_tessera "$aa" "$t" "$rep"; run_povray "$aa" "$t" "$rep"
        else
          run_povray "$aa" "$t" "$rep"; run_tessera "$aa" "$t" "$rep"
        fi
        printf '.'
      done
    done
  done
  echo
  echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"

  table 5 "Wall time of the whole process"
  table 6 "Render time as each renderer reports it (Tessera 'time:', POV-Ray 'Trace Time')"
  table 7 "Render CPU time, all threads, as each renderer reports it (Tessera 'cpu:', POV-Ray's Trace CPU-seconds)"

  image_difference
  echo
  echo "Every run: $times; images: $out/{tessera,povray}-aa{1,9}-t*.png; logs: $out/logs/"
}

echo "Tessera ($tessera) vs POV-Ray ($("$povray" --version 2>&1 | sed -n 's/^\(POV-Ray [^ ]*\).*/\1/p'))," \
  "${width}x$height, $repeats repeats, threads: $threads, $(nproc) cores"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"

for name in $scenes; do compare "$name"; done
