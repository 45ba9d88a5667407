/* tests/test_f64_vulkan.c - shaders/f64.glsl on a Vulkan device (lavapipe
   in CI, with the Khronos validation layer) against the same text compiled
   as C (tests/f64_c.h), which tests/test_f64.c checks against the host's
   doubles: every operation gives the same bits on the device, so a shader
   that computes in f64.glsl decides as the CPU's double code does, on a
   device without shaderFloat64 or shaderInt64.

   tests/f64_check.comp is compiled here, with glslangValidator (Debian:
   glslang-tools; GLSLANG overrides the command), and its module must not
   declare the Float64, Int64 or Int64Atomics capabilities.  Without a
   Vulkan device or the compiler it prints why and reports no test (0
   passed, 0 failed), unless MANYLODS_REQUIRE_VULKAN=1 (CI): then a skip is
   a failure.  Run from the repository's root (make test does). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"

#include "harness.h"
#include "tempdir.h"
#include "vkcheck.h"
#include "f64_c.h"

#define RESULTS 6 /* uvec4 per operand pair, as tests/f64_check.comp writes them */

int main(int argc, char **argv)
{
    uint32_t n = argc > 1 ? (uint32_t)strtoul(argv[1], NULL, 10) : 200000u, i, wrong = 0, wrong_ops[RESULTS * 4];
    uint64_t state = 0x5EEDF64ull + 1;
    mlodvk_device device;
    mlodvk_context *ctx = NULL;
    mlod_error e;
    char why[1200];
    size_t bytes = 0;
    uint32_t *words, *in, *out;
    VkDeviceSize sizes[2];
    vkc_program program;
    mlod_result res;
    int opened;

    words = vkc_compile("tests/f64_check.comp", "", &bytes, why, sizeof why);
    if (!words) return vkc_skip(why);
    CHECK(vkc_wide_capabilities(words, bytes / 4, 0) == 0,
          "tests/f64_check.comp declares no Float64, Int64 or Int64Atomics capability (found %d)",
          vkc_wide_capabilities(words, bytes / 4, 0));

    opened = vkc_open(&device, &ctx, why, sizeof why);
    if (opened <= 0) {
        free(words);
        return opened == 0 ? vkc_skip(why) : test_finish();
    }
    printf("  device: %s\n", mlodvk_context_device_name(ctx));

    memset(&program, 0, sizeof program);
    sizes[0] = 16 * (VkDeviceSize)n;           /* operands */
    sizes[1] = 16 * RESULTS * (VkDeviceSize)n; /* results */
    res = vkc_program_create(ctx, words, bytes, sizes, 2, 4, &program, &e);
    CHECK(res == MLOD_OK, "the test pipeline and buffers: %s", e.message);
    if (res == MLOD_OK) {
        in = program.buffers[0].mapped;
        for (i = 0; i < n; i++) {
            uint64_t a = f64t_operand(&state, i % 7), b = f64t_partner(&state, a, i / 7);
            in[4 * i] = (uint32_t)a;
            in[4 * i + 1] = (uint32_t)(a >> 32);
            in[4 * i + 2] = (uint32_t)b;
            in[4 * i + 3] = (uint32_t)(b >> 32);
        }
        res = vkc_program_run(ctx, &program, &n, (n + 63) / 64, &e);
        CHECK(res == MLOD_OK, "the dispatch of %u operand pairs: %s", n, e.message);
    }
    if (res == MLOD_OK) {
        /* the same results from the C compile of f64.glsl, word for word */
        static const char *names[RESULTS * 4] = {"add", "add", "sub", "sub", "mul", "mul", "div", "div",
                                                  "sqrt", "sqrt", "to float", "lt, le, eq", "from float",
                                                  "from float", "from int", "from int", "from uint", "from uint",
                                                  "to int", "(unused)", "floor", "floor", "ceil", "ceil"};
        memset(wrong_ops, 0, sizeof wrong_ops);
        out = program.buffers[1].mapped;
        for (i = 0; i < n; i++) {
            uvec2 a = f64t_pair(in[4 * i], in[4 * i + 1]), b = f64t_pair(in[4 * i + 2], in[4 * i + 3]), r;
            uint32_t want[RESULTS * 4], k;
            int small = f64_lt(f64_abs(a), f64t_pair(0u, 0x41E00000u));
            r = f64_add(a, b), want[0] = r.x, want[1] = r.y;
            r = f64_sub(a, b), want[2] = r.x, want[3] = r.y;
            r = f64_mul(a, b), want[4] = r.x, want[5] = r.y;
            r = f64_div(a, b), want[6] = r.x, want[7] = r.y;
            r = f64_sqrt(a), want[8] = r.x, want[9] = r.y;
            want[10] = floatBitsToUint(f64_to_float(a));
            want[11] = (uint32_t)f64_lt(a, b) | (uint32_t)f64_le(a, b) << 1 | (uint32_t)f64_eq(a, b) << 2;
            r = f64_from_float(uintBitsToFloat(b.x)), want[12] = r.x, want[13] = r.y;
            r = f64_from_int((int32_t)b.y), want[14] = r.x, want[15] = r.y;
            r = f64_from_uint(b.y), want[16] = r.x, want[17] = r.y;
            want[18] = small ? (uint32_t)f64_to_int(a) : 0u;
            want[19] = 0u;
            r = f64_floor(a), want[20] = r.x, want[21] = r.y;
            r = f64_ceil(a), want[22] = r.x, want[23] = r.y;
            for (k = 0; k < RESULTS * 4; k++)
                if (out[RESULTS * 4 * i + k] != want[k]) {
                    if (!wrong++)
                        fprintf(stderr, "first difference: pair %u (0x%08x%08x, 0x%08x%08x), %s: device 0x%08x, C 0x%08x\n",
                                i, a.y, a.x, b.y, b.x, names[k], out[RESULTS * 4 * i + k], want[k]);
                    wrong_ops[k]++;
                }
        }
        for (i = 0; i < RESULTS * 4; i++) {
            /* a double's two words count once, under its name's first word */
            uint32_t count = wrong_ops[i];
            if (i == 19 || (i > 0 && strcmp(names[i], names[i - 1]) == 0)) continue;
            if (i + 1 < RESULTS * 4 && strcmp(names[i], names[i + 1]) == 0) count += wrong_ops[i + 1];
            CHECK(count == 0, "%s: %u of %u operand pairs differ between the device and the C compile", names[i],
                  count, n);
        }
        printf("  %u operand pairs: add, sub, mul, div, sqrt, floor, ceil, comparisons and conversions, %u words differ\n", n,
               wrong);
    }
    CHECK(device.validation_messages == 0, "%u validation message(s), the last: %s", device.validation_messages,
          device.last_message);
    vkc_program_destroy(ctx, &program);
    mlodvk_context_destroy(ctx);
    mlodvk_device_destroy(&device);
    free(words);
    return test_finish();
}
