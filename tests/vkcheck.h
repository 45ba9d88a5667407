/* tests/vkcheck.h - what the tests of a test-only compute shader share
   (tests/test_f64_vulkan.c, tests/test_lookup_vulkan.c): the skip rule,
   compiling the shader with glslangValidator, and the scan of the
   module's capabilities.  Include after harness.h and tempdir.h. */
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

#endif
