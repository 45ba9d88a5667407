/* tests/compile/fp_hash.c - one hash of every bit the pipeline computes, for
   the compile matrix's floating-point entries: the same source built with
   other compilers and flags (-O3 -march=native, -ffp-contract=fast, ...)
   must print the same hash, or must not compile at all (flags the header
   refuses).  Written in the common subset of C99 and C++11.

   It builds a tree with cones, areas, colours and refit data on a bumpy
   sheet, refits it to three more poses, cuts it for views of every kind (with
   and without back-face culling) in basic, incremental and lazy mode,
   splats the cut and the ISM baseline with normal and colour channels and
   fills the holes; every float and every node index goes into a 64-bit
   FNV-1a hash, printed as "hash 0123456789abcdef".  Any error prints its
   message and exits 1.

   It holds the implementation with MANYLODS_STATIC, so that the compiler
   may inline the library into this program's code compiled with the same
   flags, as it may in a user's; its own arithmetic is exact under any
   flags (short binary fractions), so only the implementation can change
   the hash. */
#define MANYLODS_STATIC
#define MANYLODS_IMPLEMENTATION
#include "../../manylods.h"

#include <stdio.h>
#include <string.h>

#define FP_GRID 17u
#define FP_VERTICES (FP_GRID * FP_GRID)
#define FP_TRIANGLES (2u * (FP_GRID - 1) * (FP_GRID - 1))
#define FP_VIEWS 8u

static uint64_t fp_hash_bytes(uint64_t hash, const void *data, size_t bytes)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < bytes; i++) hash = (hash ^ p[i]) * 0x100000001b3ull;
    return hash;
}

/* A bumpy sheet of FP_GRID x FP_GRID vertices over [-1, 1]^2 whose heights
   are hashed from (x, z, pose) in steps of 1/32: every coordinate is a short
   binary fraction, so this code computes the same floats under any flags. */
static void fp_sheet(uint32_t pose, float positions[3 * FP_VERTICES], float colors[3 * FP_VERTICES],
                     uint32_t indices[3 * FP_TRIANGLES])
{
    uint32_t i, j, t = 0;
    for (i = 0; i < FP_GRID; i++)
        for (j = 0; j < FP_GRID; j++) {
            uint32_t k = i * FP_GRID + j, h = (i * 73856093u) ^ (j * 19349663u) ^ (pose * 83492791u);
            h = (h ^ (h >> 13)) * 0x5bd1e995u;
            positions[3 * k + 0] = (float)((int)i - (int)(FP_GRID / 2)) / 8.0f;
            positions[3 * k + 1] = (float)((int)((h >> 16) & 15u) - 8) / 32.0f;
            positions[3 * k + 2] = (float)((int)j - (int)(FP_GRID / 2)) / 8.0f;
            colors[3 * k + 0] = (float)i / 16.0f;
            colors[3 * k + 1] = (float)j / 16.0f;
            colors[3 * k + 2] = (float)(h & 3u) / 4.0f;
        }
    for (i = 0; i + 1 < FP_GRID; i++)
        for (j = 0; j + 1 < FP_GRID; j++) {
            uint32_t a = i * FP_GRID + j, quad[6];
            quad[0] = a, quad[1] = a + 1, quad[2] = a + FP_GRID + 1;
            quad[3] = a, quad[4] = a + FP_GRID + 1, quad[5] = a + FP_GRID;
            memcpy(indices + 6 * t++, quad, sizeof quad);
        }
}

/* Views of every kind around and above the sheet (the last two cube
   maps), from short binary fractions as well. */
static void fp_views(uint32_t frame, mlod_view views[FP_VIEWS])
{
    uint32_t v;
    memset(views, 0, FP_VIEWS * sizeof *views);
    for (v = 0; v < FP_VIEWS; v++) {
        mlod_view *view = views + v;
        view->kind = v < 6 ? (mlod_view_kind)(v % 4) : MLOD_VIEW_CUBE;
        view->position[0] = (float)((int)(v % 3) - 1) * 1.5f + (float)frame / 4.0f;
        view->position[1] = 0.75f + (float)v / 4.0f;
        view->position[2] = v & 1u ? 2.5f : -2.25f;
        view->forward[0] = -view->position[0];
        view->forward[1] = -view->position[1];
        view->forward[2] = -view->position[2];
        view->up[1] = 1.0f;
        view->width = view->kind == MLOD_VIEW_CUBE ? 18 + 6 * v : 24 + 4 * v; /* cube: 3s x 2s */
        view->height = view->kind == MLOD_VIEW_CUBE ? 12 + 4 * v : 20 + 2 * v;
        view->fov_y = 1.25f;
        view->near_plane = view->kind == MLOD_VIEW_ORTHOGRAPHIC ? -5.0f : 0.0625f;
        view->far_plane = 50.0f;
        view->half_width = 1.5f;
        view->half_height = 1.25f;
        view->flags = v & 1u ? (uint32_t)MLOD_VIEW_CULL_BACKFACES : 0u;
    }
}

