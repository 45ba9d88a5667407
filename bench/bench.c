/* bench/bench.c - what `make bench` runs: the speed / accuracy trade of
   manylods, measured against an exact reference and against the peers a
   user would otherwise pick.

     bench [--quick | --selftest] [--threads T] [--out DIR] [--scene object|room|views]
           [--sizes N,N,...] [--eps E,E,...] [--views V,V,...] [MESH.obj|MESH.ply]

   Scenes (deterministic):
     object  a closed, bumpy (2,3) torus knot that deforms every frame (the
             tree is refitted), seen by 1024 paraboloid virtual point lights
             on a sphere around it, facing its centre, 32 x 32 px tiles (a
             1024 x 1024 atlas), the light rig turning 10 degrees per frame:
             the protocol of Tables 1 and 2 of the ManyLoDs paper;
     room    the closed room of examples/scenes.h, subdivided and twisting,
             with 1024 paraboloid lights on its surfaces facing along the
             surface normal: near walls reach the rim of every tile, so cuts
             are large;
     views   many views at once (MegaViews): the room, unchanging, N = 2^20,
             with 1 k to 1 M hemispherical lights at random surface points,
             each rendering a global dual paraboloid of 2 x 11 x 11 px through
             the view tree (mlod_megaviews_render, delta 0.5) and, up to 64 k,
             through the per-view cut and splat of the same maps; both against
             Embree's exact maps; time, memory, pairs, sharing, error and the
             growth exponents per view count, and a log-log plot (views.svg).
   MESH replaces the object's and the room's meshes (centred, bounding
   radius 1).

   For each scene, sample count N, epsilon and mode (basic, incremental,
   lazy q=1, lazy q=2) it runs a warm-up frame (every mode cuts from the
   root, as a program's first frame would; no splat), then measured frames, and
   reports medians of build, refit, cut and splat times, node-views
   evaluated, cut size per view, bytes, and the accuracy of the last frame's
   atlas against an Embree ray-cast reference of the same frame (bench/
   metrics.h).  Every cut of every frame is checked first (each view's cut
   partitions the leaves, left to right; incremental equals basic node for
   node, so its splat is basic's; lazy converges to basic once the views
   stop, checked at the smallest N), and every atlas must be non-empty; a
   failed check prints FAIL and exits 1.  Peers in the same run: a per-view
   recursive traversal (bench/recursive.h), Imperfect Shadow Maps at equal
   time, our basic cut drawn as half discs and pull-push filled
   (mlod_atlas_desc.disc_scale 0.5), Embree casting the exact maps (the
   lean peer of bench/rt.h: rays set up once per map, only the pixels a
   map shows, the fastest of its ray variants and BVH qualities in the
   same run), Embree's BVH build and refit; and the N that mlod_suggest_sample_count suggests (for
   the closest surface any light sees), run when at most twice the largest N.

   The Targets table (issue 16's targets, then issue 7's that it does not
   restate) sets each figure beside its target and anchor.  At the headline
   setting (object, largest N, epsilon 1) the bench also measures, checked
   like the sweep: build, refit, basic cut and splat on one thread and on
   two, interleaved; incremental against basic with the rig turning 1
   degree per frame and with a static rig; an incremental update whose
   views and tree did not change; the basic cut with a tree without cones
   and views without back-face culling; and one 1024 x 1024 perspective
   view of the object (Table 2's setting) cut at c = 1, 2, 4 px, beside
   Embree casting the same view.  Many-view cuts are anchored to the
   paper's Table 1 (1024 VPLs), the one view to its Table 2.

   --quick     a smaller sweep (256 views, N 2^16 and 2^18, epsilon 1 and 4;
               views: 1 k to 16 k, N 2^17)
   --selftest  a small scene in a second or two: checks the checks, the
               reference and the metrics; exit status 0 when all hold
   --out DIR   also write DIR/BENCHMARKS.md, DIR/bench.csv, DIR/bench.svg and
               DIR/views.svg
   --sizes, --eps  replace the sweep's lists (comma-separated)
   --views     replace the view counts of the many-views table
   --threads T the built-in pool's threads (default 2; Embree gets as many)

   Files: one program, one translation unit.  This file holds the
   overview, the machine's description, --selftest and main; it includes,
   each after what it calls:
     bench_common.h      what the protocols share: settings, timing, the
                         row table, the lean Embree peer, the scenes and
                         their frames, the checks, the metrics glue
     protocol_single.c   the single large view (Table 2's setting)
     protocol_targets.c  the Targets table: its own measurements, the table
     protocol_vulkan.c   manylods_vk.h beside the CPU (BENCH_VULKAN)
     protocol_sweep.c    the per-scene protocol (object, room): the sweep,
                         its peers, the suggested N
     protocol_views.c    many views at once (MegaViews)
     report.c            BENCHMARKS.md, bench.csv, bench.svg
   Each starts with what it measures: its rows and their anchors.  The
   helpers beside them are headers of their own (metrics.h, rt.h,
   recursive.h, shapes.h, plot.h); cut_avx2.c is the library compiled
   apart with -mavx2 -mfma and linked in. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "../examples/meshio.h"
#include "../examples/sampling_summary.h"
#include "metrics.h"
#include "plot.h"
#include "recursive.h"
#include "rt.h"
#include "shapes.h"
#ifdef BENCH_AVX2
#include "cut_avx2.h"
#endif
#ifdef BENCH_VULKAN
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"
#endif

#ifndef BENCH_FLAGS
#define BENCH_FLAGS "(flags not recorded)"
#endif
/* The lanes the float filters run in (mlod_simd_level: the build's and
   the processor's; VECTOR LANES in the manual). */
