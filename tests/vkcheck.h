/* tests/vkcheck.h - what the tests of a test-only compute shader share
   (tests/test_f64_vulkan.c, tests/test_lookup_vulkan.c): the skip rule,
   compiling the shader with glslangValidator, the scan of the module's
   capabilities, opening the device, and one shader's pipeline, buffers
   and dispatch.  Include after harness.h, tempdir.h and manylods_vk.h
   with MANYLODS_VK_IMPLEMENTATION (it uses the backend's internals). */
#ifndef MANYLODS_TEST_VKCHECK_H
#define MANYLODS_TEST_VKCHECK_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* No device or no compiler: no test (0 passed, 0 failed), unless
   MANYLODS_REQUIRE_VULKAN=1 (CI), where a skip is a failure.  Returns the
   exit code. */
static int vkc_skip(const char *why)
{
    const char *require = getenv("MANYLODS_REQUIRE_VULKAN");
    printf("SKIPPED: %s\n", why);
    if (require && strcmp(require, "1") == 0) {
        printf("MANYLODS_REQUIRE_VULKAN=1: a skip is a failure\n0 passed, 1 failed\n");
        return 1;
    }
    printf("0 passed, 0 failed\n");
    return 0;
}

/* The SPIR-V words of `shader` (a path from the repository's root)
   compiled with glslangValidator (GLSLANG overrides the command) for
   Vulkan 1.1 with `flags` and shaders/ on the include path, malloc'd, or
   NULL (why in `why`). */
static uint32_t *vkc_compile(const char *shader, const char *flags, size_t *bytes, char *why, size_t why_size)
{
    char dir[256], cmd[1024], path[300];
    const char *glslang = getenv("GLSLANG");
    uint32_t *words = NULL;
    FILE *f;
    long size;
    if (!test_temp_dir(dir, sizeof dir, "shader")) {
        snprintf(why, why_size, "no temporary directory");
        return NULL;
    }
    snprintf(path, sizeof path, "%s/check.spv", dir);
    snprintf(cmd, sizeof cmd, "%s -V --target-env vulkan1.1 %s -Ishaders %s -o %s >%s/log 2>&1",
             glslang && *glslang ? glslang : "glslangValidator", flags, shader, path, dir);
    if (system(cmd) != 0) {
        snprintf(why, why_size, "%s could not compile %s with '%s' (its log: %s/log)",
                 glslang && *glslang ? glslang : "glslangValidator", shader, flags, dir);
        return NULL;
    }
    f = fopen(path, "rb");
    if (f && fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) > 20 && size % 4 == 0 && fseek(f, 0, SEEK_SET) == 0) {
        words = (uint32_t *)malloc((size_t)size);
        if (words && fread(words, 1, (size_t)size, f) != (size_t)size) {
            free(words);
            words = NULL;
        }
        *bytes = (size_t)size;
    }
    if (f) fclose(f);
    if (!words) snprintf(why, why_size, "could not read %s", path);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (words && system(cmd) != 0) fprintf(stderr, "note: could not remove %s\n", dir);
    return words;
}

/* The capabilities a module declares that need 64-bit types or atomics
   (OpCapability Float64 = 10, Int64 = 11, Int64Atomics = 12), and with
   subgroups too those of subgroup operations (GroupNonUniform = 61,
   GroupNonUniformVote = 62), as a count (99 for a malformed module). */
static int vkc_wide_capabilities(const uint32_t *words, size_t count, int subgroups)
{
    size_t i = 5;
    int wide = 0;
    while (i < count) {
        uint32_t op = words[i] & 0xFFFFu, length = words[i] >> 16;
        if (length == 0) return 99;
        if (op == 17 && length == 2 &&
            (words[i + 1] == 10 || words[i + 1] == 11 || words[i + 1] == 12 ||
             (subgroups && (words[i + 1] == 61 || words[i + 1] == 62))))
            wide++;
        i += length;
    }
    return wide;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char *name);

/* The device the tests use (the CPU's, lavapipe, unless
   MANYLODS_VULKAN_GPU is set), with the validation layer, and a context on
   it.  1: both open; 0: no device (why says so: skip); -1: the context
   failed (a failed check; the device is closed again). */
