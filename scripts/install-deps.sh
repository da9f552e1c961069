#!/usr/bin/env bash
# Installs the system packages vct needs for building, rendering and testing on Debian 12 or
# Ubuntu 22.04+, skipping those already present. Uses sudo when not run as root.
set -euo pipefail

packages=(libvulkan1 mesa-vulkan-drivers vulkan-validationlayers xvfb xauth cmake ninja-build python3 g++ git
          libxkbcommon-x11-0 libx11-xcb1 fonts-dejavu-core)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    echo "installing: ${missing[*]}"
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1; then
    if [ -x "$HOME/.cargo/bin/cargo" ]; then
        echo "cargo is in ~/.cargo/bin; add it to PATH (source ~/.cargo/env)" >&2
    else
        echo "Rust is not installed. Install it with rustup (https://rustup.rs), then re-run." >&2
    fi
    exit 1
fi