#define BENCH_LANES bench_lanes()
static const char *bench_lanes(void)
{
    switch (mlod_simd_level()) {
    case MLOD_SIMD_AVX512: return "the float filters in 8 lanes compiled for AVX-512 (chosen at run time)";
    case MLOD_SIMD_AVX2: return "the float filters in 8 lanes (AVX2, chosen at run time)";
    case MLOD_SIMD_SSE2: return "the float filters in 4 lanes (SSE2)";
    case MLOD_SIMD_NEON: return "the float filters in 4 lanes (NEON)";
    default: return "the float filters on scalars (no vector lanes)";
    }
}

#include "bench_common.h"
#include "protocol_single.c"
#include "protocol_targets.c"
#include "protocol_vulkan.c"
#include "protocol_sweep.c"
#include "protocol_views.c"
#include "report.c"

/* ------------------------------------------------------------ machine */

/* The first three fields of /proc/loadavg ("?" where there is none). */
static void read_load(char *out, size_t size)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double a, b5, c;
    if (f && fscanf(f, "%lf %lf %lf", &a, &b5, &c) == 3)
        snprintf(out, size, "%.2f %.2f %.2f", a, b5, c);
    else
        snprintf(out, size, "?");
    if (f) fclose(f);
}

static void describe_machine(bench *b)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512], model[128] = "unknown CPU";
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    time_t t = time(NULL);
    if (f) {
        while (fgets(line, sizeof line, f))
            if (strncmp(line, "model name", 10) == 0) {
                char *colon = strchr(line, ':'), *end;
                if (colon) {
                    snprintf(model, sizeof model, "%s", colon + 2);
                    if ((end = strchr(model, '\n'))) *end = '\0';
                }
                break;
            }
        fclose(f);
    }
    snprintf(b->machine, sizeof b->machine, "%s, %ld cores online", model, cores);
    read_load(b->load_start, sizeof b->load_start);
#if defined(__clang__)
    snprintf(b->compiler, sizeof b->compiler, "clang %s", __clang_version__);
#elif defined(__GNUC__)
    snprintf(b->compiler, sizeof b->compiler, "gcc %s", __VERSION__);
#else
    snprintf(b->compiler, sizeof b->compiler, "unknown compiler");
#endif
    strftime(b->date, sizeof b->date, "%Y-%m-%d %H:%M UTC", gmtime(&t));
    snprintf(b->threads, sizeof b->threads, "%u threads (built-in pool, MANYLODS_PTHREADS)", b->cfg.threads);
}