static uint64_t fp_hash_tree(uint64_t hash, const mlod_tree *tree)
{
    hash = fp_hash_bytes(hash, tree->spheres, 4 * sizeof(float) * tree->node_count);
    hash = fp_hash_bytes(hash, tree->cones, 4 * sizeof(float) * tree->node_count);
    hash = fp_hash_bytes(hash, tree->areas, sizeof(float) * tree->node_count);
    return fp_hash_bytes(hash, tree->colors, 3 * sizeof(float) * tree->node_count);
}

static uint64_t fp_hash_cut(uint64_t hash, const mlod_cut *cut)
{
    uint32_t v;
    for (v = 0; v < mlod_cut_view_count(cut); v++) {
        mlod_cut_view c = mlod_cut_get(cut, v);
        hash = fp_hash_bytes(hash, c.nodes, sizeof(uint32_t) * c.count);
        hash = fp_hash_bytes(hash, c.status, c.count);
    }
    return hash;
}

static uint64_t fp_hash_atlas(uint64_t hash, const mlod_atlas *atlas)
{
    size_t pixels = (size_t)atlas->width * atlas->height;
    hash = fp_hash_bytes(hash, atlas->depth, sizeof(float) * pixels);
    hash = fp_hash_bytes(hash, atlas->normal, 3 * sizeof(float) * pixels);
    return fp_hash_bytes(hash, atlas->color, 3 * sizeof(float) * pixels);
}

static int fp_check(mlod_result result, const mlod_error *error)
{
    if (result == MLOD_OK) return 1;
    fprintf(stderr, "fp_hash: %s\n", error->message);
    return 0;
}

int main(void)
{
    static float positions[3 * FP_VERTICES], colors[3 * FP_VERTICES];
    static uint32_t indices[3 * FP_TRIANGLES];
    mlod_view views[FP_VIEWS];
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_cut_params params;
    mlod_atlas_desc atlas_desc;
    mlod_tree *tree = NULL;
    mlod_cut *cut = NULL;
    mlod_atlas *atlas = NULL;
    mlod_error error;
    uint64_t hash = 0xcbf29ce484222325ull;
    int frame, ok;
    const mlod_cut_mode modes[3] = {MLOD_CUT_BASIC, MLOD_CUT_INCREMENTAL, MLOD_CUT_LAZY};

    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    memset(&params, 0, sizeof params);
    memset(&atlas_desc, 0, sizeof atlas_desc);
    memset(&error, 0, sizeof error);
    fp_sheet(0, positions, colors, indices);
    mesh.positions = positions;
    mesh.vertex_count = FP_VERTICES;
    mesh.indices = indices;
    mesh.index_count = 3 * FP_TRIANGLES;
    mesh.colors = colors;
    desc.sample_count = 3000;
    desc.seed = 7;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT;
    params.epsilon = 1.5f;
    params.lazy_steps = 1;
    atlas_desc.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
    atlas_desc.disc_scale = 0.5f;
    fp_views(0, views);

    ok = fp_check(mlod_build_mesh(&mesh, &desc, &tree, &error), &error) &&
         fp_check(mlod_cut_create(FP_VIEWS, NULL, &cut, &error), &error) &&
         fp_check(mlod_atlas_create(views, FP_VIEWS, &atlas_desc, NULL, &atlas, &error), &error);
    if (ok) hash = fp_hash_tree(hash, tree);
    for (frame = 0; ok && frame < 3; frame++) {
        fp_sheet((uint32_t)frame + 1, positions, colors, indices);
        fp_views((uint32_t)frame + 1, views);
        params.mode = modes[frame];
        ok = fp_check(mlod_refit_mesh(tree, &mesh, NULL, &error), &error) &&
             fp_check(mlod_cut_update(cut, tree, views, &params, &error), &error) &&
             fp_check(mlod_splat(atlas, tree, cut, views, NULL, &error), &error);
        if (!ok) break;
        hash = fp_hash_cut(fp_hash_atlas(fp_hash_tree(hash, tree), atlas), cut);
        ok = fp_check(mlod_splat_ism(atlas, tree, views, 400, 3, NULL, &error), &error) &&
             fp_check(mlod_atlas_fill_holes(atlas, NULL, &error), &error);
        if (ok) hash = fp_hash_atlas(hash, atlas);
    }
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
    if (!ok) return 1;
    printf("hash %016llx\n", (unsigned long long)hash);
    return 0;
}
