#!/bin/bash
# Times a change against the landed main on this machine, side by side: BASE and NEW are two vct
# binaries (main built beside the change), run alternately ROUNDS times (default 2) on each case,
# so that both see the same machine state. Writes OUT (JSON: per case and binary, every run's
# figures), which `vct bench --report DIR --rewrite --speed OUT` puts into the report's speed
# section as the median of each binary's runs and their ratio.
#   scripts/speed-vs-main.sh BASE NEW OUT
# Each case is one `vct render`, its figure the median GPU frame time over its frames after the
# first (--frames N: the first frame also pays for llvmpipe compiling each pipeline at its first
# dispatch, which the `first` figure keeps: that run's wall clock). Needs ../shared for Sponza.
set -e
BASE=$1; NEW=$2; OUT=$3; ROUNDS=${ROUNDS:-2}
[ -x "$BASE" ] && [ -x "$NEW" ] && [ -n "$OUT" ] || { echo "usage: $0 BASE NEW OUT" >&2; exit 2; }
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} MESA_SHADER_CACHE_DISABLE=true
R=$(cd "$(dirname "$0")/.." && pwd); T=$(mktemp -d)
INSIDE=$R/assets/scenes/cornell-inside.toml; SP=$R/assets/scenes/sponza.toml
# name|frames|arguments
CASES=(
  "demo (Cornell spot 256², 128³, render default)|3|"
  "Cornell 1280×720, 64³, camera inside (render default)|3|$INSIDE"
  "viewer default, Cornell 1280×720, 64³, orbiting 0.5° a frame|12|--width 1280 --height 720 --res 64 --gi-scale 8 --gi-accumulate on --reuse-volume on --orbit 0.5"
  "viewer default, Cornell 1280×720, 64³, still|12|--width 1280 --height 720 --res 64 --gi-scale 8 --gi-accumulate on --reuse-volume on"
)
[ -e "$R/../shared/scenes/sponza/sponza.obj" ] && CASES+=(
  "viewer default, Sponza 640×360, 64³, orbiting 0.5° a frame|12|$SP --res 64 --gi-scale 8 --gi-accumulate on --reuse-volume on --orbit 0.5"
)
echo "[" > "$OUT"; first=1
for c in "${CASES[@]}"; do
  IFS='|' read -r name frames args <<< "$c"
  for r in $(seq "$ROUNDS"); do
    for which in base new; do
      bin=$BASE; [ $which = new ] && bin=$NEW
      s=$(date +%s%N)
      # shellcheck disable=SC2086
      "$bin" render $args --frames "$frames" --out "$T/x.png" --timings "$T/t.json" > "$T/log" 2>&1 \
        || { echo "$which failed on $name:"; tail -5 "$T/log"; exit 1; } >&2
      wall=$(( ($(date +%s%N) - s) / 1000000 ))
      [ $first = 1 ] || echo "," >> "$OUT"; first=0
      printf '{"case": "%s", "binary": "%s", "round": %d, "frames": %d, "run_wall_ms": %d, "timings": ' \
        "$name" "$which" "$r" "$frames" "$wall" >> "$OUT"
      cat "$T/t.json" >> "$OUT"; echo "}" >> "$OUT"
      total=$(python3 -c 'import json,sys; print(next(p["ms"] for p in json.load(open(sys.argv[1]))["passes"] if p["pass"] == "total"))' "$T/t.json")
      echo "$name [$which $r]: frame $total ms, run $wall ms" >&2
    done
  done
done
echo "]" >> "$OUT"; rm -rf "$T"
