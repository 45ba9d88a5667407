/* tests/compile/tu_user.c - a translation unit that only uses the library
   (no MANYLODS_IMPLEMENTATION), linked with tu_impl.c.  Common subset of
   C99 and C++11: the matrix also compiles it as C++ against a C-compiled
   implementation and the other way round. */
#include "../../manylods.h"
#include "../../manylods.h" /* twice: the include guard holds */
#include "smoke.h"

int main(void)
{
    uint32_t checksum;
    return smoke_run("tu_user.c", NULL, &checksum);
}
