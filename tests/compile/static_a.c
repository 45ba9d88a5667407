/* tests/compile/static_a.c - a private copy of the library (MANYLODS_STATIC),
   linked into one program with static_b.c, which has its own.  Uses only a
   part of the API, so unused private functions must not warn. */
#define MANYLODS_STATIC
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int static_a_run(uint32_t *checksum);

int static_a_run(uint32_t *checksum)
{
    return smoke_run("static_a.c", NULL, checksum);
}
