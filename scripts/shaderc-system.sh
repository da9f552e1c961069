#!/usr/bin/env bash
# Prepares the distribution's shaderc for the `shaderc` crate, so that `build.rs` links it instead
# of building glslang from source (about 10 minutes on 2 cores, against seconds).
#
# Debian's and Ubuntu's `libshaderc_combined.a` (libshaderc-dev) leaves glslang's and
# SPIRV-Tools' symbols undefined, so this merges it with their static libraries (glslang-dev,
# spirv-tools) into one archive in "$1", then proves the archive by compiling a
# tessellation-control shader with it. On success the folder holds `libshaderc_combined.a`; on
# any failure it holds nothing, and the `shaderc` crate builds from source instead.
set -uo pipefail
dest="$1"
say() { echo "shaderc: $*" >&2; }

multiarch="$(gcc -print-multiarch 2>/dev/null || true)"
libdir=""
for d in "/usr/lib/$multiarch" /usr/lib64 /usr/lib; do
    [ -n "$d" ] && [ -f "$d/libshaderc_combined.a" ] && { libdir="$d"; break; }
done
mkdir -p "$dest"
if [ -z "$libdir" ]; then
    rm -f "$dest/libshaderc_combined.a"
    say "no system libshaderc_combined.a; glslang will be built from source"
    exit 0
fi
# Prepared already, from the libraries installed now.
[ "$dest/libshaderc_combined.a" -nt "$libdir/libshaderc_combined.a" ] && exit 0
rm -f "$dest/libshaderc_combined.a"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
{
    echo "create $work/libshaderc_combined.a"
    for lib in shaderc_combined glslang MachineIndependent GenericCodeGen OSDependent OGLCompiler \
               SPIRV HLSL SPIRV-Tools-opt SPIRV-Tools; do
        [ -f "$libdir/lib$lib.a" ] && echo "addlib $libdir/lib$lib.a"
    done
    echo save
    echo end
} >"$work/merge.mri"

cat >"$work/probe.cc" <<'CC'
#include <shaderc/shaderc.h>
#include <string.h>
int main() {
    const char *src = "#version 450\nlayout(vertices = 3) out;\n"
                      "void main() { gl_TessLevelOuter[0] = 1.0; }\n";
    shaderc_compiler_t c = shaderc_compiler_initialize();
    shaderc_compilation_result_t r = shaderc_compile_into_spv(
        c, src, strlen(src), shaderc_tess_control_shader, "probe.tesc", "main", 0);
    return shaderc_result_get_compilation_status(r) == shaderc_compilation_status_success &&
                   shaderc_result_get_length(r) > 20 ? 0 : 1;
}
CC
if ar -M <"$work/merge.mri" 2>"$work/log" &&
    g++ "$work/probe.cc" -o "$work/probe" -L"$work" -lshaderc_combined -lpthread 2>>"$work/log" &&
    "$work/probe" 2>>"$work/log"; then
    mv "$work/libshaderc_combined.a" "$dest/"
    say "linking the system's shaderc, glslang and SPIRV-Tools from $libdir"
else
    say "the system's shaderc in $libdir does not link ($(head -c 300 "$work/log" | tr '\n' ' '));" \
        "glslang will be built from source"
fi
