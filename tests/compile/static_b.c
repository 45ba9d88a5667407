/* tests/compile/static_b.c - the second private copy (see static_a.c), with
   main: both copies must give the same cuts. */
#include <stdio.h>

#define MANYLODS_STATIC
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int static_a_run(uint32_t *checksum);

int main(void)
{
    uint32_t a = 0, b = 1;
    int failed = static_a_run(&a) | smoke_run("static_b.c", NULL, &b);
    if (a != b) {
        printf("the two private copies give different cuts\n");
        failed = 1;
    }
    return failed;
}
