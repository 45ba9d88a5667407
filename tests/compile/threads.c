/* tests/compile/threads.c - the built-in thread pool (MANYLODS_PTHREADS),
   after the program's own system headers.  The cuts must not depend on the
   thread count.  Common subset of C99 and C++11. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MANYLODS_PTHREADS
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    static const uint32_t thread_counts[] = {1, 2, 4};
    uint32_t serial = 0, threaded = 0, i;
    int failed = smoke_run("threads.c, no pool", NULL, &serial);
    for (i = 0; i < sizeof thread_counts / sizeof *thread_counts; i++) {
        mlod_pool *pool = mlod_pool_create(thread_counts[i]);
        mlod_parallel parallel;
        if (!pool) {
            printf("mlod_pool_create(%u) failed\n", thread_counts[i]);
            return 1;
        }
        parallel = mlod_pool_parallel(pool);
        failed |= smoke_run("threads.c, pool", &parallel, &threaded);
        if (threaded != serial) {
            printf("%u threads give different cuts than the calling thread alone\n", thread_counts[i]);
            failed = 1;
        }
        mlod_pool_destroy(pool);
    }
    return failed;
}
