/* tests/compile/smoke.h - one small use of the whole pipeline, shared by the
   compile-matrix programs.  Written in the common subset of C99 and C++11 so
   that every entry of the matrix compiles the same calls.  Include it after
   manylods.h.

   smoke_run() builds a tree on a unit cube, cuts it for four views (one of
   each kind) in basic mode, refits it with the same mesh, cuts again in
   incremental mode and checks that both modes give the same cuts and that
   every cut partitions the leaves.  It prints what went wrong and returns
   non-zero on any failure; *checksum receives a hash of the basic cuts. */
#ifndef MANYLODS_SMOKE_H
#define MANYLODS_SMOKE_H

#include <stdio.h>
#include <string.h>

#define SMOKE_VIEWS 4u
#define SMOKE_SAMPLES 2000u

static void smoke_cube(float positions[24], uint32_t indices[36])
{
    static const uint32_t quads[6][4] = {
        {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    uint32_t i;
    for (i = 0; i < 8; i++) {
        positions[3 * i + 0] = (float)(i & 1u ? (i & 2u ? 0 : 1) : (i & 2u ? 1 : 0));
        positions[3 * i + 1] = (float)((i >> 1) & 1u);
        positions[3 * i + 2] = (float)((i >> 2) & 1u);
    }
    for (i = 0; i < 6; i++) {
        indices[6 * i + 0] = quads[i][0];
        indices[6 * i + 1] = quads[i][1];
        indices[6 * i + 2] = quads[i][2];
        indices[6 * i + 3] = quads[i][0];
        indices[6 * i + 4] = quads[i][2];
        indices[6 * i + 5] = quads[i][3];
    }
}

static void smoke_view(mlod_view *view, mlod_view_kind kind, float x, float y, float z)
{
    memset(view, 0, sizeof *view);
    view->kind = kind;
    view->position[0] = x;
    view->position[1] = y;
    view->position[2] = z;
    view->forward[0] = 0.5f - x; /* towards the cube's centre */
    view->forward[1] = 0.5f - y;
    view->forward[2] = 0.5f - z;
    if (view->forward[1] * view->forward[1] > view->forward[0] * view->forward[0] + view->forward[2] * view->forward[2])
        view->up[2] = 1.0f; /* looking up or down: z is up */
    else
        view->up[1] = 1.0f;
    view->width = 64;
    view->height = 48;
    view->fov_y = 1.0f;
    view->near_plane = 0.01f;
    view->far_plane = 100.0f;
    view->half_width = 1.0f;
    view->half_height = 1.0f;
}

/* 1 when the subtrees of the cut's nodes cover every leaf exactly once.  In
   the heap layout the nodes of a subtree on one level form one index range
   [first, last]; children of leaves fall past the last node. */
static int smoke_partitions(const mlod_tree *tree, mlod_cut_view view)
{
    unsigned char hits[SMOKE_SAMPLES];
    uint64_t first, last, leaf;
    uint32_t i;
    if (tree->leaf_count != SMOKE_SAMPLES) return 0;
    memset(hits, 0, sizeof hits);
    for (i = 0; i < view.count; i++) {
        if (view.nodes[i] >= tree->node_count) return 0;
        for (first = last = view.nodes[i]; first < tree->node_count; first = 2 * first + 1, last = 2 * last + 2) {
            leaf = first > tree->leaf_count - 1u ? first : tree->leaf_count - 1u;
            for (; leaf <= last && leaf < tree->node_count; leaf++) hits[leaf - (tree->leaf_count - 1u)]++;
        }
    }
    for (i = 0; i < SMOKE_SAMPLES; i++)
        if (hits[i] != 1) return 0;
    return 1;
}

static uint32_t smoke_hash(uint32_t hash, uint32_t value)
{
    return (hash ^ value) * 16777619u;
}

static int smoke_run(const char *label, const mlod_parallel *parallel, uint32_t *checksum)
{
    float positions[24];
    uint32_t indices[36];
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_view views[SMOKE_VIEWS];
    mlod_cut_params params;
    mlod_tree *tree = NULL;
    mlod_cut *basic = NULL, *incremental = NULL;
    mlod_error error;
    uint32_t v, i, hash = 2166136261u;
    int failed = 0;

    smoke_cube(positions, indices);
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = positions;
    mesh.vertex_count = 8;
    mesh.indices = indices;
    mesh.index_count = 36;
    memset(&desc, 0, sizeof desc);
    desc.sample_count = SMOKE_SAMPLES;
    desc.seed = 7;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_REFIT;
    smoke_view(&views[0], MLOD_VIEW_PERSPECTIVE, 3.0f, 2.0f, 2.5f);
    smoke_view(&views[1], MLOD_VIEW_PARABOLOID, -2.0f, 0.5f, 0.5f);
    smoke_view(&views[2], MLOD_VIEW_DUAL_PARABOLOID, 0.5f, 3.0f, 0.5f);
    smoke_view(&views[3], MLOD_VIEW_ORTHOGRAPHIC, 0.5f, 0.5f, -3.0f);
    views[1].flags = MLOD_VIEW_CULL_BACKFACES;
    memset(&params, 0, sizeof params);
    params.mode = MLOD_CUT_BASIC;
    params.epsilon = 2.0f;
    params.lazy_steps = 1;
    params.parallel = parallel;
    memset(&error, 0, sizeof error);

    if (mlod_build_mesh(&mesh, &desc, &tree, &error) != MLOD_OK ||
        mlod_cut_create(SMOKE_VIEWS, NULL, &basic, &error) != MLOD_OK ||
        mlod_cut_create(SMOKE_VIEWS, NULL, &incremental, &error) != MLOD_OK ||
        mlod_cut_update(basic, tree, views, &params, &error) != MLOD_OK ||
        mlod_cut_update(incremental, tree, views, &params, &error) != MLOD_OK) {
        printf("%s: %s: %s\n", label, mlod_result_name(error.code), error.message);
        failed = 1;
    }
    if (!failed && tree->leaf_count != SMOKE_SAMPLES) {
        printf("%s: %u leaves, expected %u\n", label, tree->leaf_count, SMOKE_SAMPLES);
        failed = 1;
    }
    if (!failed) {
        views[0].position[0] = 3.2f; /* move one view, refit, and cut incrementally */
        views[0].forward[0] = 0.5f - 3.2f;
        params.mode = MLOD_CUT_INCREMENTAL;
        if (mlod_refit_mesh(tree, &mesh, parallel, &error) != MLOD_OK ||
            mlod_cut_update(incremental, tree, views, &params, &error) != MLOD_OK) {
            printf("%s: %s: %s\n", label, mlod_result_name(error.code), error.message);
            failed = 1;
        }
        params.mode = MLOD_CUT_BASIC;
        if (!failed && mlod_cut_update(basic, tree, views, &params, &error) != MLOD_OK) {
            printf("%s: %s: %s\n", label, mlod_result_name(error.code), error.message);
            failed = 1;
        }
    }
    for (v = 0; !failed && v < SMOKE_VIEWS; v++) {
        mlod_cut_view a = mlod_cut_get(basic, v), b = mlod_cut_get(incremental, v);
        if (!smoke_partitions(tree, a) || a.count != b.count ||
            memcmp(a.nodes, b.nodes, a.count * sizeof *a.nodes) != 0) {
            printf("%s: view %u: basic cut of %u nodes, incremental cut of %u nodes differ\n", label, v,
                   a.count, b.count);
            failed = 1;
        }
        for (i = 0; i < a.count; i++) hash = smoke_hash(smoke_hash(hash, a.nodes[i]), a.status[i]);
    }
    mlod_cut_destroy(incremental);
    mlod_cut_destroy(basic);
    mlod_tree_destroy(tree);
    *checksum = hash;
    return failed;
}

#endif
