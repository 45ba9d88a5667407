/* examples/progress.h - the examples' clock and their progress lines.

     double app_now_ms(void);                  monotonic wall time, ms
     void app_stage(const char *format, ...);  "[  3.2 s] what starts now"

   app_stage prints one line to stderr as a stage begins, with the wall time
   elapsed since the program's first app_stage, and flushes it: a long run
   shows where it is even when its output goes to a pipe or a file (stdout,
   with the results, is left as it is).  Call it from one thread.
   C99 (and C++), header-only; POSIX clock_gettime: define
   _POSIX_C_SOURCE 200809L before any system header. */
#ifndef MANYLODS_EXAMPLES_PROGRESS_H
#define MANYLODS_EXAMPLES_PROGRESS_H

#include <stdarg.h>
#include <stdio.h>
#include <time.h>

static inline double app_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* One progress line on stderr: the seconds since the first call, then the
   printf-formatted text. */
#if defined(__GNUC__)
static inline void app_stage(const char *format, ...) __attribute__((format(printf, 1, 2)));
#endif
static inline void app_stage(const char *format, ...)
{
    static double start_ms = -1.0;
    double now = app_now_ms();
    va_list args;
    if (start_ms < 0.0) start_ms = now;
    fprintf(stderr, "[%6.1f s] ", (now - start_ms) * 1e-3);
    va_start(args, format);
    vfprintf(stderr, format, args);
    va_end(args);
    fputc('\n', stderr);
    fflush(stderr);
}

#endif /* MANYLODS_EXAMPLES_PROGRESS_H */
