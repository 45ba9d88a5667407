/* examples/demo.c - what `make demo` runs.

   Builds a tree on the procedural room of examples/scenes.h, then animates
   a few frames: the room twists (scene_deform), the tree is refitted, and
   the cuts of many views are recomputed in each of the three modes:

     256  virtual point lights (paraboloid views, 32 x 32, back-face culled)
          sitting on the surface, one per 1/256 of the samples;
     8    light probes (dual paraboloids, 64 x 32) above the furniture;
     1    camera (perspective, 512 x 288), its cut far larger than the rest;
     1    sun (orthographic, 128 x 128) above the room.

   It prints the tree's size, the build / refit / cut times (monotonic clock,
   mean over the animated frames), the cut sizes per mode, and whether the
   incremental cuts equal the basic ones node for node.  A warm-up frame
   first computes every mode's cuts in basic mode, as a program would on its
   first frame: incremental and lazy updates then start from those cuts.
   Built with MANYLODS_PTHREADS (the Makefile's default) it runs refit and
   cuts on the built-in pool with 2 threads. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "scenes.h"

#define SAMPLES 100000u
#define LIGHTS 256u
#define PROBES 8u
#define VIEWS (LIGHTS + PROBES + 2u)
#define FRAMES 4 /* animated frames, after one warm-up frame */
#define EPSILON_PX 2.0f

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void set3(float out[3], float x, float y, float z)
{
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

/* The views of frame `frame`: lights follow the (refitted) surface. */
static void make_views(mlod_view *views, const mlod_tree *tree, int frame)
{
    uint32_t i;
    float a = 0.02f * (float)frame;
    memset(views, 0, VIEWS * sizeof *views);
    for (i = 0; i < LIGHTS; i++) { /* a light 0.05 above a sample, facing along its normal */
        uint32_t node = tree->leaf_count - 1u + (uint32_t)((uint64_t)i * tree->leaf_count / LIGHTS);
        const float *c = tree->spheres + 4 * (size_t)node, *n = tree->cones + 4 * (size_t)node;
        mlod_view *v = &views[i];
        v->kind = MLOD_VIEW_PARABOLOID;
        set3(v->position, c[0] + 0.05f * n[0], c[1] + 0.05f * n[1], c[2] + 0.05f * n[2]);
        set3(v->forward, n[0], n[1], n[2]);
        if (n[1] > 0.7f || n[1] < -0.7f) set3(v->up, 1, 0, 0); else set3(v->up, 0, 1, 0);
        v->width = v->height = 32;
        v->flags = MLOD_VIEW_CULL_BACKFACES;
    }
    for (i = 0; i < PROBES; i++) { /* probes on a ring above the furniture */
        mlod_view *v = &views[LIGHTS + i];
        float t = 6.2831853f * (float)i / PROBES;
        v->kind = MLOD_VIEW_DUAL_PARABOLOID;
        set3(v->position, 1.5f * cosf(t), 2.5f, 1.5f * sinf(t));
        set3(v->forward, 1, 0, 0);
        set3(v->up, 0, 1, 0);
        v->width = 64;
        v->height = 32;
    }
    { /* the camera, slowly turning */
        mlod_view *v = &views[LIGHTS + PROBES];
        v->kind = MLOD_VIEW_PERSPECTIVE;
        set3(v->position, 1.8f, 1.6f, 1.8f);
        set3(v->forward, -1.0f - 0.3f * a, -0.3f, -1.0f + 0.3f * a);
        set3(v->up, 0, 1, 0);
        v->width = 512;
        v->height = 288;
        v->fov_y = 1.0f;
        v->near_plane = 0.05f;
        v->far_plane = 20.0f;
    }
    { /* the sun, straight down onto the room */
        mlod_view *v = &views[LIGHTS + PROBES + 1];
        v->kind = MLOD_VIEW_ORTHOGRAPHIC;
        set3(v->position, 0, 4, 0);
        set3(v->forward, 0, -1, 0);
        set3(v->up, 0, 0, 1);
        v->width = v->height = 128;
        v->near_plane = 0;
        v->far_plane = 5;
        v->half_width = v->half_height = 2.5f;
    }
}

/* One mode's cuts and what the demo measures of them. */
typedef struct mode_run {
    const char *name;
    mlod_cut_params params;
    mlod_cut *cut;
    double ms;                      /* summed over the animated frames */
    uint64_t evaluated;             /* criterion evaluations, animated frames */
    uint32_t views_unlike_basic;    /* in the last frame */
    uint32_t frames_unlike_basic;   /* frames with at least one such view */
} mode_run;

static uint32_t views_unlike(const mlod_cut *a, const mlod_cut *b)
{
    uint32_t v, unlike = 0;
    for (v = 0; v < VIEWS; v++) {
        mlod_cut_view x = mlod_cut_get(a, v), y = mlod_cut_get(b, v);
        if (x.count != y.count || memcmp(x.nodes, y.nodes, x.count * sizeof *x.nodes) != 0 ||
            memcmp(x.status, y.status, x.count) != 0)
            unlike++;
    }
    return unlike;
}

static void print_cut(const mode_run *m)
{
    uint64_t count = 0, drawn = 0, culled = 0, oversize = 0, coarse = 0;
    uint32_t v, lo = UINT32_MAX, hi = 0;
    for (v = 0; v < VIEWS; v++) {
        mlod_cut_view c = mlod_cut_get(m->cut, v);
        count += c.count;
        drawn += c.drawn;
        culled += c.culled;
        oversize += c.oversize;
        coarse += c.coarse;
        if (c.count < lo) lo = c.count;
        if (c.count > hi) hi = c.count;
    }
    printf("%-12s %8.2f ms/frame  cuts of %llu nodes: %llu drawn, %llu culled, %llu oversize, %llu coarse;"
           " %u..%u per view; %.1f MiB\n",
           m->name, m->ms / FRAMES, (unsigned long long)count, (unsigned long long)drawn,
           (unsigned long long)culled, (unsigned long long)oversize, (unsigned long long)coarse, lo, hi,
           (double)mlod_cut_bytes(m->cut) / (1024.0 * 1024.0));
}

int main(void)
{
    scene_mesh room;
    float *positions = NULL, *normals = NULL;
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_tree *tree = NULL;
    mlod_view *views = NULL;
    mlod_error error;
    mode_run modes[3];
    const mlod_parallel *parallel = NULL;
    const char *threads = "1 thread (built without MANYLODS_PTHREADS)";
    double t0, build_ms, refit_ms = 0;
    int frame, status = 1;
    uint32_t m;
#ifdef MANYLODS_PTHREADS
    mlod_parallel pool_parallel;
    mlod_pool *pool = mlod_pool_create(2);
    if (pool) {
        pool_parallel = mlod_pool_parallel(pool);
        parallel = &pool_parallel;
        threads = "2 threads (built-in pool)";
    } else {
        threads = "1 thread (mlod_pool_create failed)";
    }
#endif

    memset(&error, 0, sizeof error);
    memset(modes, 0, sizeof modes);
    if (!scene_room(&room)) {
        fprintf(stderr, "demo: out of memory\n");
        return 1;
    }
    positions = (float *)malloc(3 * sizeof(float) * room.vertex_count);
    normals = (float *)malloc(3 * sizeof(float) * room.vertex_count);
    views = (mlod_view *)malloc(VIEWS * sizeof *views);
    if (!positions || !normals || !views) {
        fprintf(stderr, "demo: out of memory\n");
        goto done;
    }

    memset(&mesh, 0, sizeof mesh);
    mesh.positions = room.positions;
    mesh.normals = room.normals;
    mesh.colors = room.colors;
    mesh.vertex_count = room.vertex_count;
    mesh.indices = room.indices;
    mesh.index_count = room.index_count;
    memset(&desc, 0, sizeof desc);
    desc.sample_count = SAMPLES;
    desc.seed = 1;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_REFIT;

    t0 = now_ms();
    if (mlod_build_mesh(&mesh, &desc, &tree, &error) != MLOD_OK) goto failed;
    build_ms = now_ms() - t0;

    modes[0].name = "basic";
    modes[1].name = "incremental";
    modes[2].name = "lazy (q=1)";
    for (m = 0; m < 3; m++) {
        modes[m].params.mode = (mlod_cut_mode)m; /* MLOD_CUT_BASIC, _INCREMENTAL, _LAZY */
        modes[m].params.epsilon = EPSILON_PX;
        modes[m].params.lazy_steps = 1;
        modes[m].params.parallel = parallel;
        if (mlod_cut_create(VIEWS, NULL, &modes[m].cut, &error) != MLOD_OK) goto failed;
    }

    /* Frame 0 warms up: every mode's cuts in basic mode.  Frames 1 .. FRAMES
       deform the room, refit, and update the cuts in each mode. */
    mesh.positions = positions;
    mesh.normals = normals;
    for (frame = 0; frame <= FRAMES; frame++) {
        scene_deform(&room, 0.02f * (float)frame, positions, normals);
        t0 = now_ms();
        if (mlod_refit_mesh(tree, &mesh, parallel, &error) != MLOD_OK) goto failed;
        if (frame > 0) refit_ms += now_ms() - t0;
        make_views(views, tree, frame);
        for (m = 0; m < 3; m++) {
            uint32_t v;
            t0 = now_ms();
            if (mlod_cut_update(modes[m].cut, tree, views, frame ? &modes[m].params : &modes[0].params,
                                &error) != MLOD_OK)
                goto failed;
            if (frame == 0) continue;
            modes[m].ms += now_ms() - t0;
            for (v = 0; v < VIEWS; v++) modes[m].evaluated += mlod_cut_get(modes[m].cut, v).evaluated;
        }
        for (m = 1; m < 3; m++) {
            modes[m].views_unlike_basic = views_unlike(modes[m].cut, modes[0].cut);
            if (modes[m].views_unlike_basic) modes[m].frames_unlike_basic++;
        }
    }

    printf("manylods %d.%d.%d demo: procedural room (%u triangles), %s\n", MANYLODS_VERSION_MAJOR,
           MANYLODS_VERSION_MINOR, MANYLODS_VERSION_PATCH, room.index_count / 3, threads);
    printf("%-12s %8.2f ms        %u samples, %u nodes, %.1f MiB (%u bytes per node)\n", "build", build_ms,
           tree->leaf_count, tree->node_count, (double)tree->bytes / (1024.0 * 1024.0),
           (unsigned)tree->bytes_per_node);
    printf("%-12s %8.2f ms/frame  mean of %d frames of a twisting room, after one warm-up frame\n", "refit",
           refit_ms / FRAMES, FRAMES);
    printf("%-12s %u paraboloid 32x32, %u dual paraboloid 64x32, 1 perspective 512x288, 1 orthographic 128x128;"
           " epsilon %.1f px\n", "views", LIGHTS, PROBES, (double)EPSILON_PX);
    for (m = 0; m < 3; m++) print_cut(&modes[m]);
    printf("%-12s criterion evaluations per frame: basic %llu, incremental %llu, lazy %llu\n", "work",
           (unsigned long long)(modes[0].evaluated / FRAMES), (unsigned long long)(modes[1].evaluated / FRAMES),
           (unsigned long long)(modes[2].evaluated / FRAMES));
    printf("%-12s incremental equals basic in %d of %d frames; lazy differs from basic in %u of %u views"
           " in the last frame\n", "check", FRAMES - (int)modes[1].frames_unlike_basic, FRAMES,
           modes[2].views_unlike_basic, VIEWS);
    status = modes[1].frames_unlike_basic ? 1 : 0;
    if (status) fprintf(stderr, "demo: incremental cuts differ from the basic cuts\n");
    goto done;

failed:
    fprintf(stderr, "demo: %s: %s\n", mlod_result_name(error.code), error.message);
done:
    for (m = 0; m < 3; m++)
        if (modes[m].cut) mlod_cut_destroy(modes[m].cut);
    mlod_tree_destroy(tree);
    free(views);
    free(normals);
    free(positions);
    scene_free(&room);
#ifdef MANYLODS_PTHREADS
    if (pool) mlod_pool_destroy(pool);
#endif
    return status;
}
