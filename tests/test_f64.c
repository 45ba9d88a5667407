/* tests/test_f64.c - shaders/f64.glsl, compiled as C (tests/f64_c.h),
   against the host's own doubles: every operation gives the same bits
   (NaN for NaN) over millions of operands drawn to reach every path
   (tests/f64_c.h: f64t_operand).  The host is the reference: an x86-64 or
   AArch64 double rounds to nearest, ties to even, subnormals kept.
   tests/test_f64_vulkan.c runs the same file as GLSL on a Vulkan device. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "harness.h"
#include "f64_c.h"

static double from_bits(uint64_t b)
{
    double d;
    memcpy(&d, &b, sizeof d);
    return d;
}

static uint64_t bits(double d)
{
    uint64_t b;
    memcpy(&b, &d, sizeof b);
    return b;
}

static uvec2 to_u(double d) { return f64t_pair((uint32_t)bits(d), (uint32_t)(bits(d) >> 32)); }
static double to_d(uvec2 u) { return from_bits((uint64_t)u.y << 32 | u.x); }

/* the same bits, or both NaN */
static int same(double got, double want)
{
    return (isnan(got) && isnan(want)) || bits(got) == bits(want);
}

typedef struct tally {
    const char *name;
    unsigned long count, wrong;
    char first[200];
} tally;

static void tally_init(tally *t, const char *name)
{
    memset(t, 0, sizeof *t);
    t->name = name;
}

static void note(tally *t, int ok, double a, double b, double got, double want)
{
    t->count++;
    if (ok) return;
    if (!t->wrong++)
        snprintf(t->first, sizeof t->first, "%a, %a: %a (0x%016llx), the host %a (0x%016llx)", a, b, got,
                 (unsigned long long)bits(got), want, (unsigned long long)bits(want));
}

static void report(const tally *t)
{
    CHECK(t->wrong == 0 && t->count > 0, "%s: %lu of %lu differ from the host; first: %s", t->name, t->wrong, t->count,
          t->first);
}

int main(int argc, char **argv)
{
    unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 2000000ul, i;
    uint64_t state = 0x5EEDF64ull;
    tally add, sub, mul, dv, sq, cmp, tof, fromf, fromi, toi, rnd;
    tally_init(&add, "add");
    tally_init(&sub, "sub");
    tally_init(&mul, "mul");
    tally_init(&dv, "div");
    tally_init(&sq, "sqrt");
    tally_init(&cmp, "lt, le, eq");
    tally_init(&tof, "to float");
    tally_init(&fromf, "from float");
    tally_init(&fromi, "from int, from uint");
    tally_init(&toi, "to int");
    tally_init(&rnd, "floor, ceil");
    for (i = 0; i < n; i++) {
        uint32_t k = (uint32_t)(i % 7);
        double a = from_bits(f64t_operand(&state, k)), b = from_bits(f64t_partner(&state, bits(a), (uint32_t)(i / 7)));
        uvec2 ua = to_u(a), ub = to_u(b);
        note(&add, same(to_d(f64_add(ua, ub)), a + b), a, b, to_d(f64_add(ua, ub)), a + b);
        note(&sub, same(to_d(f64_sub(ua, ub)), a - b), a, b, to_d(f64_sub(ua, ub)), a - b);
        note(&mul, same(to_d(f64_mul(ua, ub)), a * b), a, b, to_d(f64_mul(ua, ub)), a * b);
        note(&dv, same(to_d(f64_div(ua, ub)), a / b), a, b, to_d(f64_div(ua, ub)), a / b);
        note(&sq, same(to_d(f64_sqrt(ua)), sqrt(a)), a, 0.0, to_d(f64_sqrt(ua)), sqrt(a));
        note(&rnd, same(to_d(f64_floor(ua)), floor(a)) && same(to_d(f64_ceil(ua)), ceil(a)), a, 0.0,
             to_d(f64_floor(ua)), floor(a));
        note(&cmp, f64_lt(ua, ub) == (a < b) && f64_le(ua, ub) == (a <= b) && f64_eq(ua, ub) == (a == b), a, b,
             f64_lt(ua, ub) + 2 * f64_le(ua, ub) + 4 * f64_eq(ua, ub), (a < b) + 2 * (a <= b) + 4 * (a == b));
        {
            float want = (float)a, got = f64_to_float(ua);
            note(&tof, (isnan(got) && isnan(want)) || floatBitsToUint(got) == floatBitsToUint(want), a, 0.0, got, want);
        }
        {
            uint64_t r = f64t_next(&state);
            float f = uintBitsToFloat((uint32_t)r);
            int32_t si = (int32_t)(r >> 32);
            uint32_t ui = (uint32_t)(r >> 32) >> (r & 31);
            note(&fromf, same(to_d(f64_from_float(f)), (double)f), f, 0.0, to_d(f64_from_float(f)), (double)f);
            note(&fromi, same(to_d(f64_from_int(si)), (double)si) && same(to_d(f64_from_uint(ui)), (double)ui), si, ui,
                 to_d(f64_from_int(si)), (double)si);
        }
        if (fabs(a) < 2147483648.0) note(&toi, f64_to_int(ua) == (int)a, a, 0.0, f64_to_int(ua), (int)a);
    }
    {
        /* every float exponent, and the extremes of int */
        int32_t edge[] = {0, 1, -1, 2147483647, -2147483647 - 1};
        for (i = 0; i < 5; i++)
            note(&fromi, same(to_d(f64_from_int(edge[i])), (double)edge[i]), edge[i], 0.0, to_d(f64_from_int(edge[i])),
                 (double)edge[i]);
        for (i = 0; i < 512; i++) {
            float f = uintBitsToFloat((uint32_t)i << 23 | (uint32_t)(f64t_next(&state) & 0x7FFFFF));
            note(&fromf, same(to_d(f64_from_float(f)), (double)f), f, 0.0, to_d(f64_from_float(f)), (double)f);
        }
    }
    report(&add);
    report(&sub);
    report(&mul);
    report(&dv);
    report(&sq);
    report(&cmp);
    report(&tof);
    report(&fromf);
    report(&fromi);
    report(&toi);
    report(&rnd);
    printf("f64.glsl as C: %lu operand pairs, add, sub, mul, div, sqrt, floor, ceil, comparisons and conversions against the host\n",
           n);
    return test_finish();
}
