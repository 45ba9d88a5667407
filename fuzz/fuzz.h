/* fuzz/fuzz.h - what every libFuzzer harness of fuzz/ shares: reporting a
   broken invariant (the harness aborts, so libFuzzer keeps the input) and
   the verbose switch MANYLODS_FUZZ_VERBOSE (set: each input says how far it
   got), and, after manylods.h, comparing two atlases.  Include it once, in
   the harness. */
#ifndef MANYLODS_FUZZ_H
#define MANYLODS_FUZZ_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

/* 1 when MANYLODS_FUZZ_VERBOSE is set (read once, on first use). */
static int fz_verbose_flag = -1;
static int fz_verbose(void)
{
    if (fz_verbose_flag < 0) fz_verbose_flag = getenv("MANYLODS_FUZZ_VERBOSE") != NULL;
    return fz_verbose_flag;
}

/* Progress for a verbose replay. */
#define FZ_NOTE(...)                                                                                                   \
    do {                                                                                                               \
        if (fz_verbose()) fprintf(stderr, __VA_ARGS__);                                                                \
    } while (0)

/* Report a broken invariant and abort. */
static void fz_fail(const char *file, int line, const char *fmt, ...)
{
    va_list args;
    fprintf(stderr, "\nmanylods fuzz: invariant broken at %s:%d: ", file, line);
    va_start(args, fmt);
    vfprintf(stderr, fmt, args);
    va_end(args);
    fputc('\n', stderr);
    abort();
}
#define FZ_REQUIRE(cond, ...)                                                                                          \
    do {                                                                                                               \
        if (!(cond)) fz_fail(__FILE__, __LINE__, __VA_ARGS__);                                                         \
    } while (0)

#ifdef MANYLODS_H
#include <string.h>
/* Two atlases of the same layout hold the same bits: depth, and each
   channel the first has (harnesses included after manylods.h). */
static inline int fz_same_atlas(const mlod_atlas *a, const mlod_atlas *b)
{
    size_t pixels = (size_t)a->width * a->height;
    return a->width == b->width && a->height == b->height &&
           memcmp(a->depth, b->depth, pixels * sizeof(float)) == 0 &&
           (!a->normal || (b->normal && memcmp(a->normal, b->normal, 3 * pixels * sizeof(float)) == 0)) &&
           (!a->color || (b->color && memcmp(a->color, b->color, 3 * pixels * sizeof(float)) == 0));
}
#endif

#endif
