/* tests/exact.h - exact arithmetic for the tests: an independent reference
   for the containment guarantees of manylods.h.

   Every finite float is m * 2^e with |m| < 2^24 and e in [-149, 104], so
   float * 2^149 is an integer below 2^278.  exact_int is a fixed-size
   two's complement integer of EXACT_WORDS 32-bit words (768 bits), enough
   for the squares and sums below (< 2^600).  Nothing here rounds. */
#ifndef MANYLODS_TEST_EXACT_H
#define MANYLODS_TEST_EXACT_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define EXACT_WORDS 24

typedef struct exact_int {
    uint32_t w[EXACT_WORDS]; /* little-endian words, two's complement */
} exact_int;

static inline exact_int exact_zero(void)
{
    exact_int a;
    memset(&a, 0, sizeof a);
    return a;
}

static inline int exact_is_negative(const exact_int *a) { return (a->w[EXACT_WORDS - 1] >> 31) != 0; }

static inline exact_int exact_add(exact_int a, exact_int b)
{
    exact_int r;
    uint64_t carry = 0;
    int i;
    for (i = 0; i < EXACT_WORDS; i++) {
        uint64_t s = (uint64_t)a.w[i] + b.w[i] + carry;
        r.w[i] = (uint32_t)s;
        carry = s >> 32;
    }
    return r;
}

static inline exact_int exact_neg(exact_int a)
{
    exact_int one = exact_zero();
    int i;
    for (i = 0; i < EXACT_WORDS; i++) a.w[i] = ~a.w[i];
    one.w[0] = 1;
    return exact_add(a, one);
}

static inline exact_int exact_sub(exact_int a, exact_int b) { return exact_add(a, exact_neg(b)); }

/* Product, exact as long as it fits (the callers stay below 2^700). */
static inline exact_int exact_mul(exact_int a, exact_int b)
{
    exact_int r = exact_zero();
    int neg = exact_is_negative(&a) != exact_is_negative(&b), i, j, na = EXACT_WORDS, nb = EXACT_WORDS;
    if (exact_is_negative(&a)) a = exact_neg(a);
    if (exact_is_negative(&b)) b = exact_neg(b);
    while (na > 0 && !a.w[na - 1]) na--;
    while (nb > 0 && !b.w[nb - 1]) nb--;
    for (i = 0; i < na; i++) {
        uint64_t carry = 0;
        if (!a.w[i]) continue;
        for (j = 0; j < nb && i + j < EXACT_WORDS; j++) {
            uint64_t t = (uint64_t)a.w[i] * b.w[j] + r.w[i + j] + carry;
            r.w[i + j] = (uint32_t)t;
            carry = t >> 32;
        }
        for (j = i + nb; carry && j < EXACT_WORDS; j++) {
            uint64_t t = (uint64_t)r.w[j] + carry;
            r.w[j] = (uint32_t)t;
            carry = t >> 32;
        }
    }
    return neg ? exact_neg(r) : r;
}

/* -1, 0, +1 as a <, =, > b (signed). */
static inline int exact_cmp(exact_int a, exact_int b)
{
    int na = exact_is_negative(&a), nb = exact_is_negative(&b), i;
    if (na != nb) return na ? -1 : 1;
    for (i = EXACT_WORDS - 1; i >= 0; i--)
        if (a.w[i] != b.w[i]) return a.w[i] < b.w[i] ? -1 : 1;
    return 0;
}

static inline exact_int exact_from_u64(uint64_t v)
{
    exact_int r = exact_zero();
    r.w[0] = (uint32_t)v;
    r.w[1] = (uint32_t)(v >> 32);
    return r;
}

static inline exact_int exact_shl(exact_int a, unsigned bits)
{
    exact_int r = exact_zero();
    unsigned word = bits / 32, off = bits % 32;
    int i;
    for (i = EXACT_WORDS - 1; i >= (int)word; i--) {
        uint64_t v = (uint64_t)a.w[i - word] << off;
        if (off && i - (int)word - 1 >= 0) v |= (uint64_t)a.w[i - word - 1] >> (32 - off);
        r.w[i] = (uint32_t)v;
    }
    return r;
}

/* f * 2^149 for a finite float f. */
static inline exact_int exact_from_float(float f)
{
    uint32_t bits, e, m;
    exact_int r;
    memcpy(&bits, &f, sizeof bits);
    e = (bits >> 23) & 0xffu;
    m = bits & 0x7fffffu;
    if (e) m |= 0x800000u;
    r = exact_shl(exact_from_u64(m), e ? e - 1 : 0);
    return (bits >> 31) ? exact_neg(r) : r;
}

