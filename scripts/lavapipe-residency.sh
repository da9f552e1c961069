#!/usr/bin/env bash
# Runs the tests of resident voxel storage (Vulkan sparse residency), and the bench smoke run
# whose default storage it becomes, on a lavapipe that offers it: Mesa 25 from Debian 12's
# backports, unpacked into the build cache beside the system's Mesa 22.3 (which has no sparse
# residency) and chosen with VK_DRIVER_FILES for this run only.
# Debian 12 only (elsewhere it says so and stops); the apt source is the system's own Debian
# mirror with the backports suite. Usage: scripts/lavapipe-residency.sh [cargo test args...]
set -euo pipefail
cd "$(dirname "$0")/.."
. /etc/os-release
if [ "${VERSION_CODENAME:-}" != bookworm ]; then
    echo "lavapipe-residency: Debian 12 backports only (this is ${PRETTY_NAME:-unknown}); not run"
    exit 0
fi
cache="${CARGO_TARGET_DIR:-$HOME/.cache/vct/target}/../mesa-backports"
root="$cache/root"
lib="$root/usr/lib/x86_64-linux-gnu"
if [ ! -f "$lib/libvulkan_lvp.so" ]; then
    uri=$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | grep -v security | head -n1)
    [ -n "$uri" ] || uri=$(awk '$1 == "deb" && $3 == "bookworm" {print $2; exit}' /etc/apt/sources.list 2>/dev/null)
    [ -n "$uri" ] || { echo "lavapipe-residency: no Debian mirror in the apt sources" >&2; exit 1; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    mkdir -p "$work/lists/partial" "$work/cache/archives/partial"
    printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
        "$uri" >"$work/backports.sources"
    apt=(-o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache" -o "Dir::Etc::SourceList=/dev/null"
         -o "Dir::Etc::SourceParts=$work" -o "Debug::NoLocking=1" -o "APT::Sandbox::User=root")
    apt-get "${apt[@]}" update -qq
    (cd "$work" && apt-get "${apt[@]}" download -qq \
        mesa-vulkan-drivers/bookworm-backports libdrm2/bookworm-backports libdrm-amdgpu1/bookworm-backports)
    rm -rf "$root" && mkdir -p "$root"
    for deb in "$work"/*.deb; do dpkg -x "$deb" "$root"; done
fi
icd="$cache/lvp_icd.json"
printf '{"file_format_version": "1.0.0", "ICD": {"library_path": "%s", "api_version": "1.3.0"}}\n' \
    "$lib/libvulkan_lvp.so" >"$icd"
export VK_DRIVER_FILES="$icd" VK_ICD_FILENAMES="$icd" LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}" MESA_SHADER_CACHE_DISABLE=true VCT_VALIDATION=1
devices=$(cargo run --quiet --bin vct -- devices)
grep -i -e "llvmpipe" -e "residen" -e "sparse" <<<"$devices"
# The tests skip themselves on a device without residency: make sure this one has it.
grep -q '\[x\] sparseBinding + sparseResidencyImage3D' <<<"$devices" ||
    { echo "lavapipe-residency: the backports lavapipe offers no sparse residency" >&2; exit 1; }
cargo test --no-fail-fast --test resident_storage --test bench "$@"
