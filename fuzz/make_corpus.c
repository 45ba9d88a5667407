/* fuzz/make_corpus.c - writes the seed corpus of fuzz/fuzz_pipeline.c.

     cc -std=c99 fuzz/make_corpus.c -o make_corpus && ./make_corpus fuzz/corpus

   Each seed is the harness's header (flags byte, the failing allocation
   when bit 4 asks for one, the chaos bytes of geometry and views, the
   extension byte and, when its bit 2 asks for failures, their two bytes)
   followed by bytes of a fixed generator: the harness reads every field
   from them.
   The tail seeds below were picked so that each input runs the whole
   pipeline (build, refit, every cut mode, splat) on the success path; run
   the harness with MANYLODS_FUZZ_VERBOSE=1 on the corpus to see it. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

typedef struct seed {
    const char *name;
    uint8_t flags; /* bits as in fuzz_pipeline.c */
    uint8_t fail;  /* which allocation fails, when flags bit 4 is set */
    uint8_t chaos, view_chaos;
    uint8_t ext;      /* extension bits as in fuzz_pipeline.c (FZ_EXT_*) */
    uint8_t failures; /* when ext bit 2: every (2 + low nibble)-th allocation fails, 1 + high nibble times, */
    uint8_t after;    /* after this many */
    uint64_t tail;    /* generator seed of the remaining bytes */
    unsigned length;
} seed;

static const seed seeds[] = {
    {"mesh-sane", 0x06, 0, 0, 0, 0, 0, 0, 1, 1200},
    {"points-sane", 0x07, 0, 0, 0, 0, 0, 0, 2, 1600},
    {"mesh-hook", 0x0e, 0, 0, 0, 0, 0, 0, 3, 1200},
    {"mesh-normals-colours", 0x66, 0, 0, 0, 0, 0, 0, 4, 3000},
    {"points-normals-colours-radii", 0xe7, 0, 0, 0, 0, 0, 0, 5, 4000},
    {"mesh-hook-normals", 0x2e, 0, 0, 0, 0, 0, 0, 6, 2400},
    {"mesh-failing-allocation", 0x16, 60, 0, 0, 0, 0, 0, 7, 1200},
    {"mesh-raw-geometry", 0x04, 0, 0, 0, 0, 0, 0, 8, 1500},
    {"mesh-raw-views", 0x02, 0, 0, 0, 0, 0, 0, 9, 1500},
    {"points-raw-views", 0x03, 0, 0, 2, 0, 0, 0, 10, 1500},
    {"mesh-raw-low-chaos", 0x00, 0, 1, 1, 0, 0, 0, 15, 2000},
    {"points-colours-hook", 0x4f, 0, 0, 0, 0, 0, 0, 12, 2500},
    /* the extension byte */
    {"mesh-strides", 0x66, 0, 0, 0, 0x01, 0, 0, 100, 3000},
    {"points-strides", 0xe7, 0, 0, 0, 0x01, 0, 0, 100, 4000},
    {"mesh-raw-strides", 0x64, 0, 4, 0, 0x01, 0, 0, 102, 3000},
    {"points-raw-strides", 0xe5, 0, 4, 0, 0x01, 0, 0, 100, 4000},
    {"mesh-disc-scale", 0x06, 0, 0, 0, 0x02, 0, 0, 113, 1500},
    {"mesh-every-3rd-allocation-fails-4-times", 0x06, 0, 0, 0, 0x04, 0x31, 20, 102, 1500},
    {"points-every-2nd-allocation-fails-16-times", 0x0f, 0, 0, 0, 0x04, 0xf0, 40, 100, 1600},
    {"mesh-large", 0x06, 0, 0, 0, 0x78, 0, 0, 101, 1500},
    {"points-large", 0x07, 0, 0, 0, 0x78, 0, 0, 100, 1600},
    {"mesh-large-hook", 0x0e, 0, 0, 0, 0x78, 0, 0, 102, 1500},
    {"mesh-raw-views-helpers", 0x02, 0, 0, 0, 0x02, 0, 0, 101, 1500},
    {"mesh-everything", 0x6e, 0, 0, 0, 0x7f, 0x42, 60, 104, 3000},
    {"mesh-reserved-cut", 0x06, 0, 0, 0, 0x80, 0, 0, 105, 1500},
    {"mesh-reserved-cut-failing", 0x0e, 0, 0, 0, 0x84, 0x11, 8, 106, 1500},
    /* cube maps (view kind bytes 0xc0 .. 0xff): tails picked for several
       cube views each; the raw ones have invalid cube maps (two of three;
       one of two, its tile 10 x 4) */
    {"mesh-cube-maps", 0x06, 0, 0, 0, 0, 0, 0, 222, 1500},
    {"mesh-normals-cube-maps", 0x66, 0, 0, 0, 0, 0, 0, 529, 3000},
    {"points-raw-cube-maps", 0x03, 0, 0, 24, 0, 0, 0, 306, 1600},
    {"mesh-low-chaos-cube-maps", 0x02, 0, 0, 4, 0, 0, 0, 604, 1500},
    {"mesh-large-cube-maps", 0x06, 0, 0, 0, 0x78, 0, 0, 413, 1500},
};

static uint64_t next(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

int main(int argc, char **argv)
{
    size_t i;
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIRECTORY\n", argv[0]);
        return 2;
    }
    for (i = 0; i < sizeof seeds / sizeof seeds[0]; i++) {
        const seed *s = &seeds[i];
        char path[1024];
        uint64_t state = s->tail;
        unsigned k;
        FILE *f;
        snprintf(path, sizeof path, "%s/seed-%02u-%s", argv[1], (unsigned)(i + 1), s->name);
        f = fopen(path, "wb");
        if (!f) {
            perror(path);
            return 1;
        }
        fputc(s->flags, f);
        if (s->flags & 16) fputc(s->fail, f);
        fputc(s->chaos, f);
        fputc(s->view_chaos, f);
        fputc(s->ext, f);
        if (s->ext & 4) {
            fputc(s->failures, f);
            fputc(s->after, f);
        }
        for (k = 0; k < s->length; k++) fputc((int)(next(&state) >> 56), f);
        if (fclose(f) != 0) {
            perror(path);
            return 1;
        }
    }
    return 0;
}
