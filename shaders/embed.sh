#!/bin/sh
# shaders/embed.sh - compile every compute shader of shaders/ to SPIR-V,
# strip it and remove its dead code (spirv-opt), and embed the modules in
# manylods_vk.h between its GENERATED markers, packed by shaders/pack.c
# (LEB128 words, LZ77, base64: mlodvk__unpack reads them back); and copy
# shaders/interface.h between its INTERFACE markers (what `make shaders`
# runs).  Usage: shaders/embed.sh [header] (default manylods_vk.h,
# rewritten in place).  GLSLANG overrides the compiler, CC the C compiler
# that builds pack.c; SPV_OUT, when set, is a directory that receives the
# modules as embedded (NAME.spv).  The pinned compiler is Debian 12's
# glslang-tools with its spirv-tools (the versions are recorded in the
# block, and tests/check_shaders.sh compares them).
set -eu
GLSLANG=${GLSLANG:-glslangValidator}
header=${1:-manylods_vk.h}
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
${CC:-cc} -O2 -std=c99 -o "$tmp/pack" shaders/pack.c
# size, not speed: -O and -Os inline the double emulation into every caller
# (20 times the words); the driver optimises anyway
OPT="--eliminate-dead-functions --eliminate-dead-code-aggressive --compact-ids --strip-debug --strip-nonsemantic"
modules=
{
    echo "/* BEGIN GENERATED SPIR-V (make shaders) */"
    echo "/* compiler: $($GLSLANG --version | head -n 1) */"
    echo "/* optimiser: $(spirv-opt --version 2>&1 | head -n 1) */"
    echo "/* each module: glslangValidator -V --target-env vulkan1.1 [-DMLOD_F64_EMULATED] -Ishaders NAME.comp,"
    echo "   then spirv-opt $OPT */"
    # each shader as it is (the device's doubles where it computes in
    # double), and those that include common.glsl a second time with
    # -DMLOD_F64_EMULATED (doubles from 32-bit integers: real.glsl), as
    # module NAME_EMULATED
    for name in cut_init cut_step cut_step_basic cut_exact cut_scan cut_write cut_finish splat_clear splat_draw splat_resolve refit_check refit_leaves refit_merge mv_pairs mv_slots mv_inherit mv_draw mv_resolve; do
        src=shaders/$name.comp
        variants="-"
        # (directly, or through mv_layout.glsl or cut_step.glsl)
        if grep -q '#include "common.glsl"\|#include "mv_layout.glsl"\|#include "cut_step.glsl"' "$src"; then variants="- emulated"; fi
        for variant in $variants; do
            if [ "$variant" = - ]; then flags= spv=$name; else flags=-DMLOD_F64_EMULATED spv=${name}_emulated; fi
            $GLSLANG -V --target-env vulkan1.1 $flags -Ishaders "$src" -o "$tmp/$spv.full.spv" >"$tmp/log" || { cat "$tmp/log" >&2; exit 1; }
            spirv-opt $OPT "$tmp/$spv.full.spv" -o "$tmp/$spv.spv"
            spirv-val --target-env vulkan1.1 "$tmp/$spv.spv"
            modules="$modules $(echo "$spv" | tr a-z A-Z)=$tmp/$spv.spv"
            if [ -n "${SPV_OUT:-}" ]; then cp "$tmp/$spv.spv" "$SPV_OUT/$spv.spv"; fi
        done
    done
    "$tmp/pack" $modules
    echo "/* END GENERATED SPIR-V */"
} >"$tmp/block"
{
    echo "/* BEGIN INTERFACE (shaders/interface.h, make shaders) */"
    cat shaders/interface.h
    echo "/* END INTERFACE */"
} >"$tmp/interface"
awk -v block="$tmp/block" -v interface="$tmp/interface" '
    /^\/\* BEGIN GENERATED SPIR-V/ { while ((getline line < block) > 0) print line; skip = 1; next }
    /^\/\* END GENERATED SPIR-V/ { skip = 0; next }
    /^\/\* BEGIN INTERFACE/ { while ((getline line < interface) > 0) print line; skip = 1; next }
    /^\/\* END INTERFACE/ { skip = 0; next }
    !skip { print }
' "$header" >"$tmp/header"
if ! grep -q "BEGIN GENERATED SPIR-V" "$tmp/header"; then echo "embed.sh: no GENERATED markers in $header" >&2; exit 1; fi
if ! grep -q "BEGIN INTERFACE" "$tmp/header"; then echo "embed.sh: no INTERFACE markers in $header" >&2; exit 1; fi
cat "$tmp/header" >"$header"
