/* bench/cut_avx2.c - the library compiled a second time, privately
   (MANYLODS_STATIC), with the flags the Makefile gives this file
   (-mavx2 -mfma: the cut's, the splat's and MegaViews' float filters in 8
   lanes); see cut_avx2.h. */
#define MANYLODS_STATIC
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "cut_avx2.h"

#include <stdlib.h>

struct bench_avx2_cut {
    mlod_cut *cut;
};

int bench_avx2_supported(void)
{
#if defined(__AVX2__) && defined(__FMA__) && defined(MLOD__VLANES) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    return 0;
#endif
}

int bench_avx2_lanes(void)
{
#ifdef MLOD__VLANES
    return MLOD__VLANES;
#else
    return 0;
#endif
}

bench_avx2_cut *bench_avx2_cut_create(uint32_t view_count)
{
    bench_avx2_cut *c = (bench_avx2_cut *)malloc(sizeof *c);
    if (c && mlod_cut_create(view_count, NULL, &c->cut, NULL) != MLOD_OK) {
        free(c);
        c = NULL;
    }
    return c;
}

mlod_result bench_avx2_cut_update(bench_avx2_cut *cut, const mlod_tree *tree, const mlod_view *views,
                                  const mlod_cut_params *params, mlod_error *error)
{
    return mlod_cut_update(cut->cut, tree, views, params, error);
}

mlod_result bench_avx2_splat(const bench_avx2_cut *cut, mlod_atlas *atlas, const mlod_tree *tree,
                             const mlod_view *views, const mlod_parallel *parallel, mlod_error *error)
{
    mlod_atlas_invalidate(atlas); /* a full splat, as the bench times this build's */
    return mlod_splat(atlas, tree, cut->cut, views, parallel, error);
}

mlod_result bench_avx2_megaviews_render(mlod_atlas *atlas, const mlod_tree *scene, const mlod_view_tree *views,
                                        const mlod_megaviews_params *params, mlod_megaviews_stats *stats,
                                        mlod_error *error)
{
    return mlod_megaviews_render(atlas, scene, views, params, stats, error);
}

uint64_t bench_avx2_cut_hash(const bench_avx2_cut *cut)
{
    uint64_t h = 1469598103934665603ull;
    uint32_t v;
    for (v = 0; v < mlod_cut_view_count(cut->cut); v++) h = bench_hash_cut_view(h, mlod_cut_get(cut->cut, v));
    return h;
}

void bench_avx2_cut_destroy(bench_avx2_cut *cut)
{
    if (!cut) return;
    mlod_cut_destroy(cut->cut);
    free(cut);
}
