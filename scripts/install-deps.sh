#!/usr/bin/env bash
# Installs the system packages vct needs for building, rendering and testing on Debian 12 or
# Ubuntu 22.04+, skipping those already present (through sudo when not root), and prepares the
# distribution's shaderc for the build (scripts/shaderc-system.sh). Only where that shaderc is
# missing or does not link does it install what building glslang from source takes (cmake,
# ninja, git, python3).
set -euo pipefail
scripts_dir="$(cd "$(dirname "$0")" && pwd)"

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
updated=""
# install [--optional] PACKAGE...: installs those not yet installed; an optional set that the
# distribution lacks is reported, not fatal.
install() {
    local optional=""
    [ "$1" = --optional ] && { optional=1; shift; }
    local missing=() p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
    done
    ((${#missing[@]})) || return 0
    echo "installing: ${missing[*]}"
    [ -n "$updated" ] || { $sudo apt-get update -qq; updated=1; }
    if ! DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; then
        [ -n "$optional" ] || return 1
        echo "not available here: ${missing[*]}"
    fi
}

install libvulkan1 mesa-vulkan-drivers vulkan-validationlayers xvfb xauth g++ \
    libxkbcommon-x11-0 libx11-xcb1 fonts-dejavu-core
install --optional libshaderc-dev glslang-dev spirv-tools

if ! command -v cargo >/dev/null 2>&1; then
    if [ -x "$HOME/.cargo/bin/cargo" ]; then
        echo "cargo is in ~/.cargo/bin; add it to PATH (source ~/.cargo/env)" >&2
    else
        echo "Rust is not installed. Install it with rustup (https://rustup.rs), then re-run." >&2
    fi
    exit 1
fi

# The distribution's shaderc, glslang and SPIRV-Tools, merged into one archive for the
# `shaderc` crate (found through .cargo/config.toml); without it the crate builds glslang from
# source, which needs these.
"$scripts_dir/shaderc-system.sh" "$scripts_dir/../.cache/shaderc"
[ -f "$scripts_dir/../.cache/shaderc/libshaderc_combined.a" ] || install cmake ninja-build git python3