static inline int exact_finite4(const float *v)
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]) && isfinite(v[3]);
}

/* sum_k (a_k - b_k)^2, scaled by 2^298. */
static inline exact_int exact_dist2(const float *a, const float *b)
{
    exact_int s = exact_zero();
    int k;
    for (k = 0; k < 3; k++) {
        exact_int d = exact_sub(exact_from_float(a[k]), exact_from_float(b[k]));
        s = exact_add(s, exact_mul(d, d));
    }
    return s;
}

/* Sphere outer = (x, y, z, r) contains sphere inner, in real arithmetic on
   the stored floats: r_o - r_i >= 0 and (r_o - r_i)^2 >= |c_o - c_i|^2. */
static inline int exact_sphere_contains(const float *outer, const float *inner)
{
    exact_int dr;
    if (!exact_finite4(outer) || !exact_finite4(inner)) return 0;
    dr = exact_sub(exact_from_float(outer[3]), exact_from_float(inner[3]));
    if (exact_is_negative(&dr)) return 0;
    return exact_cmp(exact_mul(dr, dr), exact_dist2(outer, inner)) >= 0;
}

/* The documented slack: r_o >= (d + r_i) (1 + 2^-20), d = |c_o - c_i|,
   i.e. t = 2^20 r_o - (2^20 + 1) r_i >= 0 and t^2 >= (2^20 + 1)^2 d^2. */
static inline int exact_sphere_contains_slack(const float *outer, const float *inner)
{
    exact_int k = exact_from_u64((UINT64_C(1) << 20) + 1), t;
    if (!exact_finite4(outer) || !exact_finite4(inner)) return 0;
    t = exact_sub(exact_shl(exact_from_float(outer[3]), 20), exact_mul(k, exact_from_float(inner[3])));
    if (exact_is_negative(&t)) return 0;
    return exact_cmp(exact_mul(t, t), exact_mul(exact_mul(k, k), exact_dist2(outer, inner))) >= 0;
}

/* Point p (3 floats) lies in the closed sphere s: r >= 0 and r^2 >= |p - c|^2. */
static inline int exact_point_in_sphere(const float *p, const float *s)
{
    exact_int r;
    if (!exact_finite4(s) || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) return 0;
    r = exact_from_float(s[3]);
    if (exact_is_negative(&r)) return 0;
    return exact_cmp(exact_mul(r, r), exact_dist2(p, s)) >= 0;
}

/* ------------------------------------------------------------- cones */

#define EXACT_PI 3.141592653589793238462643383279502884L

/* Angle between two (not necessarily unit) vectors, atan2(|a x b|, a.b) in
   long double: accurate to ~1e-18 rad for any angle. */
static inline long double exact_angle(const float *a, const float *b)
{
    long double c0 = (long double)a[1] * b[2] - (long double)a[2] * b[1];
    long double c1 = (long double)a[2] * b[0] - (long double)a[0] * b[2];
    long double c2 = (long double)a[0] * b[1] - (long double)a[1] * b[0];
    long double dot = (long double)a[0] * b[0] + (long double)a[1] * b[1] + (long double)a[2] * b[2];
    return atan2l(sqrtl(c0 * c0 + c1 * c1 + c2 * c2), dot);
}

/* Cone outer = (axis, half-angle) contains cone inner with slack radians to
   spare: angle + alpha_inner + slack <= alpha_outer, or alpha_outer >= pi. */
static inline int exact_cone_contains(const float *outer, const float *inner, long double slack)
{
    if (!exact_finite4(outer) || !exact_finite4(inner)) return 0;
    if ((long double)outer[3] >= EXACT_PI) return 1;
    return exact_angle(outer, inner) + (long double)inner[3] + slack <= (long double)outer[3];
}

/* The same, fast: a double filter decides the clear cases (a margin far
   above its rounding), exact arithmetic the rest. */
static inline int exact_sphere_contains_filtered(const float *outer, const float *inner)
{
    if (exact_finite4(outer) && exact_finite4(inner)) {
        double dx = (double)outer[0] - inner[0], dy = (double)outer[1] - inner[1], dz = (double)outer[2] - inner[2];
        double d = sqrt(dx * dx + dy * dy + dz * dz), need = (d + inner[3]) * (1.0 + 1.0 / 1048576.0);
        double margin = outer[3] - need, size = outer[3] + d + inner[3];
        if (isfinite(size) && margin > 1e-12 * size) return 1;
    }
    return exact_sphere_contains_slack(outer, inner);
}

#endif /* MANYLODS_TEST_EXACT_H */
