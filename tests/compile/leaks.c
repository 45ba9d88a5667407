/* tests/compile/leaks.c - after the declarations and the implementation
   (with the thread pool) the header has defined none of the short macros
   that programs and other libraries define themselves.  matrix.sh also
   compares every macro the header adds against its MANYLODS_ / MLOD_ prefix. */
#define MANYLODS_PTHREADS
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"

#if defined(MIN) || defined(MAX) || defined(min) || defined(max)
#error "manylods.h leaks MIN, MAX, min or max"
#endif
#if defined(PI) || defined(TAU) || defined(PI_F)
#error "manylods.h leaks PI, TAU or PI_F"
#endif
#if defined(SWAP) || defined(swap) || defined(ABS) || defined(abs_) || defined(SIGN)
#error "manylods.h leaks SWAP, swap, ABS or SIGN"
#endif
#if defined(CLAMP) || defined(clamp) || defined(LERP) || defined(lerp) || defined(SQR) || defined(SQ)
#error "manylods.h leaks CLAMP, clamp, LERP, lerp, SQR or SQ"
#endif
#if defined(EPS) || defined(EPSILON) || defined(INF) || defined(INFINITY_F)
#error "manylods.h leaks EPS, EPSILON or INF"
#endif
#if defined(DOT) || defined(CROSS) || defined(LEN) || defined(vec3)
#error "manylods.h leaks DOT, CROSS, LEN or vec3"
#endif
#if defined(countof) || defined(COUNTOF) || defined(ARRAY_SIZE) || defined(ARRAY_COUNT) || defined(UNUSED)
#error "manylods.h leaks countof, ARRAY_SIZE or UNUSED"
#endif
#if defined(INLINE) || defined(FORCE_INLINE) || defined(RESTRICT) || defined(likely) || defined(unlikely)
#error "manylods.h leaks INLINE, RESTRICT, likely or unlikely"
#endif
#if defined(TRUE) || defined(FALSE) || defined(ALIGN) || defined(STATIC_ASSERT) || defined(ASSERT)
#error "manylods.h leaks TRUE, FALSE, ALIGN, STATIC_ASSERT or ASSERT"
#endif
#if defined(M_PI)
#error "manylods.h defines M_PI, or a feature macro that makes <math.h> define it"
#endif

int main(void)
{
    return mlod_result_name(MLOD_OK) ? 0 : 1;
}
