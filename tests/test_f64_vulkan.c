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

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char *name);

#define RESULTS 6 /* uvec4 per operand pair, as tests/f64_check.comp writes them */

int main(int argc, char **argv)
{
    uint32_t n = argc > 1 ? (uint32_t)strtoul(argv[1], NULL, 10) : 200000u, i, groups, wrong = 0, wrong_ops[RESULTS * 4];
    uint64_t state = 0x5EEDF64ull + 1;
    mlodvk_device_desc dd;
    mlodvk_device device;
    mlodvk_context_desc desc;
    mlodvk_context *ctx = NULL;
    mlod_error e;
    char why[1200];
    size_t bytes = 0;
    uint32_t *words, *in, *out;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set;
    mlodvk__buffer operands, results;
    mlod_result res;

    words = vkc_compile("tests/f64_check.comp", "", &bytes, why, sizeof why);
    if (!words) return vkc_skip(why);
    CHECK(vkc_wide_capabilities(words, bytes / 4, 0) == 0,
          "tests/f64_check.comp declares no Float64, Int64 or Int64Atomics capability (found %d)",
          vkc_wide_capabilities(words, bytes / 4, 0));

    memset(&dd, 0, sizeof dd);
    dd.get_instance_proc_addr = vkGetInstanceProcAddr;
    dd.validation = 1;
    dd.prefer_cpu = getenv("MANYLODS_VULKAN_GPU") == NULL;
    if (mlodvk_device_create(&dd, &device, &e) != MLOD_OK) {
        free(words);
        snprintf(why, sizeof why, "no usable Vulkan device with the validation layer: %s", e.message);
        return vkc_skip(why);
    }
    desc = mlodvk_device_context_desc(&device);
    if (mlodvk_context_create(&desc, &ctx, &e) != MLOD_OK) {
        CHECK(0, "mlodvk_context_create on %s: %s", device.name, e.message);
        free(words);
        mlodvk_device_destroy(&device);
        return test_finish();
    }
    printf("  device: %s\n", mlodvk_context_device_name(ctx));

    memset(&operands, 0, sizeof operands);
    memset(&results, 0, sizeof results);
    res = mlodvk__set_layout(ctx, 2, &set_layout, &e);
    if (res == MLOD_OK) res = mlodvk__pipeline_layout(ctx, set_layout, 4, &layout, &e);
    if (res == MLOD_OK) res = mlodvk__pipeline(ctx, words, bytes, layout, &pipeline, &e);
    if (res == MLOD_OK)
        res = mlodvk__buffer_create(ctx, 16 * (VkDeviceSize)n, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, &operands, &e);
    if (res == MLOD_OK)
        res = mlodvk__buffer_create(ctx, 16 * RESULTS * (VkDeviceSize)n, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1,
                                    &results, &e);
    if (res == MLOD_OK) res = mlodvk__pool(ctx, 1, 2, &pool, &e);
    if (res == MLOD_OK) res = mlodvk__sets(ctx, pool, set_layout, 1, &set, &e);
    CHECK(res == MLOD_OK, "the test pipeline and buffers: %s", e.message);
    if (res == MLOD_OK) {
        VkBuffer buffers[2];
        in = operands.mapped;
        for (i = 0; i < n; i++) {
            uint64_t a = f64t_operand(&state, i % 7), b = f64t_partner(&state, a, i / 7);
            in[4 * i] = (uint32_t)a;
            in[4 * i + 1] = (uint32_t)(a >> 32);
            in[4 * i + 2] = (uint32_t)b;
            in[4 * i + 3] = (uint32_t)(b >> 32);
        }
        buffers[0] = operands.buffer;
        buffers[1] = results.buffer;
        mlodvk__write_set(ctx, set, buffers, 2);
        res = mlodvk__begin(ctx, &e);
        if (res == MLOD_OK) {
            groups = (n + 63) / 64;
            ctx->vk.CmdBindPipeline(ctx->commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
            ctx->vk.CmdBindDescriptorSets(ctx->commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, NULL);
            ctx->vk.CmdPushConstants(ctx->commands, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 4, &n);
            ctx->vk.CmdDispatch(ctx->commands, groups, 1, 1);
            mlodvk__barrier(ctx);
            res = mlodvk__submit(ctx, &e);
        }
        mlodvk__abandon(ctx);
        CHECK(res == MLOD_OK, "the dispatch of %u operand pairs: %s", n, e.message);
    }
    if (res == MLOD_OK) {
        /* the same results from the C compile of f64.glsl, word for word */
        static const char *names[RESULTS * 4] = {"add", "add", "sub", "sub", "mul", "mul", "div", "div",
                                                  "sqrt", "sqrt", "to float", "lt, le, eq", "from float",
                                                  "from float", "from int", "from int", "from uint", "from uint",
                                                  "to int", "(unused)", "floor", "floor", "ceil", "ceil"};
        memset(wrong_ops, 0, sizeof wrong_ops);
        out = results.mapped;
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
    if (pool) ctx->vk.DestroyDescriptorPool(ctx->device, pool, ctx->vk_allocator);
    if (pipeline) ctx->vk.DestroyPipeline(ctx->device, pipeline, ctx->vk_allocator);
    if (layout) ctx->vk.DestroyPipelineLayout(ctx->device, layout, ctx->vk_allocator);
    if (set_layout) ctx->vk.DestroyDescriptorSetLayout(ctx->device, set_layout, ctx->vk_allocator);
    mlodvk__buffer_destroy(ctx, &operands);
    mlodvk__buffer_destroy(ctx, &results);
    mlodvk_context_destroy(ctx);
    mlodvk_device_destroy(&device);
    free(words);
    return test_finish();
}
