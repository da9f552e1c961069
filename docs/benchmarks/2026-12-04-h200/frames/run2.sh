#!/bin/bash
# Second device run: the new default coverage (auto -> hw on NVIDIA) checked and timed.
R=$PWD; W=/tmp/w; mkdir -p $W/r
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
f=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json; [ -e $f ] && export VK_DRIVER_FILES=$f
[ -e ../shared/scenes/sponza/sponza.obj ] || ln -sfn "$R/.gpu/shared" ../shared
export XDG_RUNTIME_DIR=/tmp; V=$R/.gpu/vct
T0=$(date +%s); B=${BUDGET:-150}
step() { local n=$1 t=$2; shift 2; local left=$((T0 + B - 10 - $(date +%s)))
  [ $left -lt $t ] && t=$left; [ $t -lt 5 ] && { echo "=== $n: skipped"; return; }
  echo "=== $n: $*"; local s=$(date +%s%N); timeout $t "$@" >$W/r/$n.log 2>&1; local rc=$?
  echo "rc=$rc $(( ($(date +%s%N) - s) / 1000000 )) ms"; grep -E "${G:-^(total|voxelize|method|recall|  recall|grid|error)}" $W/r/$n.log | head -${H:-8}; }
SP=assets/scenes/sponza.toml
G='method|recall|precision|IoU|error|voxelize' H=12 step vox-sponza-128 30 env VCT_VALIDATION=1 $V voxelize $SP --res 128
G='method|recall|precision|IoU|error|voxelize' H=12 step vox-sponza-256 30 $V voxelize $SP --res 256
G='method|recall|precision|IoU|error|voxelize' H=12 step vox-sponza-128-warp 30 $V voxelize $SP --res 128 --warp function
G='method|recall|precision|IoU|error|voxelize' H=12 step vox-cornell-64-warp 30 $V voxelize --res 64 --warp function
G='method|recall|precision|IoU|error|voxelize' H=12 step vox-cornell-128-warp-cons 30 $V voxelize --res 128 --warp function --coverage conservative
F="--frames 16"
step s360-s1 20 env VCT_VALIDATION=1 $V render $SP --width 640 --height 360 --res 64 $F --timings $W/r/s360-s1.json --out $W/r/s360-s1.png
step s360-s4-still 20 $V render $SP --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on --reuse-volume on $F --timings $W/r/s360-s4-still.json --out $W/r/a.png
step s360-s4-rebuild 20 $V render $SP --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on $F --timings $W/r/s360-s4-rebuild.json --out $W/r/b.png
step c720-s4-rebuild 20 $V render --width 1280 --height 720 --res 64 --gi-scale 4 --gi-accumulate on $F --timings $W/r/c720-s4-rebuild.json --out $W/r/c.png
step s1080-256 30 $V render $SP --width 1920 --height 1080 --res 256 $F --timings $W/r/s1080-256.json --out $W/r/s1080.png
step s1080-256-sparse 30 $V render $SP --width 1920 --height 1080 --res 256 --storage sparse $F --timings $W/r/s1080-256-sparse.json --out $W/r/d.png
# Where the warped frame's time goes (fitted against warped, same grid, 640x360)
step s360-128-fitted 20 $V render $SP --res 128 $F --timings $W/r/s360-128-fitted.json --out $W/r/e.png
step s360-128-warp 20 $V render $SP --res 128 --warp function $F --timings $W/r/s360-128-warp.json --out $W/r/f.png
step s360-128-warp-cons 20 $V render $SP --res 128 --warp function --coverage conservative $F --timings $W/r/s360-128-warp-cons.json --out $W/r/g.png
step s360-128-warp-dense 20 $V render $SP --res 128 --warp function --storage dense $F --timings $W/r/s360-128-warp-dense.json --out $W/r/h.png
step s360-128-fitted-dense 20 $V render $SP --res 128 --storage dense $F --timings $W/r/s360-128-fitted-dense.json --out $W/r/i.png
cd $(dirname $W) && tar czf $OUT/w2.tgz --exclude='*.png' $(basename $W); ls -la $OUT
