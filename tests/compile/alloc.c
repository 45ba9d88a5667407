/* tests/compile/alloc.c - the configuration macros: MANYLODS_MALLOC /
   MANYLODS_FREE replace the default allocator (every block comes back) and
   MANYLODS_ASSERT replaces assert (it never fires on valid input). */
#include <stdio.h>
#include <stdlib.h>

static size_t alloc_calls, live_blocks, assert_failures;

static void *counting_malloc(size_t bytes, void *user)
{
    void *p = malloc(bytes);
    (void)user;
    alloc_calls++;
    if (p) live_blocks++;
    return p;
}

static void counting_free(void *pointer, void *user)
{
    (void)user;
    if (pointer) live_blocks--;
    free(pointer);
}

static void assert_failed(const char *what)
{
    printf("MANYLODS_ASSERT(%s) failed\n", what);
    assert_failures++;
}

#define MANYLODS_MALLOC(size, user) counting_malloc(size, user)
#define MANYLODS_FREE(ptr, user) counting_free(ptr, user)
#define MANYLODS_ASSERT(x) ((x) ? (void)0 : assert_failed(#x))
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    uint32_t checksum;
    int failed = smoke_run("alloc.c", NULL, &checksum);
    if (alloc_calls == 0 || live_blocks != 0 || assert_failures != 0) {
        printf("MANYLODS_MALLOC called %lu times, %lu blocks never freed, %lu assertions failed\n",
               (unsigned long)alloc_calls, (unsigned long)live_blocks, (unsigned long)assert_failures);
        failed = 1;
    }
    return failed;
}
