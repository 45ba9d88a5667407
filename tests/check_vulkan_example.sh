#!/bin/sh
# tests/check_vulkan_example.sh - run examples/vulkan_minimal (path in $1)
# and check that it wrote a PNG.  Prints "N passed, M failed" for
# tests/run.sh; without a Vulkan device it says it skipped and counts
# nothing, unless MANYLODS_REQUIRE_VULKAN=1.
program=${1:-${BUILD:-build}/examples/vulkan_minimal}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$program" "$out/atlas.png"
status=$?
if [ "$status" = 2 ]; then
    echo "SKIPPED: no usable Vulkan device"
    if [ "${MANYLODS_REQUIRE_VULKAN:-0}" = 1 ]; then echo "0 passed, 1 failed"; exit 1; fi
    echo "0 passed, 0 failed"
    exit 0
fi
# a PNG: the 8-byte signature, then an IHDR chunk
if [ "$status" = 0 ] && [ "$(head -c 16 "$out/atlas.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a0000000d49484452" ]; then
    echo "1 passed, 0 failed"
    exit 0
fi
echo "vulkan_minimal: exit status $status, or no PNG written"
echo "0 passed, 1 failed"
exit 1
