#!/bin/bash
# Prepares a run of `scripts/device-bench.sh` on a lent GPU machine (the `device` tool of the
# tool library, ../.library/device/README.md): a stripped release build of `vct`, Sponza from
# ../shared, the chart font, cached path-traced references (give their folders as arguments),
# and the Vulkan loader and validation layer as Debian packages. Everything lands in the
# git-ignored folders .gpu/ and .gl/ (listed in .git/info/exclude), which the run carries:
#   run(command="bash scripts/device-bench.sh 2>&1 | tee $OUT/log.txt", carry=[".gl", ".gpu"])
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$HOME/.cache/vct/target}
cargo build --release --bin vct
grep -qx '/.gpu/' .git/info/exclude || echo /.gpu/ >>.git/info/exclude
grep -qx '/.gl/' .git/info/exclude || echo /.gl/ >>.git/info/exclude
mkdir -p .gpu/shared/scenes .gpu/cache .gpu/fonts .gl /tmp/amd64/partial
strip -o .gpu/vct "$CARGO_TARGET_DIR/release/vct"
cp -r ../shared/scenes/sponza .gpu/shared/scenes/
cp /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf .gpu/fonts/
for d in "$@"; do cp "$d"/reference-* .gpu/cache/; done
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
apt-get $o update >/dev/null
# The NVIDIA ICD (libGLX_nvidia) needs the GL vendor-neutral dispatch libraries beside the loader.
(cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 vulkan-validationlayers)
du -sh .gpu .gl
