/* tests/test_simd.c - every vector level in one process: mlod_simd_limit
   steps through the levels the build compiled and the processor runs
   (none, SSE2 or NEON, AVX2, AVX-512), and at each one the cut in every mode, the
   splat (sphere and tangent discs, whole and half discs), Imperfect Shadow
   Maps and MegaViews must give the bits that the scalar level
   (MLOD_SIMD_NONE: no float lanes, the float filter one node at a time)
   gives.  The level the library picks is checked against the compiler's
   own processor test (__builtin_cpu_supports), not the library's cpuid
   code. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "harness.h"
#include "testutil.h"

static mlod_pool *simd_pool;
static mlod_parallel simd_parallel;
static mlod_simd simd_levels[5];
static int simd_level_count;

static const char *level_name(mlod_simd level)
{
    static const char *const names[5] = {"none", "SSE2", "NEON", "AVX2", "AVX-512"};
    return (int)level >= 0 && (int)level < 5 ? names[level] : "?";
}

/* The level the library must pick without a limit: the highest one the
   build compiled that this processor runs, by the compiler's test. */
static mlod_simd expected_best(void)
{
#if MLOD__BASE_LEVEL == 1 && MLOD__DISPATCH_AVX2
    __builtin_cpu_init();
    if (MLOD__DISPATCH_AVX512 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw"))
        return MLOD_SIMD_AVX512;
    return __builtin_cpu_supports("avx2") ? MLOD_SIMD_AVX2 : MLOD_SIMD_SSE2;
#else
    return (mlod_simd)MLOD__BASE_LEVEL;
#endif
}

/* The distinct levels that limits none .. AVX2 give, in order. */
static void find_levels(void)
{
    int l, k;
    simd_level_count = 0;
    for (l = MLOD_SIMD_NONE; l <= MLOD_SIMD_AVX512; l++) {
        mlod_simd got = mlod_simd_limit((mlod_simd)l);
        for (k = 0; k < simd_level_count && simd_levels[k] != got; k++) continue;
        if (k == simd_level_count) simd_levels[simd_level_count++] = got;
    }
    mlod_simd_limit(MLOD_SIMD_AVX512);
}

static void test_levels(void)
{
    int l, k;
    mlod_simd best = expected_best();
    CHECK(mlod_simd_limit(MLOD_SIMD_NONE) == MLOD_SIMD_NONE, "the limit none gives none");
    CHECK(mlod_simd_level() == MLOD_SIMD_NONE, "the level query follows the limit");
    CHECK(mlod_simd_limit((mlod_simd)99) == best, "no limit: the best level, %s (got %s)", level_name(best),
          level_name(mlod_simd_level()));
    CHECK(mlod_simd_level() == best, "the level query: %s", level_name(mlod_simd_level()));
    CHECK(mlod_simd_limit((mlod_simd)-5) == MLOD_SIMD_NONE, "a limit below none gives none");
    for (l = MLOD_SIMD_NONE; l <= MLOD_SIMD_AVX512; l++) {
        mlod_simd got = mlod_simd_limit((mlod_simd)l);
        CHECK(got <= (mlod_simd)l && got <= best, "limit %s: level %s, at most the limit and the best",
              level_name((mlod_simd)l), level_name(got));
    }
    CHECK(simd_levels[0] == MLOD_SIMD_NONE, "the first level is none");
    CHECK(simd_levels[simd_level_count - 1] == best, "the last level is the best");
    CHECK(simd_level_count == (MLOD__BASE_LEVEL == 0 ? 1
                               : MLOD__BASE_LEVEL == 1 ? (best == MLOD_SIMD_AVX512 ? 4 : best == MLOD_SIMD_AVX2 ? 3 : 2)
                                                       : 2),
          "levels: %d", simd_level_count);
    mlod_simd_limit(MLOD_SIMD_AVX512);
    printf("  levels run:");
    for (k = 0; k < simd_level_count; k++) printf(" %s", level_name(simd_levels[k]));
    printf("\n");
}

#define SIMD_VIEWS 48

/* Views of every kind around the scene, and the two shapes the cut's lanes
   take with constants (a paraboloid light, a perspective frustum, eye in
   floats), each frame moved a little. */
static void make_views(const double *c, double R, int frame, mlod_view *views)
{
    uint64_t rng = 7;
    uint32_t v;
    for (v = 0; v < SIMD_VIEWS; v++) {
        mlod_view_kind kind = (mlod_view_kind)(v % 5);
        views[v] = tu_random_view(&rng, kind, c, R);
        if (v % 3 == 0 && (kind == MLOD_VIEW_PARABOLOID || kind == MLOD_VIEW_PERSPECTIVE)) {
            views[v].flags = MLOD_VIEW_CULL_BACKFACES;
            views[v].width = views[v].height = 32;
        }
        views[v].position[0] += (float)(0.01 * R * frame);
        views[v].position[1] -= (float)(0.005 * R * frame);
    }
}

static void test_cuts(const mlod_tree *tree, const double *c, double R)
{
    static const mlod_cut_mode modes[3] = {MLOD_CUT_BASIC, MLOD_CUT_INCREMENTAL, MLOD_CUT_LAZY};
    static const float epsilons[2] = {1.0f, 4.0f};
    mlod_view before[SIMD_VIEWS], views[SIMD_VIEWS];
    int m, e, k, call;
    make_views(c, R, 0, before);
    make_views(c, R, 1, views);
    for (m = 0; m < 3; m++)
        for (e = 0; e < 2; e++) {
            mlod_cut *ref = NULL; /* level none's */
            for (k = 0; k < simd_level_count; k++) {
                mlod_cut *cut = NULL;
                mlod_cut_params p;
                mlod_error err;
                int ok = 1;
                uint32_t v, total = 0, differs = UINT32_MAX;
                memset(&p, 0, sizeof p);
                p.epsilon = epsilons[e];
                p.parallel = &simd_parallel;
                p.lazy_steps = 1;
                mlod_simd_limit(simd_levels[k]);
                if (mlod_cut_create(SIMD_VIEWS, NULL, &cut, &err) != MLOD_OK) {
                    CHECK(0, "cut create: %s", err.message);
                    return;
                }
                /* another frame's cut first, so that incremental and lazy start from it */
                p.mode = MLOD_CUT_BASIC;
                ok &= mlod_cut_update(cut, tree, before, &p, &err) == MLOD_OK;
                p.mode = modes[m];
                for (call = 0; call < (modes[m] == MLOD_CUT_LAZY ? 3 : 1); call++)
                    ok &= mlod_cut_update(cut, tree, views, &p, &err) == MLOD_OK;
                CHECK(ok, "cut update at level %s: %s", level_name(simd_levels[k]), ok ? "" : err.message);
                if (k == 0) {
                    for (v = 0; v < SIMD_VIEWS; v++) total += mlod_cut_get(cut, v).count;
                    CHECK(total > SIMD_VIEWS, "the cuts hold entries (%u)", total);
                    ref = cut;
                    continue;
                }
                for (v = 0; v < SIMD_VIEWS && differs == UINT32_MAX; v++) {
                    mlod_cut_view a = mlod_cut_get(cut, v), b = mlod_cut_get(ref, v);
                    if (!tu_same_cut(&a, &b)) differs = v;
                }
                CHECK(differs == UINT32_MAX, "mode %d, epsilon %g: level %s's cut of view %u differs from level none's",
                      m, epsilons[e], level_name(simd_levels[k]), differs);
                mlod_cut_destroy(cut);
            }
            mlod_cut_destroy(ref);
        }
    mlod_simd_limit(MLOD_SIMD_AVX512);
}

/* An atlas's depths and node ids, equal bit for bit. */
static int atlases_equal(const mlod_atlas *a, const mlod_atlas *b)
{
    size_t n = (size_t)a->width * a->height;
    if (a->width != b->width || a->height != b->height) return 0;
    if (memcmp(a->depth, b->depth, sizeof(float) * n)) return 0;
    return (a->ids == NULL) == (b->ids == NULL) && (!a->ids || !memcmp(a->ids, b->ids, sizeof(uint32_t) * n));
}

static uint64_t drawn_pixels(const mlod_atlas *a)
{
    size_t i, n = (size_t)a->width * a->height;
    uint64_t drawn = 0;
    for (i = 0; i < n; i++) drawn += a->depth[i] < INFINITY;
    return drawn;
}

static void test_splats(const mlod_tree *tree, const double *c, double R)
{
    static const struct {
        uint32_t splat;
        float scale;
        int ism;
    } cases[5] = {{MLOD_SPLAT_SPHERES, 1.0f, 0}, {MLOD_SPLAT_SPHERES, 0.5f, 0}, {MLOD_SPLAT_TANGENT, 1.0f, 0},
                  {MLOD_SPLAT_TANGENT, 0.5f, 0}, {MLOD_SPLAT_SPHERES, 1.0f, 1}};
    mlod_view views[SIMD_VIEWS];
    mlod_cut *cut = NULL;
    mlod_cut_params p;
    mlod_error err;
    int i, k;
    make_views(c, R, 0, views);
    memset(&p, 0, sizeof p);
    p.mode = MLOD_CUT_BASIC;
    p.epsilon = 1.0f;
    p.parallel = &simd_parallel;
    if (mlod_cut_create(SIMD_VIEWS, NULL, &cut, &err) != MLOD_OK || mlod_cut_update(cut, tree, views, &p, &err) != MLOD_OK) {
        CHECK(0, "cut: %s", err.message);
        mlod_cut_destroy(cut);
        return;
    }
    for (i = 0; i < 5; i++) {
        mlod_atlas *ref = NULL;
        for (k = 0; k < simd_level_count; k++) {
            mlod_atlas_desc d;
            mlod_atlas *a = NULL;
            mlod_result r;
            memset(&d, 0, sizeof d);
            d.splat = cases[i].splat;
            d.disc_scale = cases[i].scale;
            if (mlod_atlas_create(views, SIMD_VIEWS, &d, NULL, &a, &err) != MLOD_OK) {
                CHECK(0, "atlas: %s", err.message);
                break;
            }
            mlod_simd_limit(simd_levels[k]);
            r = cases[i].ism ? mlod_splat_ism(a, tree, views, 4096, 11, &simd_parallel, &err)
                             : mlod_splat(a, tree, cut, views, &simd_parallel, &err);
            CHECK(r == MLOD_OK, "splat case %d at level %s: %s", i, level_name(simd_levels[k]), r == MLOD_OK ? "" : err.message);
            if (k == 0) {
                ref = a;
                CHECK(drawn_pixels(a) > 1000, "case %d draws pixels (%llu)", i, (unsigned long long)drawn_pixels(a));
                continue;
            }
            CHECK(atlases_equal(a, ref), "splat case %d (%s): level %s's atlas differs from level none's", i,
                  cases[i].ism ? "ISM" : "cut", level_name(simd_levels[k]));
            mlod_atlas_destroy(a);
        }
        mlod_atlas_destroy(ref);
    }
    mlod_cut_destroy(cut);
    mlod_simd_limit(MLOD_SIMD_AVX512);
}

/* MegaViews: lights on the surface's bounding sphere, facing in, rendered
   through the view tree with and without sharing (delta), with and
   without grouping. */
static void test_megaviews(const mlod_tree *tree, const double *c, double R)
{
    enum { LIGHTS = 300 };
    static float eyes[3 * LIGHTS], dirs[3 * LIGHTS];
    static const float deltas[2] = {0.0f, 0.5f}, groups[2] = {0.0f, 0.02f};
    mlod_view_set set;
    mlod_view_tree *vt = NULL;
    mlod_error err;
    uint64_t rng = 3;
    uint32_t i;
    int j, k, g;
    for (i = 0; i < LIGHTS; i++) {
        double d[3];
        tu_random_unit(&rng, d);
        for (j = 0; j < 3; j++) {
            eyes[3 * i + j] = (float)(c[j] + 1.1 * R * d[j]);
            dirs[3 * i + j] = (float)-d[j];
        }
    }
    memset(&set, 0, sizeof set);
    set.eyes = eyes;
    set.eye_stride = 3 * sizeof(float);
    set.count = LIGHTS;
    set.directions = dirs;
    set.direction_stride = 3 * sizeof(float);
    set.half_fov = 1.5707964f;
    if (mlod_view_tree_build(&set, NULL, &simd_parallel, &vt, &err) != MLOD_OK) {
        CHECK(0, "view tree: %s", err.message);
        return;
    }
    for (j = 0; j < 2; j++)
        for (g = 0; g < 2; g++) {
            mlod_atlas *ref = NULL;
            for (k = 0; k < simd_level_count; k++) {
                mlod_megaviews_params p;
                mlod_megaviews_stats stats;
                mlod_atlas_desc d;
                mlod_atlas *a = NULL;
                mlod_view tile = mlod_megaviews_view(eyes, 8, MLOD_VIEW_CULL_BACKFACES);
                mlod_view *tiles = (mlod_view *)malloc(sizeof(mlod_view) * LIGHTS);
                mlod_result r;
                for (i = 0; i < LIGHTS; i++) tiles[i] = tile;
                memset(&d, 0, sizeof d);
                d.splat = MLOD_SPLAT_SPHERES;
                r = mlod_atlas_create(tiles, LIGHTS, &d, NULL, &a, &err);
                free(tiles);
                if (r != MLOD_OK) {
                    CHECK(0, "atlas: %s", err.message);
                    break;
                }
                memset(&p, 0, sizeof p);
                p.epsilon = 1.0f;
                p.delta = deltas[j];
                p.resolution = 8;
                p.flags = MLOD_VIEW_CULL_BACKFACES;
                p.group_radius = (float)(groups[g] * R);
                p.parallel = &simd_parallel;
                mlod_simd_limit(simd_levels[k]);
                r = mlod_megaviews_render(a, tree, vt, &p, &stats, &err);
                CHECK(r == MLOD_OK, "render at level %s: %s", level_name(simd_levels[k]), r == MLOD_OK ? "" : err.message);
                if (k == 0) {
                    ref = a;
                    CHECK(drawn_pixels(a) > 1000, "the render draws pixels (%llu)", (unsigned long long)drawn_pixels(a));
                    continue;
                }
                CHECK(atlases_equal(a, ref), "MegaViews delta %g, group %g: level %s's atlas differs from level none's",
                      deltas[j], groups[g], level_name(simd_levels[k]));
                mlod_atlas_destroy(a);
            }
            mlod_atlas_destroy(ref);
        }
    mlod_view_tree_destroy(vt);
    mlod_simd_limit(MLOD_SIMD_AVX512);
}

int main(int argc, char **argv)
{
    scene_mesh mesh;
    mlod_tree *tree;
    double c[3], R;
    test_groups_begin(argc, argv);
    simd_pool = mlod_pool_create(2);
    simd_parallel = mlod_pool_parallel(simd_pool);
    memset(&mesh, 0, sizeof mesh);
    if (!scene_torus(&mesh, 1.0f, 0.35f, 96, 48)) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    tu_bounds(&mesh, c, &R);
    tree = tu_build(&mesh, 60000, 5, MLOD_ATTR_CONE);
    CHECK(tree != NULL, "the tree builds");
    find_levels();
    TEST_GROUP("levels", test_levels());
    if (tree) {
        TEST_GROUP("cuts", test_cuts(tree, c, R));
        TEST_GROUP("splats", test_splats(tree, c, R));
        TEST_GROUP("megaviews", test_megaviews(tree, c, R));
    }
    mlod_tree_destroy(tree);
    scene_free(&mesh);
    mlod_pool_destroy(simd_pool);
    test_groups_end();
    return test_finish();
}
