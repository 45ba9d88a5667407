/* tests/compile/impl.c - the implementation and a use of it in one C file.
   Compiled as C99 with -Wall -Wextra -pedantic -Werror by gcc and clang. */
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    uint32_t checksum;
    return smoke_run("impl.c", NULL, &checksum);
}
