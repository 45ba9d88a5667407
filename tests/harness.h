/* tests/harness.h - the tiny test harness shared by every test program.

   CHECK(cond, fmt, ...) counts one check; a failing check prints where and
   why.  Each program ends with test_finish(), which prints the plain line
   "N passed, M failed" and returns the exit code; tests/run.sh adds up the
   lines of all programs. */
#ifndef MANYLODS_TEST_HARNESS_H
#define MANYLODS_TEST_HARNESS_H

#include <stdio.h>
#include <stdarg.h>

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

static int test_finish(void)
{
    printf("%lu passed, %lu failed\n", test_passed_count, test_failed_count);
    fflush(stdout); /* LeakSanitizer's exit report would drop a buffered line */
    return test_failed_count ? 1 : 0;
}

#endif
