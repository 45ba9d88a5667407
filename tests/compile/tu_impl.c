/* tests/compile/tu_impl.c - the translation unit that holds the
   implementation, linked with tu_user.c.  It includes the header once
   without the implementation first (as another header of the program might
   have), then again with it: the implementation must still be compiled. */
#include "../../manylods.h"
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
