#!/usr/bin/env bash
# Runs the cargo-fuzz target over scene-file parsing and OBJ -> scene conversion for a bounded
# time (seconds, default 60), starting from the committed corpus. Installs cargo-fuzz when it is
# missing. The target is built on the stable toolchain without a sanitizer (`-s none`): the code
# under test is safe Rust, and libFuzzer's coverage guidance still finds panics, hangs, aborts
# and runaway allocations.
# A crash fails the script and leaves the reproducer under fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzzer: installing cargo-fuzz"
    cargo install --locked --quiet cargo-fuzz
fi
target_dir="${VCT_FUZZ_TARGET_DIR:-$HOME/.cache/vct/fuzz-target}"
corpus="$(mktemp -d)"
trap 'rm -rf "$corpus" "$corpus.log"' EXIT
cp fuzz/corpus/scene_input/* "$corpus/"
cd fuzz
log="$corpus.log"
CARGO_TARGET_DIR="$target_dir" cargo fuzz build -s none scene_input
if ! CARGO_TARGET_DIR="$target_dir" cargo fuzz run -s none scene_input "$corpus" -- \
    -max_total_time="$seconds" -rss_limit_mb=4096 -timeout=10 >"$log" 2>&1; then
    grep -m1 -A3 "panicked" "$log" || true
    tail -n 30 "$log"
    echo "fuzzer: scene_input crashed; the reproducer is under fuzz/artifacts/scene_input/" >&2
    exit 1
fi
tail -n 3 "$log"
echo "fuzzer: scene_input ran ${seconds} s without a crash"
