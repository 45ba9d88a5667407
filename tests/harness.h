/* tests/harness.h - the tiny test harness shared by every test program.

   CHECK(cond, fmt, ...) counts one check; a failing check prints where and
   why.  Each program ends with test_finish(), which prints the plain line
   "N passed, M failed" and returns the exit code; tests/run.sh adds up the
   lines of all programs.

   TEST_GROUP(name, call) runs one group of checks when the program was
   given no arguments or names it (test_groups_begin(argc, argv) first,
   test_groups_end() before test_finish(): one check that every name given
   ran); TEST_TIMES=1 in the environment prints each group's processor
   time. */
#ifndef MANYLODS_TEST_HARNESS_H
#define MANYLODS_TEST_HARNESS_H

#include <stdio.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static unsigned long test_passed_count, test_failed_count;

static void test_report(int ok, const char *file, int line, const char *fmt, ...)
{
    va_list args;
    if (ok) {
        test_passed_count++;
        return;
    }
    test_failed_count++;
    if (test_failed_count > 50) return; /* the count still says how many */
    fprintf(stderr, "FAIL %s:%d: ", file, line);
    va_start(args, fmt);
    vfprintf(stderr, fmt, args);
    va_end(args);
    fputc('\n', stderr);
}

/* CHECK(condition, printf-style message describing what was expected) */
#define CHECK(cond, ...) test_report((cond) ? 1 : 0, __FILE__, __LINE__, __VA_ARGS__)

static int test_group_argc, test_groups_ran;
static char **test_group_argv;

static inline void test_groups_begin(int argc, char **argv)
{
    test_group_argc = argc;
    test_group_argv = argv;
}

static inline int test_group_selected(const char *name)
{
    int i;
    if (test_group_argc < 2) return 1;
    for (i = 1; i < test_group_argc; i++)
        if (strcmp(test_group_argv[i], name) == 0) return 1;
    return 0;
}

#define TEST_GROUP(name, call)                                                                                         \
    do {                                                                                                               \
        clock_t start_ = clock();                                                                                      \
        if (!test_group_selected(name)) break;                                                                         \
        call;                                                                                                          \
        test_groups_ran++;                                                                                             \
        if (getenv("TEST_TIMES")) printf("  %-24s %.2f s\n", name, (double)(clock() - start_) / CLOCKS_PER_SEC);       \
    } while (0)

static inline void test_groups_end(void)
{
    if (test_group_argc >= 2)
        CHECK(test_groups_ran == test_group_argc - 1, "every group named ran (%d of %d)", test_groups_ran,
              test_group_argc - 1);
}

static int test_finish(void)
{
    printf("%lu passed, %lu failed\n", test_passed_count, test_failed_count);
    fflush(stdout); /* LeakSanitizer's exit report would drop a buffered line */
    return test_failed_count ? 1 : 0;
}

#endif
