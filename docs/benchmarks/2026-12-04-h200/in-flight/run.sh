#!/bin/bash
# Third device run: frames in flight (vct render --in-flight K), wall clock against GPU time.
R=$PWD; W=/tmp/w; mkdir -p $W/r
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
f=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json; [ -e $f ] && export VK_DRIVER_FILES=$f
[ -e ../shared/scenes/sponza/sponza.obj ] || ln -sfn "$R/.gpu/shared" ../shared
export XDG_RUNTIME_DIR=/tmp; V=$R/.gpu/vct; SP=assets/scenes/sponza.toml
run() { # name args...: each waited for, 1 and 2 in flight, twice, alternating
  local n=$1; shift
  for rep in 1 2; do for k in 0 1 2; do
    local a=""; [ $k -gt 0 ] && a="--in-flight $k"
    timeout 60 $V render "$@" $a --timings $W/r/$n-k$k-r$rep.json --out $W/r/x.png > $W/r/$n-k$k-r$rep.log 2>&1
    echo "$n k=$k rep=$rep rc=$? $(grep -E '^wall' $W/r/$n-k$k-r$rep.log) GPU $(grep -E '^total ' $W/r/$n-k$k-r$rep.log | head -1)"
  done; done
}
run c720-still --width 1280 --height 720 --res 64 --gi-scale 4 --gi-accumulate on --reuse-volume on --frames 300
run c720-rebuild --width 1280 --height 720 --res 64 --gi-scale 4 --gi-accumulate on --frames 300
run s360-still $SP --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on --reuse-volume on --frames 300
run s360-rebuild $SP --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on --frames 300
run s720-128-s1 $SP --width 1280 --height 720 --res 128 --frames 200
VCT_VALIDATION=sync VK_LAYER_ENABLES=VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT timeout 60 $V render $SP --width 640 --height 360 --res 64 --gi-scale 4 --gi-accumulate on --frames 20 --in-flight 2 --out $W/r/x.png > $W/r/sync.log 2>&1; echo "sync validation, 2 in flight: rc=$?"; tail -2 $W/r/sync.log
cd $(dirname $W) && tar czf $OUT/w3.tgz --exclude='*.png' $(basename $W); ls -la $OUT
