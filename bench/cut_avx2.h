/* bench/cut_avx2.h - the cut, splat and MegaViews of a second, private copy of the library
   compiled with -mavx2 -mfma (bench/cut_avx2.c), for the Targets row that
   says what those flags buy on the same frames as the portable build.  The
   tree and the parallel hook are the main copy's: plain data and a
   function pointer, which both copies read alike. */
#ifndef BENCH_CUT_AVX2_H
#define BENCH_CUT_AVX2_H

#include "../manylods.h"

typedef struct bench_avx2_cut bench_avx2_cut;

/* h folded with one view's cut, node and status in order (FNV-1a): equal
   hashes of every view, equal cuts. */
static inline uint64_t bench_hash_cut_view(uint64_t h, mlod_cut_view cv)
{
    uint32_t j;
    for (j = 0; j < cv.count; j++) {
        h = (h ^ cv.nodes[j]) * 1099511628211ull;
        h = (h ^ cv.status[j]) * 1099511628211ull;
    }
    return h;
}

/* 1 when this processor runs AVX2 and FMA code (and this copy was built
   with them), else 0. */
int bench_avx2_supported(void);
/* The lanes of this copy's float filter (8). */
int bench_avx2_lanes(void);
/* A cut for view_count views of this copy, or NULL. */
bench_avx2_cut *bench_avx2_cut_create(uint32_t view_count);
/* mlod_cut_update of this copy; fills error on failure. */
mlod_result bench_avx2_cut_update(bench_avx2_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                  const mlod_cut_params *params, mlod_error *error);
/* mlod_splat of this copy, of its cut, into an atlas of the main copy
   (plain data); fills error on failure. */
mlod_result bench_avx2_splat(const bench_avx2_cut *cut, mlod_atlas *atlas, const mlod_tree *tree,
                             const mlod_view *views, const mlod_parallel *parallel, mlod_error *error);
/* mlod_megaviews_render of this copy, over the main copy's trees, into an
   atlas of the main copy; fills error on failure. */
mlod_result bench_avx2_megaviews_render(mlod_atlas *atlas, const mlod_tree *scene, const mlod_view_tree *views,
                                        const mlod_megaviews_params *params, mlod_megaviews_stats *stats,
                                        mlod_error *error);
/* bench_hash_cut_view over every view, from 1469598103934665603. */
uint64_t bench_avx2_cut_hash(const bench_avx2_cut *cut);
void bench_avx2_cut_destroy(bench_avx2_cut *cut);

#endif
