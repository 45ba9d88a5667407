#!/usr/bin/env bash
# tests/deps.sh - bring what `make test` (and `make fuzz`, `make bench`)
# need, on Debian or Ubuntu: the one list of the project's packages, shared
# by the Makefile and .ci/run.
#
#   tests/deps.sh           install what is missing (as root, with apt-get),
#                           or stop with the exact command to run
#   tests/deps.sh --list    print the packages, one line
#
# What the packages are for:
#   gcc g++ clang make libc6-dev   the compilers of the tests and the matrix
#   libclang-rt-N-dev              clang's sanitizer runtimes and libFuzzer
#                                  (clang only recommends it)
#   libembree-dev                  Embree 3, the benchmark's exact reference
#                                  (bench --selftest runs in make test)
#   libvulkan-dev                  the Vulkan headers and loader (manylods_vk.h)
#   mesa-vulkan-drivers            lavapipe, the CPU Vulkan device the tests use
#   vulkan-validationlayers        the validation layer test_vulkan runs under
#   glslang-tools spirv-tools      recompile shaders/ and compare with the
#                                  SPIR-V embedded in manylods_vk.h
#   gcc-aarch64-linux-gnu          (x86-64 hosts) build the tests for AArch64,
#   libc6-dev-arm64-cross          run them under qemu: the cut's NEON lanes
#   qemu-user                      (tests/compile/matrix.sh, neon-*)
# Exit status 0 when everything is there (afterwards), 1 otherwise.
set -u

clang_major=$(clang --version 2>/dev/null | sed -n 's/.*clang version \([0-9][0-9]*\)\..*/\1/p' | head -n 1)
packages=(gcc g++ clang make libc6-dev "libclang-rt-${clang_major:-14}-dev" libembree-dev
          libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools spirv-tools)
if [ "$(uname -m)" = x86_64 ]; then
    packages+=(gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user)
fi

if [ "${1:-}" = --list ]; then
    echo "${packages[*]}"
    exit 0
fi

if ! command -v dpkg-query >/dev/null 2>&1; then
    echo "tests/deps.sh: this is not a Debian-like system (no dpkg-query): install the equivalents of"
    echo "    ${packages[*]}"
    echo "  (gcc, g++, clang with its sanitizer and libFuzzer runtimes, make, Embree 3, the Vulkan"
    echo "  loader and headers, Mesa's lavapipe, the Khronos validation layer, glslang and SPIRV-Tools),"
    echo "  then run make test-only (make test without this check)"
    exit 1
fi

missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$package")
done
[ ${#missing[@]} = 0 ] && exit 0

if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "make test needs these Debian packages, which are not installed: ${missing[*]}"
    echo "install them, then run make test again:"
    echo "    sudo apt-get install -y --no-install-recommends ${missing[*]}"
    exit 1
fi

echo "tests/deps.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! apt-get update -qq || ! apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; then
    echo "tests/deps.sh: apt-get could not install: ${missing[*]}"
    exit 1
fi
echo "tests/deps.sh: installed ${missing[*]}"
