#!/bin/sh
# tests/compile/examples_cxx.sh - every example (examples/*.c) compiled as
# C++11 too, so that a C++ project can take any of them as its start: $CXX
# -x c++ -std=c++11 with the C build's flags, -O2 -Wall -Wextra and
# -pedantic-errors for -pedantic (what C++11 lacks is an error:
# designated initializers, compound literals, variable-length arrays;
# C++'s own errors, such as an int or a void * converted implicitly, are
# anyway), and the Makefile's DEMO_DEFINES (default -DMANYLODS_PTHREADS)
# for the examples built on examples/app.h, as the Makefile builds them.
# Warnings do not fail an example (the C build does not stop at them
# either): its ok line counts them, its log keeps them.  Objects only, not
# linked (the C builds and tests/check_examples.c run the examples).  An
# example that includes manylods_vk.h needs <vulkan/vulkan.h>: without it
# that example is skipped, or fails under MANYLODS_REQUIRE_VULKAN=1 (as in
# tests/compile/vulkan.sh).  Prints "  ok    NAME" or "  FAIL  NAME" with
# the compiler's messages, then "N passed, M failed".
#
# Environment: CXX (default g++), CFLAGS (added, as the Makefile adds them),
# DEMO_DEFINES, MATRIX_OUT (default build/matrix: objects and logs go to
# its examples_cxx/).
cd "$(dirname "$0")/../.." || exit 1
out=${MATRIX_OUT:-build/matrix}/examples_cxx
mkdir -p "$out" || exit 1
have_vulkan=0
printf '#include <vulkan/vulkan.h>\n' | ${CXX:-g++} -x c++ -fsyntax-only - 2>/dev/null && have_vulkan=1
passed=0
failed=0
for source in examples/*.c; do
    name=$(basename "$source" .c)
    defines=
    grep -q '^#include "app.h"' "$source" && defines=${DEMO_DEFINES--DMANYLODS_PTHREADS}
    if [ "$have_vulkan" = 0 ] && grep -q 'manylods_vk.h' "$source"; then
        if [ "${MANYLODS_REQUIRE_VULKAN:-0}" = 1 ]; then
            failed=$((failed + 1))
            echo "  FAIL  $name: <vulkan/vulkan.h> not found (Debian: libvulkan-dev)"
        else
            echo "  skip  $name: <vulkan/vulkan.h> not found (Debian: libvulkan-dev)"
        fi
        continue
    fi
    # shellcheck disable=SC2086
    if ${CXX:-g++} -x c++ -std=c++11 -O2 -Wall -Wextra -pedantic-errors ${CFLAGS:-} $defines -c "$source" \
        -o "$out/$name.o" >"$out/$name.log" 2>&1; then
        passed=$((passed + 1))
        warnings=$(grep -c 'warning:' "$out/$name.log")
        if [ "$warnings" = 0 ]; then echo "  ok    $name"; else echo "  ok    $name ($warnings warnings: $out/$name.log)"; fi
    else
        failed=$((failed + 1))
        echo "  FAIL  $name"
        sed 's/^/      | /' "$out/$name.log" | head -n 30
    fi
done
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
