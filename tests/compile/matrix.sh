#!/usr/bin/env bash
# tests/compile/matrix.sh - the compile matrix: manylods.h built the ways its
# users build it, every entry with -Wall -Wextra -pedantic -Werror, linked and
# run.  Each entry that builds and runs is one passed check; the script ends
# with the plain line "N passed, M failed" (tests/run.sh adds it to the rest)
# and exits 1 when an entry failed.
#
#   tests/compile/matrix.sh [NAME-GLOB...]    run every entry, or those named
#
# Entries run MATRIX_JOBS at a time (default: the number of processors) and
# are reported in order once all have run.
#
# Environment: CC, CXX (default gcc, g++), CLANG, CLANGXX (default clang,
# clang++), MATRIX_OUT (default build/matrix), MATRIX_JOBS, VERBOSE=1 to log
# every step.
set -u
cd "$(dirname "$0")/../.." || exit 1

CC=${CC:-gcc}
CXX=${CXX:-g++}
CLANG=${CLANG:-clang}
CLANGXX=${CLANGXX:-clang++}
OUT=${MATRIX_OUT:-build/matrix}
STRICT="-Wall -Wextra -pedantic -Werror -O2"
# The entries about linkage, names and configuration (two TUs, symbols,
# MANYLODS_STATIC, threads, unity builds, macros, MANYLODS_DEF, the README's
# example) build at -O1, which keeps GCC's flow-based warnings at half -O2's
# compile time; the language, floating-point and vector-lane entries at -O2
# and above.
LINKAGE="-Wall -Wextra -pedantic -Werror -O1"
LIBS="-lm -pthread"
SRC=tests/compile
mkdir -p "$OUT" || exit 1

jobs_max=${MATRIX_JOBS:-$(nproc 2>/dev/null || echo 1)}
[ "$jobs_max" -ge 1 ] 2>/dev/null || jobs_max=1
passed=0
failed=0
names=()  # the entries started, in order
titles=()

# steps CMD...: run each command string in turn, echoing it; stop at the
# first that fails.
steps() {
    local command
    for command in "$@"; do
        echo "+ $command"
        eval "$command" || return 1
    done
}

