#!/bin/bash
# One prepared device run: smoke + validation, frame timings, accuracy with warp, the main bench.
# Every step is bounded; results are tarred into $OUT at the end.
R=$PWD
W=/tmp/w; mkdir -p $W/r $W/acc
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
f=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -e $f ] && export VK_DRIVER_FILES=$f
[ -e ../shared/scenes/sponza/sponza.obj ] || ln -sfn "$R/.gpu/shared" ../shared
cp .gpu/cache/* $W/acc/ 2>/dev/null; mkdir -p $W/acc/cache && mv $W/acc/reference-* $W/acc/cache/
export XDG_RUNTIME_DIR=/tmp
mkdir -p /usr/share/fonts/truetype/dejavu && cp -n .gpu/fonts/DejaVuSans.ttf /usr/share/fonts/truetype/dejavu/
V=$R/.gpu/vct
log() { echo "=== $(date +%T) $*"; }
nvidia-smi -L; nvidia-smi --query-gpu=driver_version,clocks.sm,clocks.max.sm --format=csv
T0=$(date +%s); B=${BUDGET:-330}
step() { # name timeout cmd...  (never past T0 + B - 15 s, so the tar below always runs)
  local n=$1 t=$2; shift 2; local left=$((T0 + B - 15 - $(date +%s)))
  [ $left -lt $t ] && t=$left; [ $t -lt 5 ] && { log "$n: skipped, no time"; return; }
  log "$n (limit $t s): $*"; local s=$(date +%s%N)
  timeout $t "$@" >$W/r/$n.log 2>&1; local rc=$?
  echo "rc=$rc $(( ($(date +%s%N) - s) / 1000000 )) ms"; tail -n ${TAIL:-4} $W/r/$n.log
}
TAIL=30 step smoke 40 env VCT_VALIDATION=1 $V render --out $W/r/cornell.png --timings $W/r/cornell.json
TAIL=6 step sync 40 env VCT_VALIDATION=sync $V render --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on --reuse-volume on --frames 6 --out $W/r/sync.png
TAIL=6 step sponza-val 40 env VCT_VALIDATION=1 $V render assets/scenes/sponza.toml --frames 2 --out $W/r/sponza.png
# Issue 17's frame-time table, on the GPU (median of 16 frames)
F="--frames 16"
C="--width 1280 --height 720 --res 64"
S="assets/scenes/sponza.toml --width 640 --height 360 --res 64"
step c720-s1 20 $V render $C --gi-scale 1 $F --timings $W/r/c720-s1.json --out $W/r/c720-s1.png
step c720-s4-acc-still 20 $V render $C --gi-scale 4 --gi-accumulate on --reuse-volume on $F --timings $W/r/c720-s4-still.json --out $W/r/c720-s4.png
step c720-s4-acc-rebuild 20 $V render $C --gi-scale 4 --gi-accumulate on $F --timings $W/r/c720-s4-rebuild.json --out $W/r/c720-s4r.png
step s360-s1 20 $V render $S --gi-scale 1 $F --timings $W/r/s360-s1.json --out $W/r/s360-s1.png
step s360-s4-acc-still 20 $V render $S --gi-scale 4 --gi-accumulate on --reuse-volume on $F --timings $W/r/s360-s4-still.json --out $W/r/s360-s4.png
step s360-s4-acc-rebuild 20 $V render $S --gi-scale 4 --gi-accumulate on $F --timings $W/r/s360-s4-rebuild.json --out $W/r/s360-s4r.png
# A GPU-sized frame: Sponza 1920x1080 at 256, each storage
for st in dense sparse resident; do
  step s1080-256-$st 30 $V render assets/scenes/sponza.toml --width 1920 --height 1080 --res 256 --storage $st $F --timings $W/r/s1080-256-$st.json --out $W/r/s1080-$st.png
done
step s1080-256-s1-reuse 30 $V render assets/scenes/sponza.toml --width 1920 --height 1080 --res 256 --reuse-volume on $F --timings $W/r/s1080-256-reuse.json --out $W/r/s1080-reuse.png
# Accuracy: three Sponza views, fitted and warped, 64 and 128 (references cached, 512 spp)
TAIL=24 step acc-layouts 90 $V bench --accuracy --given-only --layouts --spp 512 --res 64,128 --out $W/acc/lay assets/scenes/sponza.toml assets/scenes/sponza-arcade.toml assets/scenes/sponza-end.toml
TAIL=8 step acc-cornell 60 $V bench --accuracy --out $W/acc/corn
# The speed/accuracy sweep (voxelizers x resolutions x storage), Cornell and Sponza
TAIL=12 step bench 150 $V bench assets/scenes/sponza.toml --out $W/bench/main
TAIL=12 step stability 120 $V bench --stability --out $W/bench/stability
log done
cd $(dirname $W) && tar czf $OUT/w.tgz --exclude=cache --exclude='*.exr' --exclude='flip-*' --exclude='indirect-*' --exclude='r/*.png' $(basename $W)
tar czf $OUT/img.tgz $(basename $W)/r/{cornell,sponza,s1080-dense,s1080-resident,s360-s4}.png; ls -la $OUT
