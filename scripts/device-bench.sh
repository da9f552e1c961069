#!/bin/bash
# Runs on a lent GPU machine, from the repository root, after scripts/device-prepare.sh: the benches
# behind the report's GPU figures (docs/report/README.md) in one call, each step bounded so that the
# whole stays inside BUDGET seconds (default 330) and the results always come back, as $OUT/w.tgz
# (data, charts and logs; no images or references) and $OUT/img.tgz (a few renders).
# STEPS (a bash regex) runs only the steps whose names match, e.g. STEPS='persp|acc-layouts'.
# COMMIT names the commit measured in the stamp. Unpacked here, the run goes into the report with
# `vct bench --report docs/report --rewrite --gpu w` (its own section, stamped with the device).
R=$PWD; W=/tmp/w; V=$R/.gpu/vct
rm -rf $W; mkdir -p $W/r $W/acc/cache
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
f=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -e $f ] && export VK_DRIVER_FILES=$f
[ -e ../shared/scenes/sponza/sponza.obj ] || ln -sfn "$R/.gpu/shared" ../shared
cp .gpu/cache/* $W/acc/cache/ 2>/dev/null
f=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
[ -e $f ] || { mkdir -p "$(dirname $f)" && cp .gpu/fonts/DejaVuSans.ttf $f; }
export XDG_RUNTIME_DIR=/tmp
nvidia-smi -L; nvidia-smi --query-gpu=driver_version,clocks.sm,clocks.max.sm --format=csv
T0=$(date +%s); B=${BUDGET:-330}
step() { # name limit command...: never past T0 + B - 15 s, so the tar below always runs
  local n=$1 t=$2; shift 2; local left=$((T0 + B - 15 - $(date +%s)))
  [ -n "$STEPS" ] && ! [[ $n =~ $STEPS ]] && return
  [ $left -lt $t ] && t=$left; [ $t -lt 5 ] && { echo "=== $n: skipped, no time"; return; }
  echo "=== $(date +%T) $n (limit $t s): $*"; local s=$(date +%s%N)
  timeout $t "$@" >$W/r/$n.log 2>&1; echo "rc=$? $(( ($(date +%s%N) - s) / 1000000 )) ms"
  tail -n ${TAIL:-4} $W/r/$n.log
}
SP=assets/scenes/sponza.toml
F="--frames 16"
C="--width 1280 --height 720 --res 64"
S="$SP --width 640 --height 360 --res 64"
TAIL=20 step smoke 40 env VCT_VALIDATION=1 $V render --out $W/r/cornell.png --timings $W/r/cornell.json
TAIL=6 step sync 40 env VCT_VALIDATION=sync $V render $S --gi-scale 4 --gi-accumulate on --reuse-volume on --frames 6 --out $W/r/sync.png
# The frame-time table: full resolution, the viewer's default rebuilding the volume, and still.
step c720-s1 20 $V render $C --gi-scale 1 $F --timings $W/r/c720-s1.json --out $W/r/c720-s1.png
step c720-s4-rebuild 20 $V render $C --gi-scale 4 --gi-accumulate on $F --timings $W/r/c720-s4-rebuild.json --out $W/r/x.png
step c720-s4-still 20 $V render $C --gi-scale 4 --gi-accumulate on --reuse-volume on $F --timings $W/r/c720-s4-still.json --out $W/r/x.png
step s360-s1 20 $V render $S --gi-scale 1 $F --timings $W/r/s360-s1.json --out $W/r/s360-s1.png
step s360-s4-rebuild 20 $V render $S --gi-scale 4 --gi-accumulate on $F --timings $W/r/s360-s4-rebuild.json --out $W/r/x.png
step s360-s4-still 20 $V render $S --gi-scale 4 --gi-accumulate on --reuse-volume on $F --timings $W/r/s360-s4-still.json --out $W/r/x.png
for st in resident sparse dense; do
  step s1080-256-$st 30 $V render $SP --width 1920 --height 1080 --res 256 --storage $st $F --timings $W/r/s1080-256-$st.json --out $W/r/s1080-$st.png
done
step s360-128-warp 20 $V render $SP --res 128 --warp function $F --timings $W/r/s360-128-warp.json --out $W/r/x.png
step s360-clip4x64 20 $V render $SP --clipmap 4 --res 64 --storage sparse $F --timings $W/r/s360-clip4x64.json --out $W/r/x.png
step s360-128-fitted 20 $V render $SP --res 128 $F --timings $W/r/s360-128-fitted.json --out $W/r/x.png
step s360-128-persp 20 $V render $SP --res 128 --warp perspective $F --timings $W/r/s360-128-persp.json --out $W/r/s360-persp.png
TAIL=6 step smoke-persp 40 env VCT_VALIDATION=1 $V render $SP --res 128 --warp perspective --frames 3 --out $W/r/x.png
TAIL=3 step vox-persp 60 $V voxelize $SP --res 128 --warp perspective
# Frames in flight: the wall clock a frame, each waited for, and with one or two in flight.
for k in 0 1 2; do a=""; [ $k -gt 0 ] && a="--in-flight $k"
  step s360-still-k$k 20 $V render $S --gi-scale 4 --gi-accumulate on --reuse-volume on --frames 300 $a --timings $W/r/s360-still-k$k.json --out $W/r/x.png
  [ -e $W/r/s360-still-k$k.log ] && grep "^wall" $W/r/s360-still-k$k.log
done
# Accuracy against the path tracer (references from .gpu/cache where their keys match).
TAIL=16 step acc-layouts 90 $V bench --accuracy --given-only --layouts --clipmaps 2x64,4x64 --perspective-ratios 0.25 --spp 512 --res 128 --out $W/acc/lay $SP assets/scenes/sponza-arcade.toml assets/scenes/sponza-end.toml
TAIL=6 step acc-cornell 60 $V bench --accuracy --out $W/acc/corn
# The voxelizer sweep and the stability regimes.
TAIL=8 step bench 150 $V bench $SP --out $W/bench/main
TAIL=8 step stability 120 $V bench --stability --out $W/bench/stability
# The stamp the report's GPU section shows (vct::bench::report::Stamp).
gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader | head -n1)
drv=$(nvidia-smi --query-gpu=driver_version --format=csv,noheader | head -n1)
printf '{"date": "%s", "commit": "%s", "device": "%s", "driver": "NVIDIA %s", "cpu": "%s", "cores": %d, "command": "scripts/device-bench.sh", "suite": "device-bench", "seconds": %d}\n' \
  "$(date -u '+%F %R')" "${COMMIT:-unknown}" "$gpu" "$drv" "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)" \
  "$(nproc)" "$(( $(date +%s) - T0 ))" >$W/stamp.json
cd "$(dirname $W)" && tar czf $OUT/w.tgz --exclude=cache --exclude='*.exr' --exclude='flip-*' \
  --exclude='indirect-*' --exclude='*.svg' --exclude='r/*.png' "$(basename $W)"
tar czf $OUT/img.tgz "$(basename $W)"/r/{cornell,s1080-resident,s360-s1,s360-persp}.png; ls -la $OUT