# entry NAME TITLE CMD...: one check of the matrix, started in the
# background ($OUT/NAME.log, then $OUT/NAME.status: 0 or 1 and the seconds
# it took); report shows it.
entry() {
    local name=$1 title=$2 pattern selected=1
    shift 2
    if [ ${#patterns[@]} -gt 0 ]; then
        selected=0
        for pattern in "${patterns[@]}"; do
            # shellcheck disable=SC2053
            [[ $name == $pattern ]] && selected=1
        done
    fi
    [ "$selected" = 1 ] || return 0
    while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n 2>/dev/null || sleep 0.2; done
    rm -f "$OUT/$name.status"
    names+=("$name")
    titles+=("$title")
    (
        entry_name=$name
        start=$SECONDS
        if steps "$@" >"$OUT/$name.log" 2>&1; then code=0; else code=1; fi
        echo "$code $((SECONDS - start))" >"$OUT/$name.status"
    ) &
    return 0
}

# report: wait for every entry, then print each in order and count them.
report() {
    local i name code took
    wait
    for i in "${!names[@]}"; do
        name=${names[i]}
        code=1
        took=?
        [ -r "$OUT/$name.status" ] && read -r code took <"$OUT/$name.status"
        if [ "$code" = 0 ]; then
            passed=$((passed + 1))
            printf '  ok    %-24s %4s s  %s\n' "$name" "$took" "${titles[i]}"
            [ "${VERBOSE:-0}" = 1 ] && sed 's/^/      | /' "$OUT/$name.log"
        else
            failed=$((failed + 1))
            printf '  FAIL  %-24s %4s s  %s\n' "$name" "$took" "${titles[i]}"
            tail -n 40 "$OUT/$name.log" | sed 's/^/      | /'
        fi
    done
}

# Macros that a translation unit defines beyond those of the system headers
# that manylods.h includes, other than MANYLODS_*, MLOD_* and reserved names.
# Prints them and fails when there are any.
new_macros() { # compiler, file with the translation unit
    local cc=$1 tu=$2 base="$2.base.c"
    $cc -std=c99 -H -fsyntax-only "$tu" 2>&1 >/dev/null | sed -n 's/^\.\. //p' | awk '!seen[$0]++' |
        sed 's/.*/#include "&"/' >"$base" || return 1
    $cc -std=c99 -E -dM "$base" | sort >"$base.macros" || return 1
    $cc -std=c99 -E -dM "$tu" | sort >"$tu.macros" || return 1
    comm -13 "$base.macros" "$tu.macros" | awk '{ sub(/\(.*/, "", $2); print $2 }' |
        grep -Ev '^(MANYLODS_|MLOD_|_)' >"$tu.leaked"
    if [ -s "$tu.leaked" ]; then
        echo "macros defined by manylods.h without the MANYLODS_ or MLOD_ prefix:"
        cat "$tu.leaked"
        return 1
    fi
    echo "no unprefixed macro"
}

# Global symbols an object defines that are not public mlod_ names.
foreign_symbols() { # object, allowed extra names (regex)
    local extra=${2:-^$}
    nm -g --defined-only "$1" | awk '{ print $3 }' | grep -Ev '^mlod_[a-z]' | grep -Ev "$extra" >"$1.foreign"
    if [ -s "$1.foreign" ]; then
        echo "global symbols outside the mlod_ namespace (or private mlod__ ones):"
        cat "$1.foreign"
        return 1
    fi
    if nm -g --defined-only "$1" | awk '{ print $3 }' | grep -q '^mlod__'; then
        echo "private mlod__ symbols with external linkage:"
        nm -g --defined-only "$1" | awk '{ print $3 }' | grep '^mlod__'
        return 1
    fi
    echo "exports only public mlod_ names"
}

# Fused multiply-adds in an object's x86-64 code (vfmadd..., vfnmsub...).
fma_count() { # object
    objdump -d "$1" | grep -Ec '\svfn?m(add|sub)[0-9a-z]*\s'
}

# The implementation compiled where the compiler would fuse a * b + c
# (GNU C mode, FMA target) has no fused multiply-add, while a plain a * b + c
# in the same mode has one (so that the check can see them at all).
no_fused_multiply_add() { # compiler
    local cc=$1 tag
    tag=$(basename "$cc")
    printf 'double fma_probe(double a, double b, double c) { return a * b + c; }\n' >"$OUT/fma_probe-$tag.c"
    $cc -std=gnu11 -O2 -mfma -c "$OUT/fma_probe-$tag.c" -o "$OUT/fma_probe-$tag.o" || return 1
    if [ "$(fma_count "$OUT/fma_probe-$tag.o")" = 0 ]; then
        echo "$cc -std=gnu11 -mfma did not fuse a * b + c: the check would see nothing"
        return 1
    fi
    $cc -std=gnu11 $STRICT -mfma -DMANYLODS_PTHREADS -c $SRC/tu_impl.c -o "$OUT/tu_impl-fma-$tag.o" || return 1
    if [ "$(fma_count "$OUT/tu_impl-fma-$tag.o")" != 0 ]; then
        echo "fused multiply-adds in the implementation ($cc -std=gnu11 -mfma):"
        objdump -d "$OUT/tu_impl-fma-$tag.o" | grep -E '\svfn?m(add|sub)[0-9a-z]*\s' | head
        return 1
    fi
    echo "a * b + c fused in the probe, never in the implementation"
}

# Interrupted (^C on `make matrix`, or a SIGTERM or SIGHUP): stop the
# entries running, and what they run.  They are background jobs, which
# ignore SIGINT: without this a ^C left them running after make.
descendants() { # pid: its children, theirs, ...
    local child
    for child in $(ps -o pid= --ppid "$1" 2>/dev/null); do
        echo "$child"
        descendants "$child"
    done
}
stop_entries() {
    local job pids=()
    trap - INT TERM HUP
    for job in $(jobs -p); do pids+=("$job" $(descendants "$job")); done
    [ ${#pids[@]} = 0 ] || kill -TERM "${pids[@]}" 2>/dev/null
}
trap 'stop_entries; exit 130' INT
trap 'stop_entries; exit 143' TERM
trap 'stop_entries; exit 129' HUP

patterns=("$@")

echo "compile matrix (build/matrix; each entry: -Wall -Wextra -pedantic -Werror, link, run)"

# One translation unit with the implementation, as C and as C++.
entry c99-gcc "C99, $CC" \
    "$CC -std=c99 $STRICT $SRC/impl.c -o $OUT/c99-gcc $LIBS" "$OUT/c99-gcc"
entry c99-clang "C99, $CLANG" \
    "$CLANG -std=c99 $STRICT $SRC/impl.c -o $OUT/c99-clang $LIBS" "$OUT/c99-clang"
for std in c++11 c++17; do
    entry "$std-gxx" "C++ ($std), $CXX, after <algorithm> <cmath> <limits> <vector>" \
        "$CXX -std=$std $STRICT $SRC/impl.cpp -o $OUT/$std-gxx $LIBS" "$OUT/$std-gxx"
    entry "$std-clangxx" "C++ ($std), $CLANGXX, after <algorithm> <cmath> <limits> <vector>" \
        "$CLANGXX -std=$std $STRICT $SRC/impl.cpp -o $OUT/$std-clangxx $LIBS" "$OUT/$std-clangxx"
done

# Two translation units: the implementation in one, a user in the other,
# across the C / C++ boundary both ways.
# The C objects of $CC serve both ways across the boundary (each compiled once).
entry two-tu-gcc "two TUs (implementation + user): C99 $CC + C99 $CC, C $CC + C++11 $CXX, C++11 $CXX + C $CC" \
    "$CC -std=c99 $LINKAGE -c $SRC/tu_impl.c -o $OUT/tu_impl.o" \
    "$CC -std=c99 $LINKAGE -c $SRC/tu_user.c -o $OUT/tu_user.o" \
    "$CC $OUT/tu_impl.o $OUT/tu_user.o -o $OUT/two-tu-gcc $LIBS" "$OUT/two-tu-gcc" \
    "$CXX -std=c++11 $LINKAGE -x c++ -c $SRC/tu_user.c -o $OUT/tu_user-cxx.o" \
    "$CXX $OUT/tu_impl.o $OUT/tu_user-cxx.o -o $OUT/two-tu-c-impl-cxx-user $LIBS" "$OUT/two-tu-c-impl-cxx-user" \
    "$CXX -std=c++11 $LINKAGE -x c++ -c $SRC/tu_impl.c -o $OUT/tu_impl-cxx.o" \
    "$CXX $OUT/tu_impl-cxx.o $OUT/tu_user.o -o $OUT/two-tu-cxx-impl-c-user $LIBS" "$OUT/two-tu-cxx-impl-c-user"
entry two-tu-clang "two TUs (implementation + user), C99, $CLANG" \
    "$CLANG -std=c99 $LINKAGE -c $SRC/tu_impl.c -o $OUT/tu_impl-clang.o" \
    "$CLANG -std=c99 $LINKAGE -c $SRC/tu_user.c -o $OUT/tu_user-clang.o" \
    "$CLANG $OUT/tu_impl-clang.o $OUT/tu_user-clang.o -o $OUT/two-tu-clang $LIBS" "$OUT/two-tu-clang"
entry exported-symbols "the implementation exports only mlod_ names ($CC, with MANYLODS_PTHREADS)" \
    "$CC -std=c99 $LINKAGE -DMANYLODS_PTHREADS -c $SRC/tu_impl.c -o $OUT/tu_impl-pthreads.o" \
    "foreign_symbols $OUT/tu_impl-pthreads.o"

# Rounding as written: no fused multiply-add where the compiler would fuse
# (the CPU computes the shaders' bits only so).  x86-64 only: -mfma.
if [ "$(uname -m)" = x86_64 ]; then
    for cc in "$CC" "$CLANG"; do
        entry "no-fma-$(basename "$cc")" "no fused multiply-add in the implementation, -std=gnu11 -mfma, $cc" \
            "no_fused_multiply_add $cc"
    done
fi

# Floating-point flags: every build the header accepts computes the same
# bits (tests/compile/fp_hash.c hashes trees, refits, cuts in every mode,
# splats, ISM and hole filling); the flags it cannot honour stop the build
# with a "manylods:" message.  The reference is $CC -std=c99 -O2.
fp_reference=
fp_hash_of() { # compiler, flags...: build fp_hash.c with them, print its hash
    local cc=$1 exe
    shift
    exe="$OUT/fp-$(basename "$cc")-$(printf '%s' "$*" | tr -c 'a-zA-Z0-9' '_')"
    $cc -Wall -Wextra -pedantic -Werror "$@" $SRC/fp_hash.c -o "$exe" $LIBS >&2 || return 1
    "$exe" | sed -n 's/^hash //p'
}
fp_same_hash() { # compiler, flags...
    local hash
    hash=$(fp_hash_of "$@") || return 1
    echo "hash $hash ($*)"
    [ -n "$hash" ] && [ "$hash" = "$fp_reference" ] && return 0
    echo "differs from the reference $fp_reference ($CC -std=c99 -O2)"
    return 1
}
fp_refused() { # compiler, flags...: the build fails with the header's message
    local cc=$1 log="$OUT/fp-refused-$entry_name.log"
    shift
    if $cc "$@" -c $SRC/fp_hash.c -o "$OUT/fp-refused-$entry_name.o" >"$log" 2>&1; then
        echo "$cc $* compiled the implementation: it must refuse these flags"
        return 1
    fi
    grep -m1 'manylods: compile the implementation without' "$log" || { cat "$log"; return 1; }
}
fp_reference=$(fp_hash_of "$CC" -std=c99 -O2 2>"$OUT/fp-reference.log")
[ -n "$fp_reference" ] || { echo "  FAIL  fp_hash.c does not build or run with $CC -std=c99 -O2"; cat "$OUT/fp-reference.log"; }
echo "  floating-point reference hash $fp_reference ($CC -std=c99 -O2)"
native=-march=native
for cc in "$CC" "$CLANG" "$CXX" "$CLANGXX"; do
    tag=$(basename "$cc")
    std=-std=gnu11
    case $tag in *++*) std="-x c++ -std=gnu++17" ;; esac
    # GCC contracts by default in GNU modes: there -O3 $native with and without
    # -ffp-contract=fast is one build (the same object), run once
    if $cc -dM -E -x c /dev/null 2>/dev/null | grep -q '__clang__'; then
        entry "fp-native-$tag" "same hash: $tag -O3 $native" "fp_same_hash $cc $std -O3 $native"
        entry "fp-contract-$tag" "same hash: $tag -O3 $native -ffp-contract=fast" \
            "fp_same_hash $cc $std -O3 $native -ffp-contract=fast"
    else
        entry "fp-contract-$tag" "same hash: $tag -O3 $native, -ffp-contract=fast (its default here)" \
            "fp_same_hash $cc $std -O3 $native -ffp-contract=fast"
    fi
    entry "fp-fast-math-$tag" "refused: $tag -ffast-math, -Ofast, -ffinite-math-only" \
        "fp_refused $cc $std -O2 -ffast-math" "fp_refused $cc $std -Ofast" "fp_refused $cc $std -O2 -ffinite-math-only"
done
for cc in "$CC" "$CXX"; do
    tag=$(basename "$cc")
    std=-std=gnu11
    case $tag in *++*) std="-x c++ -std=gnu++17" ;; esac
    entry "fp-unsafe-$tag" "refused: $tag -funsafe-math-optimizations and its parts (they have macros)" \
        "fp_refused $cc $std -O2 -funsafe-math-optimizations" "fp_refused $cc $std -O2 -fassociative-math -fno-signed-zeros -fno-trapping-math" \
        "fp_refused $cc $std -O2 -freciprocal-math" "fp_refused $cc $std -O2 -fno-signed-zeros"
done
for cc in "$CLANG" "$CLANGXX"; do
    tag=$(basename "$cc")
    std=-std=gnu11
    case $tag in *++*) std="-x c++ -std=gnu++17" ;; esac
    entry "fp-unsafe-$tag" "same hash: $tag -funsafe-math-optimizations and its parts (no macro: made harmless)" \
        "fp_same_hash $cc $std -O2 -funsafe-math-optimizations" \
        "fp_same_hash $cc $std -O3 $native -ffp-contract=fast -fassociative-math -freciprocal-math -fno-signed-zeros -fno-trapping-math" \
        "fp_same_hash $cc $std -O2 -fno-honor-nans"
done

# The cut's vector float filter: every path this machine runs (none, SSE2,
# AVX with -mavx2 where the processor has it, -march=native) gives the same
# bits, and test_cut (which compares the filter with the exact path) passes
# on each.
entry fp-simd-off "same hash: $CC -O2 -DMANYLODS_NO_SIMD (the scalar filter)" \
    "fp_same_hash $CC -std=c99 -O2 -DMANYLODS_NO_SIMD"
if grep -qw avx2 /proc/cpuinfo 2>/dev/null; then
    entry fp-avx2 "same hash: $CC -O2 -mavx2 (8 lanes)" "fp_same_hash $CC -std=c99 -O2 -mavx2"
fi
entry fp-no-avx2 "same hash: $CC -O2 -DMANYLODS_NO_AVX2 (SSE2 lanes, no dispatch)" \
    "fp_same_hash $CC -std=c99 -O2 -DMANYLODS_NO_AVX2"
entry fp-contract-dispatch "same hash: $CC -O3 -ffp-contract=fast, no -m flags (the lanes chosen at run time)" \
    "fp_same_hash $CC -std=gnu11 -O3 -ffp-contract=fast" "fp_same_hash $CLANG -std=gnu11 -O3 -ffp-contract=fast"
entry cut-simd-off "tests/test_cut.c with -DMANYLODS_NO_SIMD, $CC" \
    "$CC -std=c99 $STRICT -DMANYLODS_NO_SIMD tests/test_cut.c -o $OUT/cut-simd-off $LIBS" "$OUT/cut-simd-off"
# The cut's planning with a small round budget and segment growth: small trees take the paths of
# large ones (a wide view's rooms from its previous cut, rounds that outgrow their shares).
entry cut-small-budget "tests/test_cut.c's cut groups with a round budget of 2^14 and segments of 256, $CC" \
    "$CC -std=c99 $STRICT '-DMLOD__ROUND_BUDGET=((size_t)1 << 14)' -DMLOD__SEGMENT_GROWTH=256u tests/test_cut.c -o $OUT/cut-small-budget $LIBS" \
    "$OUT/cut-small-budget random_trees hand_made restart motion threads skip one_view"
# Windows of 2^10 entries: every update goes through many windows, chunks split and are written in place,
# and windows whose views are all unchanged are passed over; the cuts and the versions the splat reads stay
# those of one window.
entry cut-small-window "tests/test_cut.c's cut groups (shrinking cuts: chunks joining) and tests/test_redraw.c with windows of 2^10 entries, $CC" \
    "$CC -std=c99 $STRICT '-DMLOD__WINDOW=((size_t)1 << 10)' tests/test_cut.c -o $OUT/cut-small-window $LIBS && $CC -std=c99 $STRICT '-DMLOD__WINDOW=((size_t)1 << 10)' tests/test_redraw.c -o $OUT/redraw-small-window $LIBS" \
    "$OUT/cut-small-window random_trees hand_made restart shrinking motion threads skip one_view && $OUT/redraw-small-window"
entry cut-native "tests/test_cut.c with $native, $CLANG" \
    "$CLANG -std=c99 $STRICT $native tests/test_cut.c -o $OUT/cut-native $LIBS" "$OUT/cut-native"
# The same under the address and undefined-behaviour sanitizers: the vector paths' widest lanes (make
# test's sanitized tests run SSE2's 4) within the buffers their callers give them.
entry cut-native-asan "tests/test_cut.c with $native, $CLANG -fsanitize=address,undefined -O1" \
    "$CLANG -std=c99 $STRICT $native -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined tests/test_cut.c -o $OUT/cut-native-asan $LIBS" \
    "$OUT/cut-native-asan"
# The splat's float filter (mlod__fast_discs) on 8 lanes and on none: each decision and each tile as the double path's.
entry splat-native "tests/test_splat.c's filtered discs and ISM with $native, $CLANG" \
    "$CLANG -std=c99 $STRICT $native tests/test_splat.c -o $OUT/splat-native $LIBS" \
    "$OUT/splat-native filtered_discs image_lanes small_discs ism_exact determinism"
entry splat-simd-off "tests/test_splat.c's filtered discs and ISM with -DMANYLODS_NO_SIMD, $CC" \
    "$CC -std=c99 $STRICT -DMANYLODS_NO_SIMD tests/test_splat.c -o $OUT/splat-simd-off $LIBS" \
    "$OUT/splat-simd-off filtered_discs image_lanes small_discs ism_exact determinism"
# MegaViews' pair filter (mlod__vpair) on 8 lanes and on none: the same renders as the exact path.
entry megaviews-native "tests/test_megaviews.c's pair filter, descent, walks and groups with $native, $CLANG" \
    "$CLANG -std=c99 $STRICT $native tests/test_megaviews.c -o $OUT/megaviews-native $LIBS" \
    "$OUT/megaviews-native pair_filter descend walks groups"
entry megaviews-simd-off "tests/test_megaviews.c's pair filter, descent and walks with -DMANYLODS_NO_SIMD, $CC" \
    "$CC -std=c99 $STRICT -DMANYLODS_NO_SIMD tests/test_megaviews.c -o $OUT/megaviews-simd-off $LIBS" \
    "$OUT/megaviews-simd-off pair_filter descend walks"

# The vector levels chosen at run time (VECTOR LANES): tests/test_simd.c
# runs each level the build holds and the processor has in one process and
# compares its cuts, atlases and renders with the scalar level's.  The gcc
# build (gcc's target pragma) runs in tests/run.sh; here clang's attribute
# pragma, a build for the processor (its own lanes only) and one without
# AVX2.  And a copy of the header under another name, which finds itself
# again only through MANYLODS_SELF.
entry simd-levels-clang "tests/test_simd.c (every level in one process), $CLANG -O2" \
    "$CLANG -std=c99 $STRICT tests/test_simd.c -o $OUT/simd-levels-clang $LIBS" "$OUT/simd-levels-clang"
entry simd-levels-native "tests/test_simd.c with $native (the processor's own lanes and none), $CLANG" \
    "$CLANG -std=c99 $STRICT $native tests/test_simd.c -o $OUT/simd-levels-native $LIBS" "$OUT/simd-levels-native"
entry simd-levels-no-avx2 "tests/test_simd.c with -DMANYLODS_NO_AVX2 (SSE2 and none), $CC" \
    "$CC -std=c99 $STRICT -DMANYLODS_NO_AVX2 tests/test_simd.c -o $OUT/simd-levels-no-avx2 $LIBS" \
    "$OUT/simd-levels-no-avx2"
self_tu() { # the implementation from $OUT/self/inc/lod.h (a renamed copy), printing the level in use
    mkdir -p "$OUT/self/inc" && cp manylods.h "$OUT/self/inc/lod.h" &&
        printf '#define MANYLODS_IMPLEMENTATION\n#include "lod.h"\n#include <stdio.h>\nint main(void) { printf("%%d\\n", (int)mlod_simd_level()); return 0; }\n' >"$OUT/self/tu.c"
}
self_refused() { # without MANYLODS_SELF the copy looks for manylods.h beside it, which is not there
    if $CC -std=c99 -I"$OUT/self/inc" -c "$OUT/self/tu.c" -o "$OUT/self/tu.o" >"$OUT/self/refused.log" 2>&1; then
        echo "the renamed copy built without MANYLODS_SELF"
        return 1
    fi
    grep -m1 'manylods: the implementation includes its own file again as MANYLODS_SELF' "$OUT/self/refused.log"
}
entry simd-self "a renamed copy of the header (lod.h) with -DMANYLODS_SELF='\"lod.h\"', $CC and $CLANG" \
    "self_tu" "self_refused" \
    "$CC -std=c99 $STRICT -I$OUT/self/inc -DMANYLODS_SELF='\"lod.h\"' $OUT/self/tu.c -o $OUT/self/gcc $LIBS" \
    "$CLANG -std=c99 $STRICT -I$OUT/self/inc -DMANYLODS_SELF='\"lod.h\"' $OUT/self/tu.c -o $OUT/self/clang $LIBS" \
    "$OUT/self/gcc" "$OUT/self/clang"

# The NEON lanes (AArch64), where an AArch64 cross compiler and qemu are
# here (tests/deps.sh brings them on x86-64): the same hash with and
# without them, and test_cut's groups that check the cut and its float
# filter against exact references on them (the whole program takes minutes
# under qemu).  Elsewhere not run, and not counted.
if command -v aarch64-linux-gnu-gcc >/dev/null 2>&1 && command -v qemu-aarch64 >/dev/null 2>&1; then
    neon_hash() { # flags...: fp_hash.c built for AArch64 with them, run under qemu, against the reference
        local exe="$OUT/fp-aarch64-$(printf '%s' "$*" | tr -c 'a-zA-Z0-9' '_')" hash
        aarch64-linux-gnu-gcc -Wall -Wextra -pedantic -Werror -static "$@" $SRC/fp_hash.c -o "$exe" $LIBS || return 1
        hash=$(qemu-aarch64 "$exe" | sed -n 's/^hash //p')
        echo "hash $hash"
        [ -n "$hash" ] && [ "$hash" = "$fp_reference" ] || { echo "differs from the reference $fp_reference"; return 1; }
    }
    entry neon-fp "same hash: aarch64-linux-gnu-gcc -O2 (NEON, 4 lanes) and -DMANYLODS_NO_SIMD, under qemu" \
        "neon_hash -std=c99 -O2" "neon_hash -std=c99 -O2 -DMANYLODS_NO_SIMD"
    entry neon-cut "tests/test_cut.c's cut and float filter groups for AArch64 (NEON), under qemu" \
        "aarch64-linux-gnu-gcc -std=c99 $STRICT -static tests/test_cut.c -o $OUT/neon-cut $LIBS" \
        "qemu-aarch64 $OUT/neon-cut random_trees hand_made backface_boundary fast_filter fast_conditioning"
    entry neon-splat "tests/test_splat.c's filtered discs and ISM for AArch64 (NEON), under qemu" \
        "aarch64-linux-gnu-gcc -std=c99 $STRICT -static tests/test_splat.c -o $OUT/neon-splat $LIBS" \
        "qemu-aarch64 $OUT/neon-splat filtered_discs image_lanes ism_exact"
    entry neon-megaviews "tests/test_megaviews.c's pair filter and descent for AArch64 (NEON), under qemu" \
        "aarch64-linux-gnu-gcc -std=c99 $STRICT -static tests/test_megaviews.c -o $OUT/neon-megaviews $LIBS" \
        "qemu-aarch64 $OUT/neon-megaviews pair_filter descend"
    entry neon-simd "tests/test_simd.c for AArch64 (NEON and none in one process), under qemu" \
        "aarch64-linux-gnu-gcc -std=c99 $STRICT -static tests/test_simd.c -o $OUT/neon-simd $LIBS" \
        "qemu-aarch64 $OUT/neon-simd"
    entry f64-aarch64 "tests/test_f64.c for AArch64 (shaders/f64.glsl against AArch64's doubles), under qemu" \
        "aarch64-linux-gnu-gcc -std=c99 $STRICT -static tests/test_f64.c -o $OUT/f64-aarch64 $LIBS" \
        "qemu-aarch64 $OUT/f64-aarch64 300000"
else
    echo "  (not run: neon-fp, neon-cut, neon-splat, neon-megaviews, neon-simd, f64-aarch64: no aarch64-linux-gnu-gcc or qemu-aarch64 here)"
fi

# MANYLODS_STATIC: two private copies in one program.
entry static-gcc "MANYLODS_STATIC, two private copies in one program, $CC" \
    "$CC -std=c99 $LINKAGE -c $SRC/static_a.c -o $OUT/static_a.o" \
    "$CC -std=c99 $LINKAGE -c $SRC/static_b.c -o $OUT/static_b.o" \
    "foreign_symbols $OUT/static_a.o '^static_a_run$'" \
    "$CC $OUT/static_a.o $OUT/static_b.o -o $OUT/static-gcc $LIBS" "$OUT/static-gcc"
entry static-clang "MANYLODS_STATIC, two private copies in one program, $CLANG" \
    "$CLANG -std=c99 $LINKAGE -c $SRC/static_a.c -o $OUT/static_a-clang.o" \
    "$CLANG -std=c99 $LINKAGE -c $SRC/static_b.c -o $OUT/static_b-clang.o" \
    "$CLANG $OUT/static_a-clang.o $OUT/static_b-clang.o -o $OUT/static-clang $LIBS" "$OUT/static-clang"
entry static-gxx "MANYLODS_STATIC, two private copies in one program, C++11, $CXX" \
    "$CXX -std=c++11 $LINKAGE -x c++ -c $SRC/static_a.c -o $OUT/static_a-cxx.o" \
    "$CXX -std=c++11 $LINKAGE -x c++ -c $SRC/static_b.c -o $OUT/static_b-cxx.o" \
    "$CXX $OUT/static_a-cxx.o $OUT/static_b-cxx.o -o $OUT/static-gxx $LIBS" "$OUT/static-gxx"

# MANYLODS_PTHREADS: the built-in pool, same cuts for 1, 2 and 4 threads.
entry pthreads-gcc "MANYLODS_PTHREADS, C99, $CC" \
    "$CC -std=c99 $LINKAGE $SRC/threads.c -o $OUT/pthreads-gcc $LIBS" "$OUT/pthreads-gcc"
entry pthreads-clang "MANYLODS_PTHREADS, C99, $CLANG" \
    "$CLANG -std=c99 $LINKAGE $SRC/threads.c -o $OUT/pthreads-clang $LIBS" "$OUT/pthreads-clang"
entry pthreads-gxx "MANYLODS_PTHREADS, C++11, $CXX" \
    "$CXX -std=c++11 $LINKAGE -x c++ $SRC/threads.c -o $OUT/pthreads-gxx $LIBS" "$OUT/pthreads-gxx"

# Unity builds: the program's short macros and names, another library, then
# manylods.h with its implementation.
for cc in "$CC" "$CLANG"; do
    tag=$(basename "$cc")
    entry "unity-macros-$tag" "unity build after min/max/PI/clamp/ABS/SWAP/lerp macros, C99, $cc" \
        "$cc -std=c99 $LINKAGE $SRC/unity_macros.c -o $OUT/unity-macros-$tag $LIBS" "$OUT/unity-macros-$tag"
    entry "unity-names-$tag" "unity build after functions/types min, max, clamp, lerp, vec3, C99, $cc" \
        "$cc -std=c99 $LINKAGE $SRC/unity_names.c -o $OUT/unity-names-$tag $LIBS" "$OUT/unity-names-$tag"
done
entry unity-near-far "unity build after the empty near/far macros of <windows.h>, C99, $CC" \
    "$CC -std=c99 $LINKAGE -DUNITY_NEAR_FAR $SRC/unity_macros.c -o $OUT/unity-near-far $LIBS" "$OUT/unity-near-far"

# No leaked macros: a list of short names, then every macro the header adds.
entry no-short-macros "no MIN/MAX/PI/SWAP/... defined after the implementation, $CC" \
    "$CC -std=c99 $LINKAGE $SRC/leaks.c -o $OUT/no-short-macros $LIBS" "$OUT/no-short-macros"
printf '#include "manylods.h"\n' >"$OUT/decl_tu.c"
printf '#define MANYLODS_PTHREADS\n#define MANYLODS_IMPLEMENTATION\n#include "manylods.h"\n' >"$OUT/impl_tu.c"
entry prefixed-macros "every macro the header defines is MANYLODS_ or MLOD_ prefixed, $CC" \
    "new_macros '$CC -I.' $OUT/decl_tu.c" "new_macros '$CC -I.' $OUT/impl_tu.c"

# The configuration macros.
entry config-macros "MANYLODS_MALLOC/FREE and MANYLODS_ASSERT replace the defaults, $CC" \
    "$CC -std=c99 $LINKAGE $SRC/alloc.c -o $OUT/config-macros $LIBS" "$OUT/config-macros"

# MANYLODS_DEF replaced: the object's public functions take its attribute.
hidden_api() { # object: mlod_ functions defined, every one hidden
    local all hidden
    all=$(readelf -sW "$1" | awk '$4 == "FUNC" && $5 == "GLOBAL" && $8 ~ /^mlod_[a-z]/' | wc -l)
    hidden=$(readelf -sW "$1" | awk '$4 == "FUNC" && $5 == "GLOBAL" && $6 == "HIDDEN" && $8 ~ /^mlod_[a-z]/' | wc -l)
    echo "$hidden of $all public functions hidden"
    [ "$all" -gt 20 ] && [ "$hidden" = "$all" ]
}
entry def-override "MANYLODS_DEF replaces the default declaration specifiers, $CC" \
    "$CC -std=c99 $LINKAGE -c $SRC/def_override.c -o $OUT/def_override.o" "hidden_api $OUT/def_override.o" \
    "$CC $OUT/def_override.o -o $OUT/def-override $LIBS" "$OUT/def-override"

# The README's example, as strict as the rest, and quoted verbatim.
readme_quotes() { # file: the README's first C code block is exactly this file
    awk '/^```c$/ { inside = 1; next } /^```$/ { if (inside) exit } inside' README.md | diff -u "$1" - &&
        echo "README.md quotes $1 verbatim"
}
entry minimal-werror "examples/minimal.c, C99, $CC and $CLANG; README.md quotes it" \
    "$CC -std=c99 $LINKAGE examples/minimal.c -o $OUT/minimal-gcc $LIBS" "$OUT/minimal-gcc" \
    "$CLANG -std=c99 $LINKAGE examples/minimal.c -o $OUT/minimal-clang $LIBS" "$OUT/minimal-clang" \
    "readme_quotes examples/minimal.c"

report
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
