#!/bin/sh
# tests/compile/vulkan.sh - manylods_vk.h built as its users build it:
# with VK_NO_PROTOTYPES (volk's way) and without the Vulkan loader, as C99
# (gcc, clang) and as C++ (g++), -Wall -Wextra -pedantic -Werror; each
# build is run.  Prints "N passed, M failed"; without <vulkan/vulkan.h> it
# says it skipped, unless MANYLODS_REQUIRE_VULKAN=1.
cd "$(dirname "$0")/../.." || exit 1
out=${MATRIX_OUT:-build/matrix}
mkdir -p "$out"
if ! printf '#include <vulkan/vulkan.h>\n' | ${CC:-gcc} -x c -fsyntax-only - 2>/dev/null; then
    echo "SKIPPED: <vulkan/vulkan.h> not found (Debian: libvulkan-dev)"
    if [ "${MANYLODS_REQUIRE_VULKAN:-0}" = 1 ]; then echo "0 passed, 1 failed"; exit 1; fi
    echo "0 passed, 0 failed"
    exit 0
fi
passed=0
failed=0
check() { # name compiler flags...
    name=$1
    shift
    if "$@" tests/compile/vulkan_unit.c -o "$out/$name" -lm >"$out/$name.log" 2>&1 && "$out/$name" >>"$out/$name.log" 2>&1; then
        passed=$((passed + 1))
        echo "  ok    $name"
    else
        failed=$((failed + 1))
        echo "  FAIL  $name"
        sed 's/^/      | /' "$out/$name.log" | tail -n 30
    fi
}
check vk_gcc_c99 ${CC:-gcc} -std=c99 -Wall -Wextra -pedantic -Werror -O2
check vk_clang_c99 ${CLANG:-clang} -std=c99 -Wall -Wextra -pedantic -Werror -O2
check vk_gxx ${CXX:-g++} -x c++ -std=c++11 -Wall -Wextra -pedantic -Werror -O2
echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
