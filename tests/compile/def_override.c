/* tests/compile/def_override.c - MANYLODS_DEF defined by the user replaces
   the default: here every public function gets hidden visibility, which the
   matrix checks in the object's symbol table (and the program still runs). */
#define MANYLODS_DEF extern __attribute__((visibility("hidden")))
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    uint32_t checksum = 0;
    return smoke_run("MANYLODS_DEF hidden", NULL, &checksum);
}
