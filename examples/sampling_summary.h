/* examples/sampling_summary.h - the summary that instant_radiosity
   --sampling prints at its end, written and read by one definition: the
   example prints it (sampling_summary_print), tests/check_examples.c and
   the benchmark's Targets table (bench/protocol_targets.c) read it back
   from the example's output (sampling_summary_read).  Header-only, C99,
   functions static inline, named sampling_summary_...

   Two lines, the figures per frame averaged over frames 1 .. F (frame 0
   cuts every view from the root):
     "sampling summary: ..."  for each sampler, [0] the inverse transform
                              and [1] Metropolis-Hastings: the share of the
                              VPLs whose view is the previous frame's,
                              flicker and error (percent), incremental cut
                              and splat (ms), tiles drawn again (percent);
     "Metropolis-Hastings' incremental cut + kept maps against ..."
                              Metropolis-Hastings' cut + splat (ms) against
                              a basic cut from the root and a full splat of
                              the same VPLs, and in how many of the F + 1
                              frames the two atlases were equal bit for
                              bit. */
#ifndef SAMPLING_SUMMARY_H
#define SAMPLING_SUMMARY_H

#include <stdio.h>
#include <string.h>

typedef struct sampling_summary {
    double kept[2], flicker[2], error[2]; /* percent */
    double cut_ms[2], splat_ms[2];        /* ms per frame */
    double redrawn[2];                    /* percent of the tiles drawn again, whole or patched */
    double ms, anchor_ms;                 /* Metropolis-Hastings' cut + splat, the basic cut + full splat */
    unsigned same, frames;                /* frames with equal atlases, of frames 0 .. F */
} sampling_summary;

/* The two lines into out. */
static inline void sampling_summary_print(FILE *out, const sampling_summary *s)
{
    fprintf(out,
            "sampling summary: kept %.1f %% vs %.1f %%, flicker %.2f %% vs %.2f %%, error %.2f %% vs %.2f %%,"
            " cut %.1f ms vs %.1f ms, splat %.1f ms vs %.1f ms, tiles redrawn %.1f %% vs %.1f %%"
            " (inverse transform vs Metropolis-Hastings)\n",
            s->kept[0], s->kept[1], s->flicker[0], s->flicker[1], s->error[0], s->error[1], s->cut_ms[0], s->cut_ms[1],
            s->splat_ms[0], s->splat_ms[1], s->redrawn[0], s->redrawn[1]);
    fprintf(out,
            "Metropolis-Hastings' incremental cut + kept maps against a basic cut + full splat of its VPLs: %.1f "
            "against %.1f ms a frame (%.2fx); the same maps in %u of %u frames (the basic cut from the root, "
            "every view evaluated)\n",
            s->ms, s->anchor_ms, s->ms / s->anchor_ms, s->same, s->frames);
}

/* Read one line of the example's output into s: 1 for the first line of
   the summary, 2 for the second, 0 for any other line (s then as it was,
   but for fields a line that did not match in full may have set). */
static inline int sampling_summary_read(const char *line, sampling_summary *s)
{
    const char *at;
    if ((at = strstr(line, "sampling summary: ")) != NULL &&
        sscanf(at, "sampling summary: kept %lf %% vs %lf %%, flicker %lf %% vs %lf %%, error %lf %% vs %lf %%,"
                   " cut %lf ms vs %lf ms, splat %lf ms vs %lf ms, tiles redrawn %lf %% vs %lf %%",
               &s->kept[0], &s->kept[1], &s->flicker[0], &s->flicker[1], &s->error[0], &s->error[1], &s->cut_ms[0],
               &s->cut_ms[1], &s->splat_ms[0], &s->splat_ms[1], &s->redrawn[0], &s->redrawn[1]) == 12)
        return 1;
    if ((at = strstr(line, "Metropolis-Hastings' incremental cut + kept maps against a basic cut + full splat of its "
                           "VPLs: ")) != NULL &&
        sscanf(at, "Metropolis-Hastings' incremental cut + kept maps against a basic cut + full splat of its VPLs: %lf "
                   "against %lf ms a frame (%*fx); the same maps in %u of %u frames",
               &s->ms, &s->anchor_ms, &s->same, &s->frames) == 4)
        return 2;
    return 0;
}

#endif
