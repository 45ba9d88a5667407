/* tests/f64_c.h - compile shaders/f64.glsl (binary64 from 32-bit integers)
   as C99, for tests/test_f64.c: the GLSL types and built-ins that file uses,
   then the file itself, then the macros taken back.  Include it after the
   standard headers: it defines the macros uvec2() and uint() (GLSL's
   constructors) around the file. */
#ifndef MANYLODS_TEST_F64_C_H
#define MANYLODS_TEST_F64_C_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

typedef uint32_t uint;
typedef struct uvec2 {
    uint32_t x, y;
} uvec2;

static int findMSB(uint32_t v)
{
    int i = -1;
    while (v) {
        v >>= 1;
        i++;
    }
    return i;
}

static uint32_t floatBitsToUint(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float uintBitsToFloat(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* the product of two 32-bit words: (low word, high word) */
static uvec2 f64u_mul32(uint32_t a, uint32_t b)
{
    uint64_t p = (uint64_t)a * b;
    uvec2 r;
    r.x = (uint32_t)p;
    r.y = (uint32_t)(p >> 32);
    return r;
}

/* the int of the same bits */
static int f64u_int(uint32_t u)
{
    return (int)u;
}

#define uvec2(a, b) ((uvec2){(a), (b)})
#define uint(v) ((uint32_t)(v))
#define MLOD_F64_C
#include "../shaders/f64.glsl"
#undef uvec2
#undef uint

/* The uvec2 of two words (uvec2() is GLSL's, taken back above). */
static uvec2 f64t_pair(uint32_t lo, uint32_t hi)
{
    uvec2 r;
    r.x = lo;
    r.y = hi;
    return r;
}

/* ---- operands for the tests: doubles as bits, drawn to reach every path
   (random patterns, moderate and subnormal values, few-bit significands
   whose sums and products tie, the edges of the range, specials) ---- */

static uint64_t f64t_next(uint64_t *state) /* splitmix64 */
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static uint64_t f64t_specials(uint32_t i)
{
    static const uint64_t table[] = {
        0x0000000000000000ull, 0x8000000000000000ull, 0x7FF0000000000000ull, 0xFFF0000000000000ull,
        0x7FF8000000000000ull, 0x7FF0000000000001ull, 0x3FF0000000000000ull, 0xBFF0000000000000ull,
        0x7FEFFFFFFFFFFFFFull, 0x0010000000000000ull, 0x000FFFFFFFFFFFFFull, 0x0000000000000001ull,
        0x3FE0000000000000ull, 0x4000000000000000ull, 0x4008000000000000ull, 0x3FF0000000000001ull,
        0x3FEFFFFFFFFFFFFFull, 0x7FE0000000000000ull, 0x0020000000000000ull, 0x3CA0000000000000ull,
        0x41DFFFFFFFC00000ull, 0xC1E0000000000000ull, 0x47EFFFFFE0000000ull, 0x47EFFFFFF0000000ull,
        0x36A0000000000000ull, 0x3690000000000000ull, 0x380FFFFFE0000000ull, 0x3810000000000000ull};
    return table[i % (sizeof table / sizeof table[0])];
}

/* One operand of kind k (0 .. 6). */
static uint64_t f64t_operand(uint64_t *state, uint32_t k)
{
    uint64_t r = f64t_next(state), sign = r & 0x8000000000000000ull, frac = f64t_next(state) & 0xFFFFFFFFFFFFFull;
    uint64_t e;
    switch (k % 7) {
    case 0: return r;                                                          /* any pattern */
    case 1: e = 1000 + (r >> 8) % 47; return sign | e << 52 | frac;            /* moderate */
    case 2: return sign | frac;                                                /* subnormal */
    case 3: return f64t_specials((uint32_t)(r >> 16)) ^ (r & 1 ? sign : 0);    /* specials */
    case 4: /* few bits: ties */
        e = 1018 + (r >> 8) % 11;
        frac &= ~(0xFFFFFFFFFFFFFull >> (1 + (r >> 20) % 12));
        return sign | e << 52 | frac;
    case 5: e = (r >> 8) & 1 ? 2035 + (r >> 9) % 12 : (r >> 9) % 12; return sign | e << 52 | frac; /* range edges */
    default: e = 1023 + (r >> 8) % 3; return sign | e << 52 | (frac & 0xFFFFFFull); /* short, near 1 */
    }
}

/* A second operand close to a (cancellation, equal exponents) or of any kind. */
static uint64_t f64t_partner(uint64_t *state, uint64_t a, uint32_t k)
{
    uint64_t r = f64t_next(state);
    if (k % 3 == 0) return (a ^ (r & 1 ? 0x8000000000000000ull : 0)) + (r >> 60) - 8; /* a few ulps off +-a */
    return f64t_operand(state, (uint32_t)(r >> 32));
}

#endif