static int vkc_open(mlodvk_device *device, mlodvk_context **ctx, char *why, size_t why_size)
{
    mlodvk_device_desc dd;
    mlodvk_context_desc desc;
    mlod_error e;
    memset(&dd, 0, sizeof dd);
    dd.get_instance_proc_addr = vkGetInstanceProcAddr;
    dd.validation = 1;
    dd.prefer_cpu = getenv("MANYLODS_VULKAN_GPU") == NULL;
    if (mlodvk_device_create(&dd, device, &e) != MLOD_OK) {
        snprintf(why, why_size, "no usable Vulkan device with the validation layer: %s", e.message);
        return 0;
    }
    desc = mlodvk_device_context_desc(device);
    if (mlodvk_context_create(&desc, ctx, &e) != MLOD_OK) {
        CHECK(0, "mlodvk_context_create on %s: %s", device->name, e.message);
        mlodvk_device_destroy(device);
        return -1;
    }
    return 1;
}

#define VKC_MAX_BUFFERS 8

/* One compute shader's pipeline over `count` storage buffers (bindings 0
   .. count - 1, host-visible and mapped, sizes[k] bytes each), with
   push_bytes of push constants, and its descriptor set. */
typedef struct vkc_program {
    VkDescriptorSetLayout set_layout;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkDescriptorPool pool;
    VkDescriptorSet set;
    mlodvk__buffer buffers[VKC_MAX_BUFFERS];
    uint32_t count, push_bytes;
} vkc_program;

/* Zero p first; on failure what was made stays in p for vkc_program_destroy. */
static mlod_result vkc_program_create(mlodvk_context *ctx, const uint32_t *words, size_t bytes, const VkDeviceSize *sizes,
                                      uint32_t count, uint32_t push_bytes, vkc_program *p, mlod_error *e)
{
    VkBuffer handles[VKC_MAX_BUFFERS];
    uint32_t k;
    mlod_result res;
    p->count = count;
    p->push_bytes = push_bytes;
    res = mlodvk__set_layout(ctx, count, &p->set_layout, e);
    if (res == MLOD_OK) res = mlodvk__pipeline_layout(ctx, p->set_layout, push_bytes, &p->layout, e);
    if (res == MLOD_OK) res = mlodvk__pipeline(ctx, words, bytes, p->layout, &p->pipeline, e);
    for (k = 0; k < count && res == MLOD_OK; k++)
        res = mlodvk__buffer_create(ctx, sizes[k], VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 1, &p->buffers[k], e);
    if (res == MLOD_OK) res = mlodvk__pool(ctx, 1, count, &p->pool, e);
    if (res == MLOD_OK) res = mlodvk__sets(ctx, p->pool, p->set_layout, 1, &p->set, e);
    if (res == MLOD_OK) {
        for (k = 0; k < count; k++) handles[k] = p->buffers[k].buffer;
        mlodvk__write_set(ctx, p->set, handles, count);
    }
    return res;
}

/* Dispatch `groups` workgroups with the push constants and wait for them. */
static mlod_result vkc_program_run(mlodvk_context *ctx, const vkc_program *p, const void *push, uint32_t groups,
                                   mlod_error *e)
{
    mlod_result res = mlodvk__begin(ctx, e);
    if (res == MLOD_OK) {
        ctx->vk.CmdBindPipeline(ctx->commands, VK_PIPELINE_BIND_POINT_COMPUTE, p->pipeline);
        ctx->vk.CmdBindDescriptorSets(ctx->commands, VK_PIPELINE_BIND_POINT_COMPUTE, p->layout, 0, 1, &p->set, 0, NULL);
        ctx->vk.CmdPushConstants(ctx->commands, p->layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, p->push_bytes, push);
        ctx->vk.CmdDispatch(ctx->commands, groups, 1, 1);
        mlodvk__barrier(ctx);
        res = mlodvk__submit(ctx, e);
    }
    mlodvk__abandon(ctx);
    return res;
}

static void vkc_program_destroy(mlodvk_context *ctx, vkc_program *p)
{
    uint32_t k;
    if (p->pool) ctx->vk.DestroyDescriptorPool(ctx->device, p->pool, ctx->vk_allocator);
    if (p->pipeline) ctx->vk.DestroyPipeline(ctx->device, p->pipeline, ctx->vk_allocator);
    if (p->layout) ctx->vk.DestroyPipelineLayout(ctx->device, p->layout, ctx->vk_allocator);
    if (p->set_layout) ctx->vk.DestroyDescriptorSetLayout(ctx->device, p->set_layout, ctx->vk_allocator);
    for (k = 0; k < VKC_MAX_BUFFERS; k++) mlodvk__buffer_destroy(ctx, &p->buffers[k]);
    memset(p, 0, sizeof *p);
}

#endif