/* ----------------------------------------------------------- selftest */

/* A small scene: the checks must hold, the parallel reference must equal
   metrics_reference_atlas, and the metrics must be sane. */
static int selftest(bench *b, protocol *p)
{
    const float *positions;
    mlod_mesh mesh;
    mlod_tree *tree;
    mlod_cut *cut;
    mlod_cut_params params;
    mlod_error error;
    ranks rk;
    metrics same, ours, empty;
    size_t pixels = (size_t)p->atlas->width * p->atlas->height, q;
    float *sequential = (float *)checked_malloc(sizeof(float) * pixels), *saved;
    uint32_t *hits, *stack, v;
    rt_scene scene;
    double build_ms;
    int last = p->frame_count - 1;

    /* the lean peer's maps are metrics_reference_atlas's, up to the rounding of
       their rays (set up from a template, not per pixel) */
    positions = frame_positions(p, last);
    if (!rt_create(b->device, p->rest.indices, p->rest.index_count, positions, p->rest.vertex_count,
                   RTC_BUILD_QUALITY_MEDIUM, &scene))
        fail("selftest: Embree could not create a scene");
    rt_commit(&scene);
    metrics_reference_atlas(p->atlas, frame_views(p, last), rt_cast, &scene, sequential);
    {
        size_t bad = lean_mismatches(p->reference, sequential, pixels);
        printf("selftest: the lean peer differs from metrics_reference_atlas at %zu of %zu pixels\n", bad, pixels);
        if (bad > pixels / 1000)
            fail("selftest: the lean peer differs from metrics_reference_atlas at %zu of %zu pixels", bad, pixels);
    }
    /* exact visibility: each shadow ray's answer is the nearest hit's along the same segment */
    {
        uint32_t r, wrong = 0, tests = 0;
        for (v = 0; v < p->view_count; v++)
            for (r = 0; r < p->receiver_count; r++) {
                const mlod_view *view = frame_views(p, last) + v;
                const float *x = p->receivers + 3 * (size_t)r;
                float dir[3], t, length;
                int lit;
                unsigned char truth = p->visible[(size_t)v * p->receiver_count + r];
                if (truth == 2 || !metrics_segment(view->position, x, dir, &length)) continue;
                lit = !rt_cast(&scene, view->position, dir, &t) || t >= length;
                wrong += lit != truth;
                tests++;
            }
        printf("selftest: exact visibility: %u of %u shadow rays disagree with the nearest hit\n", wrong, tests);
        if (tests == 0 || wrong > tests / 1000)
            fail("selftest: exact visibility disagrees with the nearest hit for %u of %u pairs", wrong, tests);
    }
    rt_destroy(&scene);
    free(sequential);

    /* the reference compared with itself: no holes, no error, no disagreement */
    saved = p->atlas->depth;
    p->atlas->depth = p->reference;
    compare_last(p, &same);
    p->atlas->depth = saved;
    if (same.holes != 0 || same.depth_rms != 0 || same.shadow_differences != 0 || same.reference_hits == 0 ||
        same.shadow_tests == 0)
        fail("selftest: the reference against itself gives holes %llu, rms %g, shadow differences %llu",
             (unsigned long long)same.holes, same.depth_rms, (unsigned long long)same.shadow_differences);

    /* the interval check agrees with the literal subtree walk, on a splat
       that is close to the reference */
    tree = build_tree(b, p, b->cfg.sizes[0], &build_ms);
    mesh = frame_mesh(p, last);
    if (mlod_refit_mesh(tree, &mesh, &b->parallel, &error) != MLOD_OK) fail("selftest: refit: %s", error.message);
    ranks_init(&rk, tree);
    hits = (uint32_t *)checked_malloc(sizeof(uint32_t) * tree->leaf_count);
    stack = (uint32_t *)checked_malloc(sizeof(uint32_t) * 64);
    if (mlod_cut_create(p->view_count, NULL, &cut, &error) != MLOD_OK) fail("selftest: %s", error.message);
    memset(&params, 0, sizeof params);
    params.mode = MLOD_CUT_BASIC;
    params.epsilon = 1.0f;
    params.parallel = &b->parallel;
    if (mlod_cut_update(cut, tree, frame_views(p, last), &params, &error) != MLOD_OK)
        fail("selftest: %s", error.message);
    for (v = 0; v < p->view_count; v++) {
        mlod_cut_view c = mlod_cut_get(cut, v), broken;
        uint32_t nodes[2];
        uint8_t status[2] = {MLOD_STATUS_DRAWN, MLOD_STATUS_DRAWN};
        if ((check_cut_view(&rk, &c, 0) == NULL) != cut_partitions_by_walk(tree, &c, hits, stack))
            fail("selftest: view %u: the interval check and the subtree walk disagree", v);
        if (check_cut_view(&rk, &c, 0)) fail("selftest: view %u: %s", v, check_cut_view(&rk, &c, 0));
        /* and both reject a cut that repeats a subtree */
        nodes[0] = 1;
        nodes[1] = 1;
        broken = c;
        broken.nodes = nodes;
        broken.status = status;
        broken.count = 2;
        broken.drawn = 2;
        broken.culled = broken.oversize = broken.coarse = 0;
        if (check_cut_view(&rk, &broken, 0) == NULL || cut_partitions_by_walk(tree, &broken, hits, stack))
            fail("selftest: a cut listing node 1 twice passed a check");
    }
#ifdef BENCH_AVX2
    if (bench_avx2_supported()) { /* the Targets table's AVX2 copy cuts the same */
        bench_avx2_cut *wide = bench_avx2_cut_create(p->view_count);
        uint64_t hash = 1469598103934665603ull;
        if (!wide || bench_avx2_cut_update(wide, tree, frame_views(p, last), &params, &error) != MLOD_OK)
            fail("selftest: the AVX2 copy's cut: %s", wide ? error.message : "out of memory");
        for (v = 0; v < p->view_count; v++) hash = bench_hash_cut_view(hash, mlod_cut_get(cut, v));
        if (hash != bench_avx2_cut_hash(wide)) fail("selftest: the AVX2 copy's cuts differ from this build's");
        { /* and draws the same atlas (its splat's float filter in its own lanes) */
            mlod_atlas *wide_atlas = NULL;
            mlod_atlas_desc desc;
            memset(&desc, 0, sizeof desc);
            if (mlod_atlas_create(frame_views(p, last), p->view_count, &desc, NULL, &wide_atlas, &error) != MLOD_OK ||
                bench_avx2_splat(wide, wide_atlas, tree, frame_views(p, last), &b->parallel, &error) != MLOD_OK ||
                mlod_splat(p->atlas, tree, cut, frame_views(p, last), &b->parallel, &error) != MLOD_OK)
                fail("selftest: the AVX2 copy's splat: %s", error.message);
            if (memcmp(wide_atlas->depth, p->atlas->depth, sizeof(float) * pixels) != 0)
                fail("selftest: the AVX2 copy's atlas differs from this build's");
            mlod_atlas_destroy(wide_atlas);
        }
        printf("selftest: the copy built with -mavx2 -mfma (%d lanes) gives the same cuts and atlas\n",
               bench_avx2_lanes());
        bench_avx2_cut_destroy(wide);
    }
#endif
    if (mlod_splat(p->atlas, tree, cut, frame_views(p, last), &b->parallel, &error) != MLOD_OK)
        fail("selftest: %s", error.message);
    compare_last(p, &ours);
    if (!(ours.hole_rate < 0.5 && ours.depth_rms < 0.5 && ours.shadow_disagreement < 0.5 && ours.depth_pixels > 0))
        fail("selftest: the splat of a basic cut at 1 px is far from the reference: holes %.3f, rms %.4f, shadow %.3f",
             ours.hole_rate, ours.depth_rms, ours.shadow_disagreement);
    for (q = 0; q < pixels; q++) p->atlas->depth[q] = INFINITY;
    compare_last(p, &empty);
    if (empty.holes != empty.reference_hits || empty.hole_rate != 1.0)
        fail("selftest: an empty atlas does not have every reference hit as a hole");
    printf("selftest: reference %llu hits; splat at 1 px: holes %.2f%%, depth RMS %.3f%%, shadow %.2f%%\n",
           (unsigned long long)ours.reference_hits, 100 * ours.hole_rate, 100 * ours.depth_rms,
           100 * ours.shadow_disagreement);
    mlod_cut_destroy(cut);
    free(hits);
    free(stack);
    ranks_free(&rk);
    mlod_tree_destroy(tree);
    return 0;
}

