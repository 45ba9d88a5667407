/* tests/compile/unity_macros.c - a unity build: the program's own macros and
   types first (short function-like macros, PI, a vec3 type), then another
   single-file library, then the implementation of manylods.h.  C99, gcc and
   clang, -Werror.  With -DUNITY_NEAR_FAR also the empty `near` and `far`
   macros that <windows.h> defines (a separate entry of the matrix). */
#include <math.h>
#include <stdio.h>

#define min(a, b) ((a) < (b) ? (a) : (b))
#define max(a, b) ((a) > (b) ? (a) : (b))
#define clamp(x, lo, hi) min(max(x, lo), hi)
#define ABS(x) ((x) < 0 ? -(x) : (x))
#define SWAP(type, a, b) do { type swap_tmp_ = (a); (a) = (b); (b) = swap_tmp_; } while (0)
#define lerp(a, b, t) ((a) + ((b) - (a)) * (t))
#define PI 3.14159265f
#ifdef UNITY_NEAR_FAR
#define near
#define far
#endif
typedef struct vec3 { float x, y, z; } vec3;

#include "other_lib.h"

#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"
#include "smoke.h"

int main(void)
{
    vec3 a = {1, 2, 3}, b = {3, 2, 1};
#ifdef UNITY_NEAR_FAR
    float near x = 2, far y = -1;
#else
    float x = 2, y = -1;
#endif
    uint32_t checksum;
    int failed = smoke_run("unity_macros.c", NULL, &checksum);
    SWAP(vec3, a, b);
    if (a.x != 3 || max(x, y) != 2 || min(x, y) != -1 || clamp(5.0f, 0.0f, 1.0f) != 1 || ABS(y) != 1 ||
        lerp(0.0f, 2.0f, 0.5f) != 1 || !(PI > 3 && PI < 4) || DOT(a, b) != 10 || !other_lib_selftest()) {
        printf("the program's own macros changed meaning after manylods.h\n");
        failed = 1;
    }
    return failed;
}