/* --------------------------------------------------------------- main */

static void usage(void)
{
    fprintf(stderr, "usage: bench [--quick | --selftest] [--threads T] [--out DIR] [--scene object|room|views]\n"
                    "             [--sizes N,N,...] [--eps E,E,...] [--views V,V,...] [MESH.obj|MESH.ply]\n");
    exit(2);
}

/* A comma-separated list of up to BENCH_MAX_LIST positive numbers into
   floats or counts (1 .. MANYLODS_MAX_LEAVES); returns how many, 0 if malformed. */
static int parse_list(const char *text, float *floats, uint32_t *counts)
{
    int n = 0;
    while (*text) {
        char *end;
        double x = strtod(text, &end);
        if (end == text || n == BENCH_MAX_LIST || !(x > 0) || !isfinite(x)) return 0;
        if (counts && (x != floor(x) || x > MANYLODS_MAX_LEAVES)) return 0;
        if (floats) floats[n] = (float)x;
        if (counts) counts[n] = (uint32_t)x;
        n++;
        if (*end == ',') end++;
        else if (*end) return 0;
        text = end;
    }
    return n;
}

int main(int argc, char **argv)
{
    bench b;
    protocol object, room, *protocols[2];
    int protocol_count = 0, i;
    char device_config[64];
    const char *sizes = NULL, *eps = NULL, *view_counts = NULL;
    memset(&b, 0, sizeof b);
    memset(&object, 0, sizeof object);
    memset(&room, 0, sizeof room);
    config_defaults(&b.cfg);
#ifdef BENCH_SELFTEST
    b.cfg.selftest = 1; /* the build `make test` runs */
#endif
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--quick") == 0)
            b.cfg.quick = 1;
        else if (strcmp(argv[i], "--selftest") == 0)
            b.cfg.selftest = 1;
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            b.cfg.threads = (uint32_t)atoi(argv[++i]);
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            b.cfg.out_dir = argv[++i];
        else if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc)
            b.cfg.scene = argv[++i];
        else if (strcmp(argv[i], "--sizes") == 0 && i + 1 < argc)
            sizes = argv[++i];
        else if (strcmp(argv[i], "--eps") == 0 && i + 1 < argc)
            eps = argv[++i];
        else if (strcmp(argv[i], "--views") == 0 && i + 1 < argc)
            view_counts = argv[++i];
        else if (argv[i][0] == '-')
            usage();
        else
            b.cfg.mesh_path = argv[i];
    }
    if (b.cfg.threads < 1 || b.cfg.threads > 256) usage();
    if (b.cfg.scene && strcmp(b.cfg.scene, "object") != 0 && strcmp(b.cfg.scene, "room") != 0 &&
        strcmp(b.cfg.scene, "views") != 0)
        usage();
    if (b.cfg.quick) config_quick(&b.cfg);
    if (b.cfg.selftest) config_selftest(&b.cfg);
    if (sizes) {
        b.cfg.size_count = parse_list(sizes, NULL, b.cfg.sizes);
        if (b.cfg.size_count == 0) usage();
    }
    if (eps) {
        b.cfg.eps_count = parse_list(eps, b.cfg.eps, NULL);
        if (b.cfg.eps_count == 0) usage();
    }
    if (view_counts) {
        b.cfg.view_count_n = parse_list(view_counts, NULL, b.cfg.view_counts);
        if (b.cfg.view_count_n == 0) usage();
    }
    b.started_ms = now_ms();
    describe_machine(&b);
    b.pool = mlod_pool_create(b.cfg.threads);
    if (!b.pool) fail("mlod_pool_create(%u) failed", b.cfg.threads);
    b.parallel = mlod_pool_parallel(b.pool);
    snprintf(device_config, sizeof device_config, "threads=%u", b.cfg.threads);
    b.device = rtcNewDevice(device_config);
    if (!b.device) fail("rtcNewDevice failed (Embree error %d)", (int)rtcGetDeviceError(NULL));

    printf("manylods %d.%d.%d benchmark%s\n", MANYLODS_VERSION_MAJOR, MANYLODS_VERSION_MINOR, MANYLODS_VERSION_PATCH,
           b.cfg.quick ? " (--quick)" : b.cfg.selftest ? " (--selftest)" : "");
    printf("machine   %s\ncompiler  %s, %s: %s\nthreads   %s\nembree    %s\ndate      %s\n", b.machine, b.compiler,
           BENCH_FLAGS, BENCH_LANES, b.threads, RTC_VERSION_STRING, b.date);
    fflush(stdout);

    if (!b.cfg.scene || strcmp(b.cfg.scene, "object") == 0 || b.cfg.selftest) {
        protocol_object(&b, &object);
        protocols[protocol_count++] = &object;
    }
    if (!b.cfg.selftest && (!b.cfg.scene || strcmp(b.cfg.scene, "room") == 0)) {
        protocol_room(&b, &room);
        protocols[protocol_count++] = &room;
    }
    for (i = 0; i < protocol_count; i++) {
        protocol *p = protocols[i];
        protocol_reference(&b, p);
        printf("scene     %s: %s\n          %u vertices, diameter %.3g, area %.3g, atlas %ux%u, reference %.1f%% of "
               "pixels hit, closest surface %.3g; Embree cast %.1f ms\n          shadow bias %g px: %s\n",
               p->name, p->description, p->rest.vertex_count, p->diameter, p->area, p->atlas->width, p->atlas->height,
               100.0 * p->reference_hits / ((double)p->atlas->width * p->atlas->height), p->closest, p->polys_ms,
               p->bias_pixels, p->bias_note);
        fflush(stdout);
    }
    if (b.cfg.selftest) {
        int status = selftest(&b, &object);
        if (status == 0) {
            run_size(&b, &object, b.cfg.sizes[0], b.cfg.eps, b.cfg.eps_count, (1u << BENCH_MODES) - 1, 1, 1, 1,
                     ROW_OURS);
            run_views(&b);
            printf("selftest: all checks passed (%.1f s)\n", (now_ms() - b.started_ms) / 1e3);
        }
        protocol_free(&object);
        rtcReleaseDevice(b.device);
        mlod_pool_destroy(b.pool);
        free(b.rows);
        return status;
    }
    printf("sweep     N in {");
    for (i = 0; i < b.cfg.size_count; i++) printf("%s%u", i ? ", " : "", b.cfg.sizes[i]);
    printf("}");
    if (b.cfg.room_skips[0]) printf(" (room: without %u and %u)", b.cfg.room_skips[0], b.cfg.room_skips[1]);
    printf(", epsilon in {");
    for (i = 0; i < b.cfg.eps_count; i++) printf("%s%g", i ? ", " : "", (double)b.cfg.eps[i]);
    printf("} px, modes basic / incremental / lazy q=1 / lazy q=2; %d warm-up + %d measured frames\n\n",
           b.cfg.warmup, b.cfg.measured);
    fflush(stdout);
    for (i = 0; i < protocol_count; i++) run_protocol(&b, protocols[i]);
    if (!b.cfg.scene || strcmp(b.cfg.scene, "views") == 0) run_views(&b);
    read_load(b.load_end, sizeof b.load_end);
    printf("\nall checks passed; %.0f s in all\n\n", (now_ms() - b.started_ms) / 1e3);
    write_outputs(&b, protocols, protocol_count);
    for (i = 0; i < protocol_count; i++) protocol_free(protocols[i]);
    rtcReleaseDevice(b.device);
    mlod_pool_destroy(b.pool);
    free(b.rows);
    return 0;
}
