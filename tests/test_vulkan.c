/* tests/test_vulkan.c - manylods_vk.h against the CPU path of manylods.h.

   On a headless device (lavapipe in CI) with the Khronos validation layer:
   cuts of every view kind and mode equal the CPU's node for node and
   status for status, over frames whose views move (incremental and lazy
   continue from the previous frame's cut); lists that outgrow their
   buffers grow and resume with the same result; the splatted atlas equals
   mlod_splat's bit for bit (depth, normal, colour), with tangent discs (the
   default for a tree with cones) and sphere discs, and MegaViews' atlas
   mlod_megaviews_render's likewise; errors from the
   Vulkan functions (out of memory, device loss) come back as results and
   leave every object destroyable.  Any validation message fails the test.

   Without a Vulkan loader or device it prints why and reports no test
   (0 passed, 0 failed) - unless MANYLODS_REQUIRE_VULKAN=1 (CI), which
   turns the skip into a failure.

     test_vulkan [native] [emulated]    both groups (none named), or those named

   native: every test on a context with the device's doubles; emulated: the
   parity tests again on a context with doubles from 32-bit integers.  make
   test runs the two as two programs, side by side.  The emulated group run
   alone has lavapipe compile its shaders without LLVM's optimisation passes
   (GALLIVM_PERF=nopt, unless the caller set GALLIVM_PERF): compiling is
   nearly all of its time, 491 s of processor time with the passes and 348 s
   without (Mesa 22.3, LLVM 15, no shader cache; the cut's pipelines 250 s
   and 50 s, the refit's 28 s and 137 s), and what it compares, the bits of
   the results, must be the same either way. */
#define _POSIX_C_SOURCE 200112L /* posix_memalign */
#include <stdlib.h>

/* MANYLODS_MALLOC/FREE count the blocks: the Vulkan objects' host memory
   must come from them when the context is given no allocator. */
static long default_blocks, default_live;
static void *counted_malloc(size_t bytes)
{
    void *p = malloc(bytes);
    default_blocks += p != NULL;
    default_live += p != NULL;
    return p;
}
static void counted_free(void *p)
{
    default_live -= p != NULL;
    free(p);
}
#define MANYLODS_MALLOC(size, user) ((void)(user), counted_malloc(size))
#define MANYLODS_FREE(pointer, user) ((void)(user), counted_free(pointer))
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"

#include "testutil.h"
#include "vkutil.h"

#include <time.h>

static double seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char *name);

static mlodvk_device device;
static mlodvk_context *context;
/* The parity tests at a smaller size (fewer samples, views, modes): for
   the context with emulated doubles, whose every double operation costs
   lavapipe tens to hundreds of integer instructions. */
static int lean;

/* A validation message since the last call fails the named step. */
static uint32_t validation_seen = 0;

static void check_validation(const char *what)
{
    CHECK(device.validation_messages == validation_seen, "%s: %u validation message(s), the last: %s", what,
          device.validation_messages - validation_seen, device.last_message);
    validation_seen = device.validation_messages;
}

/* Views of one kind (or of all kinds in turn when kind < 0) around the
   scene, as the CPU tests draw them. */
#define VIEW_KINDS 5 /* perspective .. cube map */

/* A cube map's tile of about the view's size: 3s x 2s. */
static void fit_tile(mlod_view *v)
{
    uint32_t side;
    if (v->kind != MLOD_VIEW_CUBE) return;
    side = v->height / 2 ? v->height / 2 : 1;
    v->width = 3 * side;
    v->height = 2 * side;
}

static void make_views(uint64_t seed, int kind, const double *c, double R, mlod_view *views, uint32_t count)
{
    uint64_t rng = seed;
    uint32_t v;
    for (v = 0; v < count; v++) {
        mlod_view_kind k = kind < 0 ? (mlod_view_kind)(v % VIEW_KINDS) : (mlod_view_kind)kind;
        views[v] = tu_random_view(&rng, k, c, R);
        views[v].width = 8 + views[v].width / 4; /* small tiles: deep cuts stay cheap */
        views[v].height = 8 + views[v].height / 4;
        fit_tile(&views[v]);
    }
}

/* Move every view a little (the next frame). */
static void move_views(mlod_view *views, uint32_t count, double step)
{
    uint32_t v;
    for (v = 0; v < count; v++) {
        views[v].position[0] += (float)(step * ((v % 3) - 1.0));
        views[v].position[1] += (float)(step * 0.5);
        views[v].forward[0] += (float)(0.05 * ((v % 5) - 2.0));
    }
}

/* Download the device cut and compare every view with the CPU cut;
   returns the number of views that differ (the first one is reported). */
static uint32_t compare_cuts(mlodvk_cut *gpu, const mlod_cut *cpu, uint32_t view_count, const char *what)
{
    mlod_error e;
    uint32_t v, differ = 0;
    if (mlodvk_cut_download(context, gpu, &e) != MLOD_OK) {
        CHECK(0, "%s: mlodvk_cut_download: %s", what, e.message);
        return view_count;
    }
    for (v = 0; v < view_count; v++) {
        mlod_cut_view a = mlodvk_cut_get(gpu, v), b = mlod_cut_get(cpu, v);
        if (!tu_same_cut(&a, &b)) {
            if (!differ) {
                uint32_t i = 0;
                while (i < a.count && i < b.count && a.nodes[i] == b.nodes[i] && a.status[i] == b.status[i]) i++;
                fprintf(stderr, "  %s: view %u: device %u entries, CPU %u; first difference at %u: device %u/%u, CPU %u/%u\n",
                        what, v, a.count, b.count, i, i < a.count ? a.nodes[i] : 0, i < a.count ? a.status[i] : 0,
                        i < b.count ? b.nodes[i] : 0, i < b.count ? b.status[i] : 0);
            }
            differ++;
        }
    }
    return differ;
}

/* Frames of one mode on the device and on the CPU; every frame's cuts
   must be equal.  Returns the total number of entries compared; adds the
   entries the device's float filter deferred to the exact pass to
   *deferred (when not NULL). */
static uint64_t run_mode(const mlod_tree *tree, mlodvk_tree *vtree, mlod_view *views, uint32_t view_count,
                         mlod_cut_mode mode, uint32_t lazy_steps, float epsilon, uint32_t initial_capacity,
                         const char *name, uint32_t *grows, uint64_t *deferred)
{
    mlod_cut *cpu = NULL;
    mlodvk_cut *gpu = NULL;
    mlod_cut_params p;
    mlod_error e;
    uint64_t compared = 0;
    int frame;
    memset(&p, 0, sizeof p);
    p.epsilon = epsilon;
    p.lazy_steps = lazy_steps;
    if (mlod_cut_create(view_count, NULL, &cpu, &e) != MLOD_OK ||
        mlodvk_cut_create(context, view_count, initial_capacity, &gpu, &e) != MLOD_OK) {
        CHECK(0, "%s: cut_create: %s", name, e.message);
        mlod_cut_destroy(cpu);
        return 0;
    }
    for (frame = 0; frame < 4; frame++) {
        char what[160];
        uint32_t differ, v;
        p.mode = frame == 0 ? MLOD_CUT_BASIC : mode;
        snprintf(what, sizeof what, "%s, frame %d", name, frame);
        if (mlod_cut_update(cpu, tree, views, &p, &e) != MLOD_OK) {
            CHECK(0, "%s: mlod_cut_update: %s", what, e.message);
            break;
        }
        if (mlodvk_cut_update(context, gpu, vtree, views, &p, &e) != MLOD_OK) {
            CHECK(0, "%s: mlodvk_cut_update: %s", what, e.message);
            break;
        }
        if (deferred) *deferred += mlodvk_cut_get_info(gpu).deferred;
        differ = compare_cuts(gpu, cpu, view_count, what);
        CHECK(differ == 0, "%s: %u of %u views differ from the CPU cut", what, differ, view_count);
        for (v = 0; v < view_count; v++) compared += mlod_cut_get(cpu, v).count;
        move_views(views, view_count, 0.02);
    }
    if (grows) *grows = mlodvk_cut_get_info(gpu).grows;
    mlodvk_cut_destroy(context, gpu);
    mlod_cut_destroy(cpu);
    return compared;
}

static void test_cut_parity(void)
{
    static const char *kinds[VIEW_KINDS + 1] = {"perspective", "paraboloid", "dual paraboloid", "orthographic",
                                                "cube map", "mixed"};
    static const char *modes[4] = {"basic", "incremental", "lazy q=1", "lazy q=3"};
    static const float epsilons[2] = {1.0f, 4.0f};
    scene_mesh s;
    mlod_tree *tree;
    mlodvk_tree *vtree = NULL;
    mlod_error e;
    double c[3], R;
    int kind, m, ei;
    uint64_t compared = 0, deferred = 0;
    if (!scene_torus(&s, 1.0f, 0.35f, 48, 24)) {
        CHECK(0, "scene_torus failed");
        return;
    }
    tree = tu_build(&s, lean ? 3000 : 30000, 5, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    tu_bounds(&s, c, &R);
    if (!tree || mlodvk_tree_upload(context, tree, &vtree, &e) != MLOD_OK) {
        CHECK(0, "tree upload: %s", tree ? e.message : "build failed");
        mlod_tree_destroy(tree);
        scene_free(&s);
        return;
    }
    for (kind = 0; kind <= VIEW_KINDS; kind++)
        for (m = 0; m < (lean ? 2 : 4); m++)
            for (ei = lean; ei < 2; ei++) {
                mlod_view views[24];
                char name[120];
                static const mlod_cut_mode mode_of[4] = {MLOD_CUT_BASIC, MLOD_CUT_INCREMENTAL, MLOD_CUT_LAZY, MLOD_CUT_LAZY};
                make_views(1000u * (uint64_t)kind + 17u * (uint64_t)m + (uint64_t)ei, kind == VIEW_KINDS ? -1 : kind, c, R,
                           views, 24);
                snprintf(name, sizeof name, "%s, %s, eps %g", kinds[kind], modes[m], (double)epsilons[ei]);
                compared += run_mode(tree, vtree, views, lean ? 4 : 24, mode_of[m], m == 3 ? 3u : 1u, epsilons[ei], 0,
                                     name, NULL, &deferred);
                check_validation(name);
            }
    if (!lean) { /* lazy_steps 2^32 - 1: the device's rounds go in batches, as the other modes' do (one command
                    buffer of 2^32 rounds once hung the call), and the cuts converge as the CPU's (host code: with
                    the device's doubles only) */
        mlod_view views[24];
        make_views(97, -1, c, R, views, 24);
        compared += run_mode(tree, vtree, views, 24, MLOD_CUT_LAZY, 0xffffffffu, 1.0f, 0, "lazy, lazy_steps 2^32 - 1",
                             NULL, NULL);
        check_validation("lazy, lazy_steps 2^32 - 1");
    }
    printf("  cut parity: %llu cut entries compared over %d view sets x %d modes x %d epsilons x 4 frames; "
           "%llu entries took the exact pass (cut_exact)\n",
           (unsigned long long)compared, VIEW_KINDS + 1, lean ? 2 : 4, lean ? 1 : 2, (unsigned long long)deferred);
    /* the equal cuts above went through both passes: entries the float
       filter decided alone, and entries it deferred */
    CHECK(deferred > 0, "cut parity: no entry took the exact pass (cut_exact untested)");
    /* every dispatch folded into rows of one workgroup: the exact pass's
       single workgroup takes the deferred entries a workgroup's worth at a
       time; the same cuts */
    {
        mlod_view views[24];
        uint32_t *max_x = &context->properties.limits.maxComputeWorkGroupCount[0], kept = *max_x;
        uint64_t folded = 0;
        *max_x = 1;
        make_views(96, -1, c, R, views, 24);
        run_mode(tree, vtree, views, 24, MLOD_CUT_INCREMENTAL, 1, 1.0f, 0, "rows of one workgroup, incremental", NULL,
                 &folded);
        CHECK(folded > 4, "rows of one workgroup: %llu entries deferred (expected several)", (unsigned long long)folded);
        check_validation("rows of one workgroup");
        /* an epsilon so far below a pixel that no view has a float filter
           (mlod_view_filter_of's OK 0): every entry a round evaluates is
           deferred, rounds list more of them than a workgroup holds, and
           the single workgroup of each exact pass takes them a workgroup's
           worth at a time; the same cuts.  With the device's doubles only
           (the emulated ones would take minutes) */
        if (!lean) {
            mlod_tree *small = tu_build(&s, 600, 7, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
            mlodvk_tree *vsmall = NULL;
            uint64_t unfiltered = 0;
            if (!small || mlodvk_tree_upload(context, small, &vsmall, &e) != MLOD_OK) {
                CHECK(0, "rows of one workgroup, no filter: tree upload: %s", small ? e.message : "build failed");
            } else {
                run_mode(small, vsmall, views, 24, MLOD_CUT_BASIC, 1, 1e-13f, 0, "rows of one workgroup, no filter",
                         NULL, &unfiltered);
                /* 4 frames of at most depth + 4 rounds each: more than a
                   workgroup's worth in some round */
                uint64_t bound = 4 * (uint64_t)(tu_depth(small->node_count - 1) + 4) * 256;
                CHECK(unfiltered > bound,
                      "rows of one workgroup, no filter: %llu entries deferred (expected more than %llu)",
                      (unsigned long long)unfiltered, (unsigned long long)bound);
                printf("  rows of one workgroup, no filter: %llu entries deferred (%u leaves, 24 views, 4 frames)\n",
                       (unsigned long long)unfiltered, small->leaf_count);
                check_validation("rows of one workgroup, no filter");
            }
            mlodvk_tree_destroy(context, vsmall);
            mlod_tree_destroy(small);
        }
        *max_x = kept;
    }
    /* a list that outgrows its buffers: start with room for one entry per
       view; the loop stops, grows and resumes, with the same cuts */
    {
        mlod_view views[24];
        uint32_t grows = 0;
        make_views(99, -1, c, R, views, 24);
        run_mode(tree, vtree, views, 24, MLOD_CUT_INCREMENTAL, 1, 1.0f, 24, "growing lists, incremental", &grows, NULL);
        CHECK(grows >= 3, "growing lists: %u grows (expected several from a capacity of 24 entries)", grows);
        make_views(98, -1, c, R, views, 24);
        grows = 0;
        run_mode(tree, vtree, views, 24, MLOD_CUT_LAZY, 2, 1.0f, 30, "growing lists, lazy q=2", &grows, NULL);
        CHECK(grows >= 1, "growing lists, lazy: %u grows (expected at least one)", grows);
        check_validation("growing lists");
    }
    /* a refit on the CPU, uploaded with mlodvk_tree_update: incremental
       cuts continue and still equal the CPU's */
    {
        mlod_view views[24];
        mlod_cut *cpu = NULL;
        mlodvk_cut *gpu = NULL;
        mlod_cut_params p;
        memset(&p, 0, sizeof p);
        p.epsilon = 2.0f;
        make_views(7, -1, c, R, views, 24);
        if (mlod_cut_create(24, NULL, &cpu, &e) == MLOD_OK && mlodvk_cut_create(context, 24, 0, &gpu, &e) == MLOD_OK) {
            int frame;
            float *positions = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
            float *normals = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
            for (frame = 0; frame < 3 && positions && normals; frame++) {
                p.mode = frame == 0 ? MLOD_CUT_BASIC : MLOD_CUT_INCREMENTAL;
                if (frame > 0) {
                    mlod_mesh mesh = tu_mesh(&s);
                    scene_deform(&s, 0.2f * (float)frame, positions, normals);
                    mesh.positions = positions;
                    mesh.normals = normals;
                    CHECK(mlod_refit_mesh(tree, &mesh, NULL, &e) == MLOD_OK, "refit: %s", e.message);
                    CHECK(mlodvk_tree_update(context, vtree, tree, &e) == MLOD_OK, "mlodvk_tree_update: %s", e.message);
                }
                CHECK(mlod_cut_update(cpu, tree, views, &p, &e) == MLOD_OK, "refit frames: %s", e.message);
                CHECK(mlodvk_cut_update(context, gpu, vtree, views, &p, &e) == MLOD_OK, "refit frames: %s", e.message);
                CHECK(compare_cuts(gpu, cpu, 24, "after a refit") == 0, "refit frame %d: the cuts differ", frame);
            }
            free(positions);
            free(normals);
        } else {
            CHECK(0, "refit frames: cut_create: %s", e.message);
        }
        mlodvk_cut_destroy(context, gpu);
        mlod_cut_destroy(cpu);
        check_validation("refit frames");
    }
    mlodvk_tree_destroy(context, vtree);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* The device atlas equals mlod_splat's, pixel for pixel, for every kind,
   with whole discs (disc_scale 1) and with half discs (0.5: no fallback
   pixel for discs that cover no pixel centre), as tangent discs (the
   default, MLOD_SPLAT_AUTO, for the room's tree with cones); then the same
   tree's sphere discs (MLOD_SPLAT_SPHERES), the views of every kind at
   once, at disc_scale 1 (and 0.5, except with emulated doubles). */
/* The room scene's tree of n leaves with cones and colours, uploaded, and
   its bounds (c, R); 0, the failure checked and nothing held, on failure. */
static int room_tree(scene_mesh *s, uint32_t n, const char *what, mlod_tree **tree, mlodvk_tree **vtree, double *c,
                     double *R)
{
    mlod_error e;
    *tree = NULL;
    *vtree = NULL;
    if (!scene_room(s)) {
        CHECK(0, "%s: scene_room failed", what);
        return 0;
    }
    *tree = tu_build(s, n, 9, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    tu_bounds(s, c, R);
    if (!*tree || mlodvk_tree_upload(context, *tree, vtree, &e) != MLOD_OK) {
        CHECK(0, "%s: tree upload: %s", what, *tree ? e.message : "build failed");
        mlod_tree_destroy(*tree);
        scene_free(s);
        return 0;
    }
    return 1;
}

/* The basic cut and splat of these views on the CPU and on the device
   (downloaded): two new atlases (the caller destroys them, also on
   failure) and the pixels whose depth, normal or colour differ (diffs[0 ..
   2]; a channel the atlas lacks counts none), and the CPU's drawn pixels.
   0 when a call fails, with e's message. */
static int splat_on_both(const mlod_tree *tree, const mlodvk_tree *vtree, const mlod_view *views, uint32_t count,
                         const mlod_atlas_desc *ad, const mlod_cut_params *p, mlod_atlas **cpu_atlas,
                         mlod_atlas **gpu_atlas, size_t diffs[3], size_t *drawn, mlod_error *e)
{
    mlodvk_atlas *vatlas = NULL;
    mlod_cut *cpu = NULL;
    mlodvk_cut *gpu = NULL;
    size_t i, pixels;
    int ok;
    *cpu_atlas = *gpu_atlas = NULL;
    diffs[0] = diffs[1] = diffs[2] = *drawn = 0;
    ok = mlod_atlas_create(views, count, ad, NULL, cpu_atlas, e) == MLOD_OK &&
         mlod_atlas_create(views, count, ad, NULL, gpu_atlas, e) == MLOD_OK &&
         mlodvk_atlas_create(context, *cpu_atlas, &vatlas, e) == MLOD_OK && mlod_cut_create(count, NULL, &cpu, e) == MLOD_OK &&
         mlodvk_cut_create(context, count, 0, &gpu, e) == MLOD_OK && mlod_cut_update(cpu, tree, views, p, e) == MLOD_OK &&
         mlodvk_cut_update(context, gpu, vtree, views, p, e) == MLOD_OK &&
         mlod_splat(*cpu_atlas, tree, cpu, views, NULL, e) == MLOD_OK && mlodvk_splat(context, vatlas, vtree, gpu, e) == MLOD_OK &&
         mlodvk_atlas_download(context, vatlas, *gpu_atlas, e) == MLOD_OK;
    if (ok) {
        const mlod_atlas *a = *cpu_atlas, *b = *gpu_atlas;
        pixels = (size_t)a->width * a->height;
        for (i = 0; i < pixels; i++) {
            *drawn += isfinite(a->depth[i]);
            diffs[0] += memcmp(&a->depth[i], &b->depth[i], sizeof(float)) != 0;
            diffs[1] += a->normal && memcmp(a->normal + 3 * i, b->normal + 3 * i, 3 * sizeof(float)) != 0;
            diffs[2] += a->color && memcmp(a->color + 3 * i, b->color + 3 * i, 3 * sizeof(float)) != 0;
        }
    }
    mlodvk_atlas_destroy(context, vatlas);
    mlodvk_cut_destroy(context, gpu);
    mlod_cut_destroy(cpu);
    return ok;
}

static void test_splat_parity(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlodvk_tree *vtree = NULL;
    mlod_error e;
    double c[3], R;
    /* the rounds from first_spheres on (one with emulated doubles, two else) draw sphere discs, of mixed kinds */
    int kind, round, first_spheres = lean ? VIEW_KINDS + 2 : 2 * (VIEW_KINDS + 1);
    if (!room_tree(&s, lean ? 4000 : 40000, "splat", &tree, &vtree, c, &R)) return;
    for (round = 0; round < first_spheres + (lean ? 1 : 2); round++) {
        int spheres = round >= first_spheres;
        float disc_scale = spheres ? (round > first_spheres ? 0.5f : 0.0f) : round <= VIEW_KINDS ? 0.0f : 0.5f;
        const char *splat = spheres ? "spheres" : "tangent";
        mlod_view views[16];
        mlod_atlas_desc ad;
        mlod_atlas *cpu_atlas = NULL, *gpu_atlas = NULL;
        mlod_cut_params p;
        uint32_t v;
        size_t diffs[3], drawn;
        kind = spheres ? VIEW_KINDS : round % (VIEW_KINDS + 1);
        memset(&p, 0, sizeof p);
        p.mode = MLOD_CUT_BASIC;
        p.epsilon = kind == VIEW_KINDS ? 3.0f : 1.0f;
        make_views(500u + (uint64_t)kind, kind == VIEW_KINDS ? -1 : kind, c, R, views, 16);
        for (v = 0; v < 16; v++) { /* larger tiles than the cut tests */
            views[v].width = lean ? 8 + (views[v].width * 3) % 16 : 16 + (views[v].width * 3) % 48;
            views[v].height = lean ? 8 + (views[v].height * 5) % 16 : 16 + (views[v].height * 5) % 48;
            fit_tile(&views[v]);
        }
        memset(&ad, 0, sizeof ad);
        ad.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
        ad.disc_scale = disc_scale;
        ad.splat = spheres ? MLOD_SPLAT_SPHERES : MLOD_SPLAT_AUTO;
        if (!splat_on_both(tree, vtree, views, 16, &ad, &p, &cpu_atlas, &gpu_atlas, diffs, &drawn, &e)) {
            CHECK(0, "splat parity, %s, kind %d, disc_scale %g: set-up failed: %s", splat, kind, (double)disc_scale,
                  e.message);
        } else {
            size_t pixels = (size_t)cpu_atlas->width * cpu_atlas->height;
            CHECK(drawn > pixels / 20, "splat parity, %s, kind %d, disc_scale %g: only %zu of %zu pixels drawn", splat,
                  kind, (double)disc_scale, drawn, pixels);
            CHECK(diffs[0] == 0 && diffs[1] == 0 && diffs[2] == 0,
                  "splat parity, %s, kind %d, disc_scale %g: %zu depth, %zu normal, %zu colour pixels of %zu differ",
                  splat, kind, (double)disc_scale, diffs[0], diffs[1], diffs[2], pixels);
        }
        mlod_atlas_destroy(cpu_atlas);
        mlod_atlas_destroy(gpu_atlas);
        check_validation("splat parity");
    }
    mlodvk_tree_destroy(context, vtree);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* Equal depths: the device keeps the least (depth, node) of a pixel's
   draws, as mlod_splat does (the lower node index wins).  Points on one
   plane facing orthographic views, so that every node's centre lies at
   one depth and most shared pixels are ties; sphere discs; cuts of mixed
   levels.  The atlases must be equal bit for bit, node (colour) for
   node; the CPU's rule itself is tested against a reference in
   tests/test_splat.c (ties). */
static void test_tie_parity(void)
{
    enum { N = 3000, V = 8 };
    static float pos[3 * N], rad[N], col[3 * N];
    uint64_t rng = 0x71e5ull;
    mlod_points pts;
    mlod_build_desc bd = tu_desc(0, 1, MLOD_ATTR_COLOR);
    mlod_tree *tree = NULL;
    mlodvk_tree *vtree = NULL;
    mlod_view views[V];
    mlod_atlas_desc ad;
    mlod_atlas *cpu_atlas = NULL, *gpu_atlas = NULL;
    mlod_cut_params p;
    mlod_error e;
    uint32_t i, v;
    size_t diffs[3], drawn;
    for (i = 0; i < N; i++) {
        pos[3 * i] = (float)(2.0 * scene_rng_double(&rng) - 1.0);
        pos[3 * i + 1] = (float)(2.0 * scene_rng_double(&rng) - 1.0);
        pos[3 * i + 2] = -2.0f; /* one depth for every centre */
        rad[i] = (float)(0.01 + 0.04 * scene_rng_double(&rng));
        col[3 * i] = (float)i; /* the colour names the leaf; inner nodes' means differ too */
        col[3 * i + 1] = col[3 * i + 2] = 0.5f;
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.count = N;
    pts.radii = rad;
    pts.colors = col;
    for (v = 0; v < V; v++) {
        views[v] = tu_view(MLOD_VIEW_ORTHOGRAPHIC);
        views[v].position[0] = (float)(0.8 * scene_rng_double(&rng) - 0.4);
        views[v].position[1] = (float)(0.8 * scene_rng_double(&rng) - 0.4);
        views[v].width = views[v].height = lean ? 24 : 40;
        views[v].half_width = views[v].half_height = (float)(0.3 + 0.5 * scene_rng_double(&rng));
    }
    memset(&p, 0, sizeof p);
    p.mode = MLOD_CUT_BASIC;
    p.epsilon = 2.0f;
    memset(&ad, 0, sizeof ad);
    ad.channels = MLOD_ATLAS_COLOR;
    ad.splat = MLOD_SPLAT_SPHERES;
    if (mlod_build_points(&pts, &bd, &tree, &e) != MLOD_OK || mlodvk_tree_upload(context, tree, &vtree, &e) != MLOD_OK ||
        !splat_on_both(tree, vtree, views, V, &ad, &p, &cpu_atlas, &gpu_atlas, diffs, &drawn, &e)) {
        CHECK(0, "tie parity: set-up failed: %s", e.message);
    } else {
        size_t pixels = (size_t)cpu_atlas->width * cpu_atlas->height;
        CHECK(drawn > pixels / 2, "tie parity: only %zu of %zu pixels drawn", drawn, pixels);
        CHECK(diffs[0] == 0 && diffs[2] == 0, "tie parity: %zu depth, %zu colour pixels of %zu differ", diffs[0],
              diffs[2], pixels);
    }
    mlod_atlas_destroy(cpu_atlas);
    mlod_atlas_destroy(gpu_atlas);
    mlodvk_tree_destroy(context, vtree);
    mlod_tree_destroy(tree);
    check_validation("tie parity");
}

/* Bit-for-bit equal bounds (spheres, cones, colours) of two trees of one
   shape; returns the number of nodes that differ. */
static uint32_t differing_nodes(const mlod_tree *a, const mlod_tree *b)
{
    uint32_t n, differ = 0;
    for (n = 0; n < a->node_count; n++)
        differ += memcmp(a->spheres + 4 * (size_t)n, b->spheres + 4 * (size_t)n, 16) != 0 ||
                  (a->cones && memcmp(a->cones + 4 * (size_t)n, b->cones + 4 * (size_t)n, 16) != 0) ||
                  (a->colors && memcmp(a->colors + 3 * (size_t)n, b->colors + 3 * (size_t)n, 12) != 0);
    return differ;
}

/* Two-sided sheets, turned to no particular axis: a grid and the same grid
   wound the other way, tilted by 1e-11, 1e-9 or 1e-4 rad (so that leaves of nearly opposite normals
   merge: the cone merge's measured case, where the direction between the
   axes is least accurate).  The device refit gives the CPU's bounds bit for
   bit, and such merges do occur. */
static void test_opposite_cone_parity(void)
{
    static const float tilts[3] = {1e-11f, 1e-9f, 1e-4f};
    const uint32_t G = 24, per = (G + 1) * (G + 1);
    int t;
    for (t = 0; t < 3; t++) {
        scene_mesh s;
        mlod_tree *cpu = NULL, *copy = NULL;
        mlodvk_tree *vtree = NULL;
        mlod_error e;
        uint32_t side, i, j, n, opposite = 0, differ;
        if (!scene_alloc(&s, 2 * per, 2 * 6 * G * G, 0, 1)) {
            CHECK(0, "opposite cones: scene_alloc failed");
            return;
        }
        for (side = 0; side < 2; side++)
            for (j = 0; j <= G; j++)
                for (i = 0; i <= G; i++) {
                    uint32_t v = side * per + j * (G + 1) + i;
                    double x = (double)i / G, y = (double)j / G, z = side ? tilts[t] * x : 0.0;
                    /* turned to no particular axis (cos, sin of 0.4 about x, 0.7 about y) */
                    double y1 = 0.921060994 * y - 0.389418342 * z, z1 = 0.389418342 * y + 0.921060994 * z;
                    scene_set3(s.positions, v, 0.764842187 * x + 0.644217687 * z1, y1, -0.644217687 * x + 0.764842187 * z1);
                    scene_set3(s.colors, v, (float)x, (float)y, (float)side);
                }
        for (side = 0, n = 0; side < 2; side++)
            for (j = 0; j < G; j++)
                for (i = 0; i < G; i++) {
                    uint32_t a = side * per + j * (G + 1) + i, b = a + 1, c = a + G + 1, d = c + 1;
                    uint32_t q[6] = {a, b, d, a, d, c}, k;
                    for (k = 0; k < 6; k++) s.indices[n++] = side ? q[5 - k] : q[k];
                }
        cpu = tu_build(&s, 6000, 3, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
        copy = tu_build(&s, 6000, 3, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
        if (!cpu || !copy || mlodvk_tree_upload(context, cpu, &vtree, &e) != MLOD_OK ||
            mlodvk_tree_upload_refit(context, vtree, cpu, s.indices, s.index_count, &e) != MLOD_OK) {
            CHECK(0, "opposite cones: set-up failed: %s", cpu && copy ? e.message : "build failed");
        } else {
            mlod_mesh mesh = tu_mesh(&s);
            for (i = 0; 2 * i + 2 < cpu->node_count; i++) { /* parents of two leaves of nearly opposite normals */
                const float *l = cpu->cones + 4 * (2 * (size_t)i + 1), *r = cpu->cones + 4 * (2 * (size_t)i + 2);
                opposite += l[3] == 0.0f && r[3] == 0.0f && l[0] * r[0] + l[1] * r[1] + l[2] * r[2] < -0.999999f;
            }
            CHECK(mlod_refit_mesh(cpu, &mesh, NULL, &e) == MLOD_OK, "opposite cones: mlod_refit_mesh: %s", e.message);
            CHECK(mlodvk_refit_mesh_host(context, vtree, &mesh, &e) == MLOD_OK, "opposite cones: device refit: %s",
                  e.message);
            CHECK(mlodvk_tree_download(context, vtree, copy, &e) == MLOD_OK, "opposite cones: download: %s", e.message);
            differ = differing_nodes(cpu, copy);
            CHECK(opposite > 10, "opposite cones, tilt %g: only %u merges of nearly opposite leaves", (double)tilts[t],
                  opposite);
            CHECK(differ == 0, "opposite cones, tilt %g: %u of %u nodes differ from the CPU refit", (double)tilts[t], differ,
                  cpu->node_count);
            tu_check_containment(cpu, "opposite cones (CPU refit)");
        }
        check_validation("opposite cone parity");
        mlodvk_tree_destroy(context, vtree);
        mlod_tree_destroy(cpu);
        mlod_tree_destroy(copy);
        scene_free(&s);
    }
}

/* mlodvk_refit_mesh against mlod_refit_mesh: the same bounds bit for bit,
   with and without vertex normals, and the same cuts on the refitted
   trees; bad input is refused with the device tree untouched. */
static void test_refit_parity(void)
{
    scene_mesh s;
    int with_normals;
    if (!scene_torus(&s, 1.0f, 0.4f, lean ? 20 : 40, lean ? 10 : 20)) {
        CHECK(0, "scene_torus failed");
        return;
    }
    for (with_normals = 0; with_normals < 2; with_normals++) {
        uint32_t attributes = MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT;
        scene_mesh rest = s;
        mlod_tree *cpu, *copy;
        mlodvk_tree *vtree = NULL;
        mlod_error e;
        float *positions = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
        float *normals = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
        double c[3], R;
        int frame;
        if (!with_normals) rest.normals = NULL;
        cpu = tu_build(&rest, 20000, 11, attributes);
        copy = tu_build(&rest, 20000, 11, attributes); /* the same tree: downloads land here */
        tu_bounds(&s, c, &R);
        if (!cpu || !copy || !positions || !normals || mlodvk_tree_upload(context, cpu, &vtree, &e) != MLOD_OK ||
            mlodvk_tree_upload_refit(context, vtree, cpu, s.indices, s.index_count, &e) != MLOD_OK) {
            CHECK(0, "refit parity: set-up failed: %s", e.message);
        } else {
            mlod_cut *cut = NULL;
            mlodvk_cut *vcut = NULL;
            mlod_view views[16];
            mlod_cut_params p;
            memset(&p, 0, sizeof p);
            p.epsilon = 1.5f;
            make_views(77, -1, c, R, views, 16);
            CHECK(mlod_cut_create(16, NULL, &cut, &e) == MLOD_OK && mlodvk_cut_create(context, 16, 0, &vcut, &e) == MLOD_OK,
                  "refit parity: cut_create: %s", e.message);
            for (frame = 1; frame <= 3 && cut && vcut; frame++) {
                mlod_mesh mesh = tu_mesh(&rest);
                uint32_t differ;
                scene_deform(&s, 0.7f * (float)frame, positions, normals);
                mesh.positions = positions;
                mesh.normals = with_normals ? normals : NULL;
                CHECK(mlod_refit_mesh(cpu, &mesh, NULL, &e) == MLOD_OK, "refit parity: mlod_refit_mesh: %s", e.message);
                CHECK(mlodvk_refit_mesh_host(context, vtree, &mesh, &e) == MLOD_OK, "refit parity: mlodvk_refit_mesh_host: %s",
                      e.message);
                CHECK(mlodvk_tree_download(context, vtree, copy, &e) == MLOD_OK, "refit parity: download: %s", e.message);
                differ = differing_nodes(cpu, copy);
                CHECK(differ == 0, "refit parity (%s normals), frame %d: %u of %u nodes differ from the CPU refit",
                      with_normals ? "vertex" : "face", frame, differ, cpu->node_count);
                p.mode = frame == 1 ? MLOD_CUT_BASIC : MLOD_CUT_INCREMENTAL;
                CHECK(mlod_cut_update(cut, cpu, views, &p, &e) == MLOD_OK, "refit parity: cut: %s", e.message);
                CHECK(mlodvk_cut_update(context, vcut, vtree, views, &p, &e) == MLOD_OK, "refit parity: cut: %s", e.message);
                CHECK(compare_cuts(vcut, cut, 16, "refit parity") == 0, "refit parity, frame %d: the cuts differ", frame);
                move_views(views, 16, 0.03);
            }
            /* refused input: a NaN position, a triangle grown 1e60 times;
               the device tree keeps the last frame's bounds */
            {
                mlod_mesh mesh = tu_mesh(&rest);
                mlod_result res;
                float saved = positions[3 * 5 + 1];
                mesh.positions = positions;
                mesh.normals = with_normals ? normals : NULL;
                positions[3 * 5 + 1] = NAN;
                res = mlodvk_refit_mesh_host(context, vtree, &mesh, &e);
                CHECK(res == MLOD_ERROR_NON_FINITE && strstr(e.message, "position 5"),
                      "refit parity: a NaN position gives %s (%s)", mlod_result_name(res), e.message);
                positions[3 * 5 + 1] = saved;
                {
                    uint32_t v;
                    for (v = 0; v < s.vertex_count; v++) positions[3 * v] *= 1e35f; /* areas grow ~1e35 times */
                }
                res = mlodvk_refit_mesh_host(context, vtree, &mesh, &e);
                CHECK(res == MLOD_ERROR_RANGE, "refit parity: a mesh grown 1e35 times gives %s (%s)", mlod_result_name(res), e.message);
                res = mlod_refit_mesh(cpu, &mesh, NULL, &e);
                CHECK(res == MLOD_ERROR_RANGE, "refit parity: the CPU refit of the grown mesh gives %s", mlod_result_name(res));
                mesh.position_stride = 4; /* overlapping vertices: mlod_mesh's stride rule */
                res = mlodvk_refit_mesh_host(context, vtree, &mesh, &e);
                CHECK(res == MLOD_ERROR_INVALID_ARGUMENT, "refit parity: a stride of 4 bytes gives %s (%s)",
                      mlod_result_name(res), e.message);
                mesh.position_stride = 0;
                { /* a stride whose last vertex lies past 2^32 floats: the shaders' 32-bit index would wrap */
                    mlodvk_mesh_buffers mb;
                    memset(&mb, 0, sizeof mb);
                    mb.positions = mlodvk_cut_get_buffers(vcut).list; /* any buffers: refused before they are bound */
                    mb.colors = mb.positions;
                    mb.position_stride = 0x80000000u;
                    res = mlodvk_refit_mesh(context, vtree, &mb, &e);
                    CHECK(res == MLOD_ERROR_OVERFLOW, "refit parity: a stride of 2^31 floats for %u vertices gives %s (%s)",
                          s.vertex_count, mlod_result_name(res), e.message);
                }
                CHECK(mlodvk_tree_download(context, vtree, copy, &e) == MLOD_OK && differing_nodes(cpu, copy) == 0,
                      "refit parity: a refused refit changed the device tree");
            }
            mlodvk_cut_destroy(context, vcut);
            mlod_cut_destroy(cut);
        }
        check_validation("refit parity");
        mlodvk_tree_destroy(context, vtree);
        mlod_tree_destroy(cpu);
        mlod_tree_destroy(copy);
        free(positions);
        free(normals);
    }
    scene_free(&s);
}

/* ------------------------------------------------------- refusals -- */


/* The depth, normal and colour of a device splat of the cut, downloaded. */
static int splat_bytes(mlodvk_atlas *vatlas, mlodvk_tree *vtree, mlodvk_cut *cut, mlod_atlas *into)
{
    mlod_error e;
    return mlodvk_splat(context, vatlas, vtree, cut, &e) == MLOD_OK &&
           mlodvk_atlas_download(context, vatlas, into, &e) == MLOD_OK;
}

static int same_atlas(const mlod_atlas *a, const mlod_atlas *b)
{
    size_t pixels = (size_t)a->width * a->height;
    return memcmp(a->depth, b->depth, pixels * sizeof(float)) == 0 &&
           memcmp(a->normal, b->normal, 3 * pixels * sizeof(float)) == 0 &&
           memcmp(a->color, b->color, 3 * pixels * sizeof(float)) == 0;
}

/* A refused mlodvk_cut_update changes nothing: for each kind of refusal
   (a bad view at index k > 0, bad parameters), with views 0..k-1 of the
   refused call unlike the kept ones, it returns the code mlod_cut_update
   returns, and afterwards the device views buffer is unchanged byte for
   byte, the next splat gives the same atlas bit for bit, and the next
   incremental update still equals the CPU's.  A splat with views whose
   tiles are not the atlas's is refused by both. */
static void test_refusals(void)
{
    enum { VIEWS = 8, BAD = 5 };
    static const char *names[] = {"NaN position",      "width 0",       "kind 7",       "up parallel to forward",
                                  "+inf forward",      "epsilon 0",     "epsilon NaN",  "lazy_steps 0",
                                  "unknown mode",      "params NULL",   "views NULL"};
    const int cases = (int)(sizeof names / sizeof names[0]);
    scene_mesh s;
    mlod_tree *tree = NULL;
    mlodvk_tree *vtree = NULL;
    mlod_cut *cpu = NULL;
    mlodvk_cut *gpu = NULL;
    mlodvk_atlas *vatlas = NULL;
    mlod_atlas *before = NULL, *after = NULL;
    mlod_view views[VIEWS], next[VIEWS];
    mlod_atlas_desc ad;
    mlod_cut_params p;
    mlod_error e;
    double c[3], R;
    unsigned char views_before[8 * MLOD_IF_VIEW_STRIDE * VIEWS], views_after[8 * MLOD_IF_VIEW_STRIDE * VIEWS];
    int k, ready = 1;
    uint32_t v;
    if (!scene_uv_sphere(&s, 1.0f, 12, 24)) {
        CHECK(0, "refusals: scene_uv_sphere failed");
        return;
    }
    tree = tu_build(&s, 3000, 21, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    tu_bounds(&s, c, &R);
    make_views(77, -1, c, R, views, VIEWS);
    memset(&p, 0, sizeof p);
    p.mode = MLOD_CUT_BASIC;
    p.epsilon = 1.0f;
    p.lazy_steps = 1;
    memset(&ad, 0, sizeof ad);
    ad.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
    if (!tree || mlodvk_tree_upload(context, tree, &vtree, &e) != MLOD_OK ||
        mlod_atlas_create(views, VIEWS, &ad, NULL, &before, &e) != MLOD_OK ||
        mlod_atlas_create(views, VIEWS, &ad, NULL, &after, &e) != MLOD_OK ||
        mlodvk_atlas_create(context, before, &vatlas, &e) != MLOD_OK || mlod_cut_create(VIEWS, NULL, &cpu, &e) != MLOD_OK ||
        mlodvk_cut_create(context, VIEWS, 0, &gpu, &e) != MLOD_OK) {
        CHECK(0, "refusals: set-up failed: %s", e.message);
        ready = 0;
    }
    for (k = 0; ready && k < cases; k++) {
        mlod_cut_params q = p;
        const mlod_cut_params *qp = &q;
        const mlod_view *vp = next;
        mlod_result want, got;
        mlod_error ce;
        /* each case from the same accepted update */
        if (mlod_cut_update(cpu, tree, views, &p, &e) != MLOD_OK || mlodvk_cut_update(context, gpu, vtree, views, &p, &e) != MLOD_OK ||
            !splat_bytes(vatlas, vtree, gpu, before) || vk_download_views(context, gpu, VIEWS, views_before, &e) != MLOD_OK) {
            CHECK(0, "refusals, %s: the accepted update before it failed: %s", names[k], e.message);
            ready = 0;
            break;
        }
        memcpy(next, views, sizeof next);
        move_views(next, VIEWS, 0.3); /* the refused frame's views differ from the kept ones */
        switch (k) {
        case 0: next[BAD].position[1] = (float)NAN; break;
        case 1: next[BAD].width = 0; break;
        case 2: next[BAD].kind = (mlod_view_kind)7; break;
        case 3: memcpy(next[BAD].up, next[BAD].forward, sizeof next[BAD].up); break;
        case 4: next[BAD].forward[2] = (float)INFINITY; break;
        case 5: q.epsilon = 0.0f; break;
        case 6: q.epsilon = (float)NAN; break;
        case 7: q.mode = MLOD_CUT_LAZY; q.lazy_steps = 0; break;
        case 8: q.mode = (mlod_cut_mode)9; break;
        case 9: qp = NULL; break;
        default: vp = NULL; break;
        }
        q.mode = k == 7 || k == 8 ? q.mode : MLOD_CUT_INCREMENTAL;
        want = mlod_cut_update(cpu, tree, vp, qp, &ce);
        got = mlodvk_cut_update(context, gpu, vtree, vp, qp, &e);
        CHECK(want != MLOD_OK && got == want, "refusals, %s: the device returned %s, the CPU %s", names[k],
              mlod_result_name(got), mlod_result_name(want));
        CHECK(vk_download_views(context, gpu, VIEWS, views_after, &e) == MLOD_OK && memcmp(views_before, views_after, sizeof views_before) == 0,
              "refusals, %s: the device views buffer changed", names[k]);
        CHECK(splat_bytes(vatlas, vtree, gpu, after) && same_atlas(before, after),
              "refusals, %s: the next splat differs from the splat before the refusal", names[k]);
        CHECK(compare_cuts(gpu, cpu, VIEWS, names[k]) == 0, "refusals, %s: the kept cut differs from the CPU's", names[k]);
        check_validation("refusals");
    }
    /* and the next accepted incremental update continues from the kept cut */
    if (ready) {
        for (v = 0; v < VIEWS; v++) next[v] = views[v];
        move_views(next, VIEWS, 0.05);
        p.mode = MLOD_CUT_INCREMENTAL;
        CHECK(mlod_cut_update(cpu, tree, next, &p, &e) == MLOD_OK && mlodvk_cut_update(context, gpu, vtree, next, &p, &e) == MLOD_OK &&
                  compare_cuts(gpu, cpu, VIEWS, "after the refusals") == 0,
              "refusals: the incremental update after them differs from the CPU's");
        /* views whose tiles are not the atlas's: both splats refuse */
        next[3].width += 1;
        CHECK(mlod_cut_update(cpu, tree, next, &p, &e) == MLOD_OK && mlodvk_cut_update(context, gpu, vtree, next, &p, &e) == MLOD_OK,
              "refusals: an update with another tile size failed: %s", e.message);
        CHECK(mlod_splat(after, tree, cpu, next, NULL, &e) == MLOD_ERROR_MISMATCH &&
                  mlodvk_splat(context, vatlas, vtree, gpu, &e) == MLOD_ERROR_MISMATCH,
              "refusals: a splat whose view tile is not the atlas's is not refused as MLOD_ERROR_MISMATCH (%s)",
              mlod_result_name(e.code));
        { /* a lazy update's budget is the CPU's alone: the device refuses it and keeps its cut */
            mlod_cut_params q = p;
            q.mode = MLOD_CUT_LAZY;
            q.budget = 1000;
            CHECK(mlodvk_cut_update(context, gpu, vtree, views, &q, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                      compare_cuts(gpu, cpu, VIEWS, "a budget") == 0,
                  "refusals: a lazy update with a budget is not refused by the device, or its cut changed (%s)",
                  mlod_result_name(e.code));
        }
    }
    if (ready) { /* tangent discs asked of a tree without cones: both splats refuse */
        mlod_tree *bare = tu_build(&s, 300, 21, 0);
        mlodvk_tree *vbare = NULL;
        mlod_cut *bare_cpu = NULL;
        mlodvk_cut *bare_gpu = NULL;
        mlod_atlas *tangent = NULL;
        mlodvk_atlas *vtangent = NULL;
        mlod_atlas_desc td;
        memset(&td, 0, sizeof td);
        td.splat = MLOD_SPLAT_TANGENT;
        CHECK(bare && mlodvk_tree_upload(context, bare, &vbare, &e) == MLOD_OK &&
                  mlod_cut_create(VIEWS, NULL, &bare_cpu, &e) == MLOD_OK &&
                  mlodvk_cut_create(context, VIEWS, 0, &bare_gpu, &e) == MLOD_OK &&
                  mlod_cut_update(bare_cpu, bare, views, &p, &e) == MLOD_OK &&
                  mlodvk_cut_update(context, bare_gpu, vbare, views, &p, &e) == MLOD_OK &&
                  mlod_atlas_create(views, VIEWS, &td, NULL, &tangent, &e) == MLOD_OK &&
                  mlodvk_atlas_create(context, tangent, &vtangent, &e) == MLOD_OK &&
                  mlod_splat(tangent, bare, bare_cpu, views, NULL, &e) == MLOD_ERROR_MISMATCH &&
                  mlodvk_splat(context, vtangent, vbare, bare_gpu, &e) == MLOD_ERROR_MISMATCH,
              "refusals: MLOD_SPLAT_TANGENT with a tree without cones is not refused as MLOD_ERROR_MISMATCH (%s)",
              mlod_result_name(e.code));
        mlodvk_atlas_destroy(context, vtangent);
        mlodvk_cut_destroy(context, bare_gpu);
        mlodvk_tree_destroy(context, vbare);
        mlod_cut_destroy(bare_cpu);
        mlod_atlas_destroy(tangent);
        mlod_tree_destroy(bare);
    }
    mlodvk_atlas_destroy(context, vatlas);
    mlodvk_cut_destroy(context, gpu);
    mlodvk_tree_destroy(context, vtree);
    mlod_cut_destroy(cpu);
    mlod_atlas_destroy(before);
    mlod_atlas_destroy(after);
    mlod_tree_destroy(tree);
    scene_free(&s);
    check_validation("refusals");
}

/* VkAllocationCallbacks that count what is outstanding.  Each block keeps
   its offset from the malloc'd start and its size just before it. */
static long outstanding, allocations;

/* test_callback_failures: fail the fail_callback_at-th allocation (from
   1; 0: none) outside the driver calls that cannot survive it (spare_kind:
   1 crash, 2 lost), whose allocations are counted in spared[] instead. */
static long fail_callback_at, callback_calls, spared[3];
static int spare_kind;

static void *VKAPI_CALL counting_alloc(void *user, size_t size, size_t alignment, VkSystemAllocationScope scope)
{
    size_t offset = alignment > 16 ? alignment : 16;
    char *base;
    (void)user;
    (void)scope;
    if (spare_kind) {
        spared[spare_kind]++;
    } else if (++callback_calls == fail_callback_at) {
        return NULL;
    }
    if (posix_memalign((void **)&base, offset, offset + (size ? size : 1)) != 0) return NULL;
    ((size_t *)(base + offset))[-1] = size;
    ((size_t *)(base + offset))[-2] = offset;
    outstanding++;
    allocations++;
    return base + offset;
}

static void VKAPI_CALL counting_free(void *user, void *p)
{
    (void)user;
    if (!p) return;
    outstanding--;
    free((char *)p - ((size_t *)p)[-2]);
}

static void *VKAPI_CALL counting_realloc(void *user, void *old, size_t size, size_t alignment, VkSystemAllocationScope scope)
{
    void *p;
    size_t old_size;
    if (!old) return counting_alloc(user, size, alignment, scope);
    if (size == 0) {
        counting_free(user, old);
        return NULL;
    }
    old_size = ((size_t *)old)[-1];
    p = counting_alloc(user, size, alignment, scope);
    if (p) {
        memcpy(p, old, old_size < size ? old_size : size);
        counting_free(user, old);
    }
    return p;
}

/* ------------------------------------------------- failure injection -- */

/* A function table whose AllocateMemory or QueueSubmit fails on the n-th
   call (counting from 1; 0 never). */
static mlodvk_functions real;
static int alloc_calls, fail_alloc_at, submit_calls, fail_submit_at;
static VkResult submit_result;

static VKAPI_ATTR VkResult VKAPI_CALL failing_allocate(VkDevice d, const VkMemoryAllocateInfo *info,
                                                       const VkAllocationCallbacks *a, VkDeviceMemory *out)
{
    if (++alloc_calls == fail_alloc_at) return VK_ERROR_OUT_OF_DEVICE_MEMORY;
    return real.AllocateMemory(d, info, a, out);
}

static VKAPI_ATTR VkResult VKAPI_CALL failing_submit(VkQueue q, uint32_t n, const VkSubmitInfo *s, VkFence f)
{
    if (++submit_calls == fail_submit_at) return submit_result;
    return real.QueueSubmit(q, n, s, f);
}

/* The whole pipeline (tree, cut that must grow, splat, downloads) on a
   context made with the failing table; returns the first failure's
   result, after destroying everything. */
static const mlod_mesh *mesh; /* the failure tests' mesh, for the refit */

static mlod_result pipeline_with(mlodvk_context *ctx, const mlod_tree *tree, const mlod_view *views, uint32_t view_count,
                                 mlod_atlas *layout, mlod_error *e)
{
    mlodvk_tree *vtree = NULL;
    mlodvk_cut *cut = NULL;
    mlodvk_atlas *atlas = NULL;
    mlod_cut_params p;
    mlod_result res;
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.mode = MLOD_CUT_BASIC;
    res = mlodvk_tree_upload(ctx, tree, &vtree, e);
    if (res == MLOD_OK && mesh) res = mlodvk_tree_upload_refit(ctx, vtree, tree, mesh->indices, mesh->index_count, e);
    if (res == MLOD_OK && mesh) res = mlodvk_refit_mesh_host(ctx, vtree, mesh, e);
    if (res == MLOD_OK) res = mlodvk_cut_create(ctx, view_count, view_count, &cut, e);
    if (res == MLOD_OK) res = mlodvk_cut_update(ctx, cut, vtree, views, &p, e);
    if (res == MLOD_OK) {
        p.mode = MLOD_CUT_INCREMENTAL;
        res = mlodvk_cut_update(ctx, cut, vtree, views, &p, e);
    }
    if (res == MLOD_OK) res = mlodvk_cut_download(ctx, cut, e);
    if (res == MLOD_OK) res = mlodvk_atlas_create(ctx, layout, &atlas, e);
    if (res == MLOD_OK) res = mlodvk_splat(ctx, atlas, vtree, cut, e);
    if (res == MLOD_OK) res = mlodvk_atlas_download(ctx, atlas, layout, e);
    mlodvk_atlas_destroy(ctx, atlas);
    mlodvk_cut_destroy(ctx, cut);
    mlodvk_tree_destroy(ctx, vtree);
    CHECK(mlodvk_context_device_bytes(ctx) == 0, "%llu bytes of device memory left after destroying every object",
          (unsigned long long)mlodvk_context_device_bytes(ctx));
    return res;
}

/* A failing VkAllocationCallbacks allocation: the n-th allocation the
   driver asks of the caller's callbacks fails, for every n (past the first
   64 of the pipeline, every k-th), first while a context is created, then
   through the whole pipeline on a context; each must come back as
   MLOD_ERROR_OUT_OF_MEMORY, and every block is given back once the
   context is destroyed.
   Where the sweep stops short - known and not ours: lavapipe (Mesa
   22.3.6) crashes when an allocation fails inside vkCmdCopyBuffer or
   vkCmdPipelineBarrier (it copies the arguments into the block it did not
   get), and one that fails inside vkCmdBindDescriptorSets is lost below
   manylods (lavapipe or the validation layer: recording ends with
   VK_SUCCESS, so the failure cannot be reported).  Allocations made inside those three calls are
   never failed; the test prints how many it spared. */
static VKAPI_ATTR void VKAPI_CALL spared_copy(VkCommandBuffer cb, VkBuffer src, VkBuffer dst, uint32_t n,
                                              const VkBufferCopy *regions)
{
    spare_kind = 1;
    real.CmdCopyBuffer(cb, src, dst, n, regions);
    spare_kind = 0;
}

static VKAPI_ATTR void VKAPI_CALL spared_barrier(VkCommandBuffer cb, VkPipelineStageFlags from, VkPipelineStageFlags to,
                                                 VkDependencyFlags flags, uint32_t memory_count,
                                                 const VkMemoryBarrier *memory, uint32_t buffer_count,
                                                 const VkBufferMemoryBarrier *buffers, uint32_t image_count,
                                                 const VkImageMemoryBarrier *images)
{
    spare_kind = 1;
    real.CmdPipelineBarrier(cb, from, to, flags, memory_count, memory, buffer_count, buffers, image_count, images);
    spare_kind = 0;
}

static VKAPI_ATTR void VKAPI_CALL spared_bind_sets(VkCommandBuffer cb, VkPipelineBindPoint point, VkPipelineLayout layout,
                                                   uint32_t first, uint32_t count, const VkDescriptorSet *sets,
                                                   uint32_t offset_count, const uint32_t *offsets)
{
    spare_kind = 2;
    real.CmdBindDescriptorSets(cb, point, layout, first, count, sets, offset_count, offsets);
    spare_kind = 0;
}

static void test_callback_failures(const mlod_tree *tree, const mlod_view *views, uint32_t view_count, mlod_atlas *layout)
{
    VkAllocationCallbacks callbacks;
    mlodvk_functions table = real;
    mlodvk_context_desc desc = mlodvk_device_context_desc(&device);
    mlodvk_context *ctx = NULL;
    mlod_error e;
    long k, total, refused = 0, stride = 1, spared_clean[3] = {0, 0, 0};
    memset(&callbacks, 0, sizeof callbacks);
    callbacks.pfnAllocation = counting_alloc;
    callbacks.pfnReallocation = counting_realloc;
    callbacks.pfnFree = counting_free;
    table.CmdCopyBuffer = spared_copy;
    table.CmdPipelineBarrier = spared_barrier;
    table.CmdBindDescriptorSets = spared_bind_sets;
    desc.functions = &table;
    desc.vk_allocator = &callbacks;
    /* creating a context */
    outstanding = callback_calls = spared[1] = spared[2] = 0;
    fail_callback_at = 0;
    if (mlodvk_context_create(&desc, &ctx, &e) != MLOD_OK) {
        CHECK(0, "callback failures: a clean context: %s", e.message);
        return;
    }
    mlodvk_context_destroy(ctx);
    total = callback_calls;
    spared_clean[1] = spared[1];
    spared_clean[2] = spared[2];
    for (k = 1; k <= total; k++) {
        mlod_result res;
        outstanding = callback_calls = 0;
        fail_callback_at = k;
        ctx = NULL;
        res = mlodvk_context_create(&desc, &ctx, &e);
        refused += res == MLOD_ERROR_OUT_OF_MEMORY && ctx == NULL && outstanding == 0;
        if (res == MLOD_OK) mlodvk_context_destroy(ctx);
        if (res != MLOD_ERROR_OUT_OF_MEMORY || outstanding != 0) {
            CHECK(0, "callback failures: allocation %ld of %ld failed creating a context: %s (%s), %ld blocks outstanding", k,
                  total, mlod_result_name(res), res == MLOD_OK ? "" : e.message, outstanding);
            break;
        }
    }
    CHECK(refused == total, "callback failures: %ld of %ld failed allocations while creating a context refused cleanly",
          refused, total);
    printf("  VkAllocationCallbacks failures: context creation, %ld of %ld allocations failed in turn\n", refused, total);
    /* the pipeline on one context */
    fail_callback_at = 0;
    outstanding = 0;
    if (mlodvk_context_create(&desc, &ctx, &e) != MLOD_OK) {
        CHECK(0, "callback failures: a clean context: %s", e.message);
        return;
    }
    {
        long tried = 0;
        callback_calls = spared[1] = spared[2] = 0;
        CHECK(pipeline_with(ctx, tree, views, view_count, layout, &e) == MLOD_OK, "callback failures: the clean run: %s",
              e.message);
        total = callback_calls;
        spared_clean[1] += spared[1];
        spared_clean[2] += spared[2];
        refused = 0;
        stride = getenv("MANYLODS_VK_SWEEP_ALL") ? 1 : total / 256 + 1;
        for (k = 1; k <= total; k += k < 64 ? 1 : stride) {
            mlod_result res;
            tried++;
            callback_calls = 0;
            fail_callback_at = k;
            res = pipeline_with(ctx, tree, views, view_count, layout, &e);
            /* blocks: the command pool keeps or frees its own as it likes;
               what the objects held is counted when the context is gone */
            refused += res == MLOD_ERROR_OUT_OF_MEMORY;
            if (res != MLOD_ERROR_OUT_OF_MEMORY) {
                CHECK(0, "callback failures: allocation %ld of %ld failed in the pipeline: %s (%s)", k, total,
                      mlod_result_name(res), res == MLOD_OK ? "" : e.message);
                break;
            }
        }
        CHECK(refused == tried, "callback failures: %ld of %ld failed allocations in the pipeline refused cleanly", refused,
              tried);
        fail_callback_at = 0;
        CHECK(pipeline_with(ctx, tree, views, view_count, layout, &e) == MLOD_OK,
              "callback failures: the context fails after recovered errors: %s", e.message);
    }
    mlodvk_context_destroy(ctx);
    CHECK(outstanding == 0, "callback failures: %ld blocks outstanding after the context", outstanding);
    /* the layer reports each failed call (VK_ERROR_OUT_OF_HOST_MEMORY): expected */
    validation_seen = device.validation_messages;
    printf("  VkAllocationCallbacks failures: pipeline, %ld of %ld allocations failed in turn (each of the first 64, then\n"
           "  every %ld-th; MANYLODS_VK_SWEEP_ALL=1: every one)\n",
           refused, total, stride);
    printf("  NOT TESTED (lavapipe's bugs, not manylods'): %ld allocations inside vkCmdCopyBuffer and\n"
           "  vkCmdPipelineBarrier (lavapipe, Mesa 22.3.6, crashes when one fails) and %ld inside\n"
           "  vkCmdBindDescriptorSets (the failure is lost below manylods) were never failed\n",
           spared_clean[1], spared_clean[2]);
}

static void test_failures(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlodvk_functions table;
    mlod_view views[8];
    mlod_atlas *layout = NULL;
    mlod_error e;
    double c[3], R;
    int k, total_allocs, total_submits, failures_seen = 0;
    mlodvk_context_desc desc = mlodvk_device_context_desc(&device);
    mlodvk_context *probe = NULL, *ctx = NULL;
    mlod_mesh sphere_mesh;
    if (!scene_uv_sphere(&s, 1.0f, 12, 24)) return;
    tree = tu_build(&s, 4000, 3, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
    sphere_mesh = tu_mesh(&s);
    mesh = &sphere_mesh;
    tu_bounds(&s, c, &R);
    make_views(3, -1, c, R, views, 8);
    mlod_atlas_desc ad;
    memset(&ad, 0, sizeof ad);
    if (!tree || mlod_atlas_create(views, 8, &ad, NULL, &layout, &e) != MLOD_OK ||
        mlodvk_context_create(&desc, &probe, &e) != MLOD_OK) {
        CHECK(0, "failures: set-up failed: %s", e.message);
        mlod_tree_destroy(tree);
        mlod_atlas_destroy(layout);
        scene_free(&s);
        return;
    }
    real = probe->vk; /* the loaded table, through the private struct */
    mlodvk_context_destroy(probe);
    table = real;
    table.CmdDispatchIndirect = NULL; /* a caller's table with a hole: refused, not called through NULL */
    desc.functions = &table;
    CHECK(mlodvk_context_create(&desc, &ctx, &e) == MLOD_ERROR_INVALID_ARGUMENT && ctx == NULL &&
              strstr(e.message, "CmdDispatchIndirect") != NULL,
          "failures: a table without vkCmdDispatchIndirect: %s (%s)", mlod_result_name(e.code), e.message);
    {
        mlodvk_context_desc empty = mlodvk_device_context_desc(NULL);
        CHECK(mlodvk_context_create(&empty, &ctx, &e) == MLOD_ERROR_INVALID_ARGUMENT && ctx == NULL,
              "the context description of no device is refused: %s", mlod_result_name(e.code));
    }
    table = real;
    table.AllocateMemory = failing_allocate;
    table.QueueSubmit = failing_submit;
    desc.functions = &table;
    if (mlodvk_context_create(&desc, &ctx, &e) != MLOD_OK) {
        CHECK(0, "failures: a context with the failing table: %s", e.message);
        mlod_tree_destroy(tree);
        mlod_atlas_destroy(layout);
        scene_free(&s);
        return;
    }
    /* count the calls of a clean run */
    alloc_calls = submit_calls = 0;
    fail_alloc_at = fail_submit_at = 0;
    CHECK(pipeline_with(ctx, tree, views, 8, layout, &e) == MLOD_OK, "failures: the clean run failed: %s", e.message);
    total_allocs = alloc_calls;
    total_submits = submit_calls;
    CHECK(total_allocs > 10 && total_submits > 4, "failures: %d allocations, %d submissions counted", total_allocs,
          total_submits);
    for (k = 1; k <= total_allocs; k++) {
        mlod_result res;
        alloc_calls = submit_calls = 0;
        fail_alloc_at = k;
        fail_submit_at = 0;
        res = pipeline_with(ctx, tree, views, 8, layout, &e);
        failures_seen += res == MLOD_ERROR_OUT_OF_MEMORY;
        if (res != MLOD_ERROR_OUT_OF_MEMORY || !strstr(e.message, "vkAllocateMemory")) {
            CHECK(0, "failures: allocation %d of %d failed, the pipeline returned %s (%s)", k, total_allocs,
                  mlod_result_name(res), res == MLOD_OK ? "" : e.message);
            break;
        }
    }
    CHECK(failures_seen == total_allocs, "failures: %d of %d failed allocations reported as MLOD_ERROR_OUT_OF_MEMORY",
          failures_seen, total_allocs);
    for (k = 1; k <= total_submits; k++) {
        mlod_result res;
        alloc_calls = submit_calls = 0;
        fail_alloc_at = 0;
        fail_submit_at = k;
        submit_result = VK_ERROR_DEVICE_LOST;
        res = pipeline_with(ctx, tree, views, 8, layout, &e);
        if (res != MLOD_ERROR_DEVICE || !strstr(e.message, "device lost")) {
            CHECK(0, "failures: submission %d of %d lost the device, the pipeline returned %s (%s)", k, total_submits,
                  mlod_result_name(res), res == MLOD_OK ? "" : e.message);
            break;
        }
    }
    CHECK(k > total_submits, "failures: every lost-device submission reported as MLOD_ERROR_DEVICE");
    /* the caller's VkAllocationCallbacks reach every Vulkan object the
       context and its objects create, and all are given back */
    {
        VkAllocationCallbacks callbacks;
        mlodvk_context_desc counted = mlodvk_device_context_desc(&device);
        mlodvk_context *cctx = NULL;
        memset(&callbacks, 0, sizeof callbacks);
        callbacks.pfnAllocation = counting_alloc;
        callbacks.pfnReallocation = counting_realloc;
        callbacks.pfnFree = counting_free;
        counted.vk_allocator = &callbacks;
        outstanding = allocations = 0;
        fail_alloc_at = fail_submit_at = 0;
        if (mlodvk_context_create(&counted, &cctx, &e) == MLOD_OK) {
            CHECK(pipeline_with(cctx, tree, views, 8, layout, &e) == MLOD_OK, "failures: with VkAllocationCallbacks: %s",
                  e.message);
            mlodvk_context_destroy(cctx);
            CHECK(allocations > 0 && outstanding == 0,
                  "failures: VkAllocationCallbacks saw %ld allocations, %ld outstanding after destruction", allocations,
                  outstanding);
        } else {
            CHECK(0, "failures: a context with VkAllocationCallbacks: %s", e.message);
        }
    }
    test_callback_failures(tree, views, 8, layout);
    /* after all that, the context still works */
    alloc_calls = submit_calls = 0;
    fail_alloc_at = fail_submit_at = 0;
    CHECK(pipeline_with(ctx, tree, views, 8, layout, &e) == MLOD_OK, "failures: the context fails after recovered errors: %s",
          e.message);
    mlodvk_context_destroy(ctx);
    mesh = NULL;
    check_validation("failure injection");
    mlod_atlas_destroy(layout);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* The validation layer is on and reports to check_validation: a buffer of
   size 0 is invalid usage. */
static void test_validation_reports(void)
{
    VkBufferCreateInfo info;
    VkBuffer buffer = VK_NULL_HANDLE;
    uint32_t before = device.validation_messages;
    memset(&info, 0, sizeof info);
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (context->vk.CreateBuffer(device.device, &info, NULL, &buffer) == VK_SUCCESS && buffer)
        context->vk.DestroyBuffer(device.device, buffer, NULL);
    CHECK(device.validation_messages > before, "the validation layer reported no message for a buffer of size 0");
    validation_seen = device.validation_messages; /* expected: not a failure */
}

/* A context given no allocator takes its host memory from manylods.h's
   default, MANYLODS_MALLOC/FREE (counted above), and gives it all back. */
static void test_default_allocator(void)
{
    mlodvk_context_desc desc = mlodvk_device_context_desc(&device);
    mlodvk_context *ctx = NULL;
    mlodvk_cut *cut = NULL;
    mlodvk_tree *vtree = NULL;
    mlod_tree *tree;
    scene_mesh s;
    mlod_view views[4];
    mlod_cut_params p;
    mlod_error e;
    double c[3], R;
    long blocks, live;
    if (!scene_uv_sphere(&s, 1.0f, 8, 16)) {
        CHECK(0, "default allocator: scene_uv_sphere failed");
        return;
    }
    tree = tu_build(&s, 500, 5, 0);
    tu_bounds(&s, c, &R);
    make_views(9, -1, c, R, views, 4);
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    desc.allocator = NULL;
    blocks = default_blocks;
    live = default_live;
    CHECK(tree && mlodvk_context_create(&desc, &ctx, &e) == MLOD_OK && mlodvk_tree_upload(ctx, tree, &vtree, &e) == MLOD_OK &&
              mlodvk_cut_create(ctx, 4, 0, &cut, &e) == MLOD_OK && mlodvk_cut_update(ctx, cut, vtree, views, &p, &e) == MLOD_OK &&
              mlodvk_cut_download(ctx, cut, &e) == MLOD_OK,
          "default allocator: the pipeline failed: %s", e.message);
    /* the context, the tree, the cut, its per-view arrays, the downloaded lists */
    CHECK(default_blocks - blocks >= 6, "default allocator: MANYLODS_MALLOC gave %ld blocks to the Vulkan objects",
          default_blocks - blocks);
    mlodvk_cut_destroy(ctx, cut);
    mlodvk_tree_destroy(ctx, vtree);
    mlodvk_context_destroy(ctx);
    CHECK(default_live == live, "default allocator: %ld blocks of MANYLODS_MALLOC not given back to MANYLODS_FREE",
          default_live - live);
    mlod_tree_destroy(tree);
    scene_free(&s);
    check_validation("default allocator");
}

/* Arguments the API refuses. */
static void test_arguments(void)
{
    mlod_error e;
    mlodvk_cut *cut = NULL;
    mlodvk_context *none = NULL;
    mlodvk_context_desc desc;
    memset(&desc, 0, sizeof desc);
    CHECK(mlodvk_context_create(&desc, &none, &e) == MLOD_ERROR_INVALID_ARGUMENT && none == NULL,
          "an empty context description is refused");
    CHECK(mlodvk_cut_create(context, 0, 0, &cut, &e) == MLOD_ERROR_INVALID_ARGUMENT && cut == NULL,
          "a cut of 0 views is refused");
    /* the shaders count entries in uint32_t: past 2^31 - 1 the cut is refused
       before anything is allocated, with a message that says so */
    CHECK(mlodvk_cut_create(context, 1, 0x80000000u, &cut, &e) == MLOD_ERROR_OVERFLOW && cut == NULL &&
              strstr(e.message, "2147483648 entries") != NULL,
          "a cut of 2^31 entries: %s (%s)", mlod_result_name(e.code), e.message);
    CHECK(mlodvk_cut_create(context, 0x80000000u, 0, &cut, &e) == MLOD_ERROR_OVERFLOW && cut == NULL &&
              strstr(e.message, "2147483648 views") != NULL,
          "a cut of 2^31 views: %s (%s)", mlod_result_name(e.code), e.message);
    CHECK(strcmp(mlod_result_name(MLOD_ERROR_DEVICE), "MLOD_ERROR_DEVICE") == 0, "the name of MLOD_ERROR_DEVICE");
    { /* a layout changed by hand: what the shaders would trust is checked again */
        mlod_view views[2];
        mlod_atlas *layout = NULL;
        mlod_atlas_desc ad;
        mlod_atlas bad;
        mlodvk_atlas *va = (mlodvk_atlas *)1;
        uint32_t tiles[8], k;
        views[0] = views[1] = tu_view(MLOD_VIEW_PARABOLOID);
        memset(&ad, 0, sizeof ad);
        CHECK(mlod_atlas_create(views, 2, &ad, NULL, &layout, &e) == MLOD_OK, "a layout: %s", e.message);
        for (k = 0; layout && k < 5; k++) {
            bad = *layout;
            memcpy(tiles, layout->tiles, sizeof tiles);
            bad.tiles = tiles;
            if (k == 0) bad.disc_scale = NAN;
            if (k == 1) bad.disc_scale = 1.5f;
            if (k == 2) tiles[4] = layout->width; /* the second tile past the right edge */
            if (k == 3) bad.tiles = NULL;
            if (k == 4) bad.splat = MLOD_SPLAT_TANGENT + 1;
            CHECK(mlodvk_atlas_create(context, &bad, &va, &e) == MLOD_ERROR_INVALID_ARGUMENT && va == NULL,
                  "a tampered layout (%u) is refused: %s (%s)", k, mlod_result_name(e.code), e.message);
        }
        mlod_atlas_destroy(layout);
    }
    /* where the doubles come from: a value that is no mlodvk_doubles is
       refused before anything is made; lavapipe has shaderFloat64, so AUTO
       and DEVICE use it (EMULATED: test_emulated_doubles) */
    desc = mlodvk_device_context_desc(&device);
    desc.doubles = (mlodvk_doubles)7;
    CHECK(mlodvk_context_create(&desc, &none, &e) == MLOD_ERROR_INVALID_ARGUMENT && none == NULL &&
              strstr(e.message, "doubles: 7") != NULL,
          "doubles 7 is refused: %s (%s)", mlod_result_name(e.code), e.message);
    CHECK(mlodvk_context_emulates_doubles(context) == !device.float64,
          "the default context uses the device's doubles where it has shaderFloat64 (%d, the device %d)",
          mlodvk_context_emulates_doubles(context), device.float64);
    desc.doubles = MLODVK_DOUBLES_DEVICE;
    if (device.float64) {
        CHECK(mlodvk_context_create(&desc, &none, &e) == MLOD_OK && mlodvk_context_emulates_doubles(none) == 0,
              "MLODVK_DOUBLES_DEVICE on a device with shaderFloat64: %s", e.message);
    } else {
        CHECK(mlodvk_context_create(&desc, &none, &e) == MLOD_ERROR_DEVICE && strstr(e.message, "shaderFloat64"),
              "MLODVK_DOUBLES_DEVICE on a device without shaderFloat64 is refused: %s", e.message);
    }
    mlodvk_context_destroy(none);
    CHECK(mlodvk_context_emulates_doubles(NULL) == 0, "no context emulates nothing");
}

/* Every parity test on the context; prints their processor times after
   label. */
/* mlodvk_megaviews_render equals mlod_megaviews_render: the atlas bit for
   bit (depth, normal, colour) and every count of the statistics, over the
   settings that take different paths: delta 0 and the suggested delta,
   views with and without directions and fields of view, back-face
   culling, a group radius (with lights in a layer, which the view tree's
   floors cull below), a disc scale below 1, duplicate eyes, eyes
   outside the scene, odd and even resolutions, one view, all with tangent
   discs (the default for the room's tree with cones), and once with
   sphere discs (MLOD_SPLAT_SPHERES: setting 8, few views); maps of
   another orientation (params.forward, up: setting 9 down, -y with up
   +z, at delta 0 with fields of view and back faces; setting 10 an
   oblique frame with sharing and duplicate eyes); and the same refusals
   as the CPU's. */
static void test_megaviews_parity(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlodvk_tree *vtree = NULL;
    mlod_error e;
    double c[3], R;
    int setting;
    if (!room_tree(&s, lean ? 4000 : 30000, "megaviews", &tree, &vtree, c, &R)) return;
    /* lean (emulated doubles, whose pipelines alone take lavapipe about 25 s): the odd settings, which
       between them take every path of the shaders (sharing, fields of view, back faces, groups, one view),
       the sphere discs and the oblique orientation (10) */
    for (setting = lean ? 1 : 0; setting < 11; setting += lean && (setting < 7 || setting == 8) ? 2 : 1) {
        static const float frames[2][2][3] = {{{0, -1, 0}, {0, 0, 1}}, {{0.4f, -1.7f, 0.9f}, {-0.3f, 0.2f, 1.1f}}};
        uint32_t count = setting == 7 ? 1 : setting == 8 ? (lean ? 12 : 64) : setting >= 9 ? (lean ? 24 : 200)
                                          : (lean ? 24 + 13 * (uint32_t)setting : 160 + 37 * (uint32_t)setting), i;
        uint64_t rng = 900u + (uint64_t)setting;
        float *eyes = (float *)malloc(12 * (size_t)count), *dirs = (float *)malloc(12 * (size_t)count);
        float *fovs = (float *)malloc(4 * (size_t)count);
        mlod_view *vs = (mlod_view *)malloc(sizeof(mlod_view) * count);
        mlod_view_set set;
        mlod_view_tree *vt = NULL;
        mlod_megaviews_params p;
        mlod_megaviews_stats cs, gs;
        mlod_atlas_desc ad;
        mlod_atlas *cpu_atlas = NULL, *gpu_atlas = NULL;
        mlodvk_atlas *vatlas = NULL;
        size_t pixels, k, depth_diff = 0, normal_diff = 0, color_diff = 0, drawn = 0;
        memset(&p, 0, sizeof p);
        p.epsilon = setting == 4 ? 3.0f : 1.0f;
        p.delta = setting == 0 || setting == 3 || setting == 9 ? 0.0f : MLOD_MEGAVIEWS_DELTA;
        p.resolution = setting % 2 ? 5 : 8;
        p.flags = setting == 2 || setting == 3 || setting == 6 || setting == 9 ? MLOD_VIEW_CULL_BACKFACES : 0;
        p.group_radius = setting == 5 ? (float)(0.05 * R) : 0.0f;
        if (setting >= 9) {
            memcpy(p.forward, frames[setting - 9][0], 12);
            memcpy(p.up, frames[setting - 9][1], 12);
        }
        for (i = 0; i < count; i++) {
            double d[3];
            int j;
            /* eyes in the room's box, grown by a third for setting 6 (some outside) */
            for (j = 0; j < 3; j++)
                eyes[3 * i + j] = (float)(c[j] + (setting == 6 ? 1.3 : 0.8) * R * (2.0 * scene_rng_double(&rng) - 1.0));
            if ((setting == 1 || setting == 10) && i % 5 == 2) memcpy(eyes + 3 * i, eyes + 3 * (i - 1), 12);
            tu_random_unit(&rng, d);
            if (setting == 5) { /* lights in a thin layer facing up (some tilted): the view tree's floors cull */
                eyes[3 * i + 1] = (float)(c[1] - 0.3 * R + 0.02 * R * scene_rng_double(&rng));
                d[0] = i % 4 ? 0.0 : 0.2 * d[0];
                d[2] = i % 4 ? 0.0 : 0.2 * d[2];
                d[1] = 1.0;
            }
            for (j = 0; j < 3; j++) dirs[3 * i + j] = (float)d[j];
            fovs[i] = (float)(0.3 + 2.8 * scene_rng_double(&rng));
            vs[i] = mlod_megaviews_view_oriented(eyes + 3 * i, p.resolution, p.flags, p.forward, p.up);
        }
        memset(&set, 0, sizeof set);
        set.eyes = eyes;
        set.count = count;
        if ((setting >= 2 && setting <= 5) || setting >= 9) set.directions = dirs;
        if (setting == 3 || setting == 9) set.half_fovs = fovs; /* else each view a hemisphere (half_fov 0: pi/2) */
        memset(&ad, 0, sizeof ad);
        ad.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
        ad.disc_scale = setting == 4 ? 0.5f : 0.0f;
        ad.splat = setting == 8 ? MLOD_SPLAT_SPHERES : MLOD_SPLAT_AUTO;
        memset(&cs, 0, sizeof cs);
        memset(&gs, 0, sizeof gs);
        /* setting 1: the atlas's cells in the view tree's leaf order (mlod_atlas_desc.order) */
        if (mlod_view_tree_build(&set, NULL, NULL, &vt, &e) != MLOD_OK ||
            (ad.order = setting == 1 ? vt->eyes->leaf_sources : NULL,
             mlod_atlas_create(vs, count, &ad, NULL, &cpu_atlas, &e)) != MLOD_OK ||
            mlod_atlas_create(vs, count, &ad, NULL, &gpu_atlas, &e) != MLOD_OK ||
            mlodvk_atlas_create(context, cpu_atlas, &vatlas, &e) != MLOD_OK ||
            mlod_megaviews_render(cpu_atlas, tree, vt, &p, &cs, &e) != MLOD_OK ||
            mlodvk_megaviews_render(context, vatlas, vtree, vt, &p, &gs, &e) != MLOD_OK ||
            mlodvk_atlas_download(context, vatlas, gpu_atlas, &e) != MLOD_OK) {
            CHECK(0, "megaviews parity, setting %d: %s", setting, e.message);
        } else {
            pixels = (size_t)cpu_atlas->width * cpu_atlas->height;
            for (k = 0; k < pixels; k++) {
                drawn += isfinite(cpu_atlas->depth[k]);
                depth_diff += memcmp(&cpu_atlas->depth[k], &gpu_atlas->depth[k], sizeof(float)) != 0;
                normal_diff += memcmp(cpu_atlas->normal + 3 * k, gpu_atlas->normal + 3 * k, 3 * sizeof(float)) != 0;
                color_diff += memcmp(cpu_atlas->color + 3 * k, gpu_atlas->color + 3 * k, 3 * sizeof(float)) != 0;
            }
            CHECK(drawn > pixels / 20, "megaviews parity, setting %d: only %zu of %zu pixels drawn", setting, drawn,
                  pixels);
            CHECK(depth_diff == 0 && normal_diff == 0 && color_diff == 0,
                  "megaviews parity, setting %d: %zu depth, %zu normal, %zu colour pixels of %zu differ", setting,
                  depth_diff, normal_diff, color_diff, pixels);
            CHECK(cs.pairs == gs.pairs && cs.culled == gs.culled && cs.shared_draws == gs.shared_draws &&
                      cs.leaf_draws == gs.leaf_draws && cs.shared_views == gs.shared_views &&
                      cs.shared_leaves == gs.shared_leaves && cs.levels == gs.levels && cs.node_pairs == gs.node_pairs,
                  "megaviews parity, setting %d: stats differ: pairs %llu/%llu culled %llu/%llu shared %llu/%llu "
                  "leaf %llu/%llu views %llu/%llu leaves %llu/%llu levels %u/%u node pairs %llu/%llu",
                  setting, (unsigned long long)cs.pairs, (unsigned long long)gs.pairs, (unsigned long long)cs.culled,
                  (unsigned long long)gs.culled, (unsigned long long)cs.shared_draws,
                  (unsigned long long)gs.shared_draws, (unsigned long long)cs.leaf_draws,
                  (unsigned long long)gs.leaf_draws, (unsigned long long)cs.shared_views,
                  (unsigned long long)gs.shared_views, (unsigned long long)cs.shared_leaves,
                  (unsigned long long)gs.shared_leaves, cs.levels, gs.levels, (unsigned long long)cs.node_pairs,
                  (unsigned long long)gs.node_pairs);
            /* the settings exercise what they name: sharing with delta > 0, none with distinct eyes at 0 */
            if (setting == 0 || setting == 9) CHECK(cs.shared_draws == 0, "megaviews parity: delta 0 shares nothing");
            if (setting == 1 || setting == 2 || setting == 4 || setting == 6 || setting == 8 || setting == 10)
                CHECK(cs.shared_draws > 0, "megaviews parity, setting %d: something shared", setting);
            if (setting == 5) { /* the floors cull pairs the views' cones leave (without them, more pairs) */
                float *floors = vt->floors;
                mlod_megaviews_stats without;
                memset(&without, 0, sizeof without);
                vt->floors = NULL;
                CHECK(mlod_megaviews_render(cpu_atlas, tree, vt, &p, &without, &e) == MLOD_OK && without.pairs > cs.pairs,
                      "megaviews parity, setting 5: the floors cull (%llu pairs, %llu without them)",
                      (unsigned long long)cs.pairs, (unsigned long long)without.pairs);
                vt->floors = floors;
            }
            CHECK(gs.peak_bytes > 0, "megaviews parity, setting %d: device bytes reported", setting);
            if (setting == 7) { /* the refusals, as the CPU's */
                mlod_megaviews_params bad = p;
                mlod_megaviews_render(cpu_atlas, tree, vt, &p, NULL, &e);
                CHECK(mlodvk_megaviews_render(NULL, vatlas, vtree, vt, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                          mlodvk_megaviews_render(context, vatlas, vtree, NULL, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT,
                      "megaviews: NULL context or views refused");
                bad.epsilon = 0.0f;
                CHECK(mlodvk_megaviews_render(context, vatlas, vtree, vt, &bad, NULL, &e) == MLOD_ERROR_BAD_EPSILON &&
                          mlod_megaviews_render(cpu_atlas, tree, vt, &bad, NULL, &e) == MLOD_ERROR_BAD_EPSILON,
                      "megaviews: epsilon 0 refused by both");
                bad = p;
                bad.delta = -1.0f;
                CHECK(mlodvk_megaviews_render(context, vatlas, vtree, vt, &bad, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT,
                      "megaviews: a negative delta refused");
                bad = p;
                bad.resolution = p.resolution + 1;
                CHECK(mlodvk_megaviews_render(context, vatlas, vtree, vt, &bad, NULL, &e) == MLOD_ERROR_MISMATCH &&
                          mlod_megaviews_render(cpu_atlas, tree, vt, &bad, NULL, &e) == MLOD_ERROR_MISMATCH,
                      "megaviews: tiles of another resolution refused by both");
                { /* tangent discs asked of a scene without cones: refused by both */
                    mlod_tree *bare = tu_build(&s, 200, 9, 0);
                    mlodvk_tree *vbare = NULL;
                    mlod_atlas *tangent = NULL;
                    mlodvk_atlas *vtangent = NULL;
                    mlod_atlas_desc td;
                    memset(&td, 0, sizeof td);
                    td.splat = MLOD_SPLAT_TANGENT;
                    CHECK(bare && mlodvk_tree_upload(context, bare, &vbare, &e) == MLOD_OK &&
                              mlod_atlas_create(vs, count, &td, NULL, &tangent, &e) == MLOD_OK &&
                              mlodvk_atlas_create(context, tangent, &vtangent, &e) == MLOD_OK &&
                              mlod_megaviews_render(tangent, bare, vt, &p, NULL, &e) == MLOD_ERROR_MISMATCH &&
                              mlodvk_megaviews_render(context, vtangent, vbare, vt, &p, NULL, &e) == MLOD_ERROR_MISMATCH,
                          "megaviews: MLOD_SPLAT_TANGENT with a scene without cones refused by both (%s)",
                          mlod_result_name(e.code));
                    mlodvk_atlas_destroy(context, vtangent);
                    mlodvk_tree_destroy(context, vbare);
                    mlod_atlas_destroy(tangent);
                    mlod_tree_destroy(bare);
                }
            }
        }
        mlodvk_atlas_destroy(context, vatlas);
        mlod_atlas_destroy(cpu_atlas);
        mlod_atlas_destroy(gpu_atlas);
        mlod_view_tree_destroy(vt);
        free(eyes);
        free(dirs);
        free(fovs);
        free(vs);
        check_validation("megaviews parity");
    }
    mlodvk_tree_destroy(context, vtree);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

static void run_parity(const char *label)
{
    double t0 = seconds(), t1, t2;
    test_cut_parity();
    t1 = seconds();
    test_splat_parity();
    test_tie_parity();
    test_refit_parity();
    test_opposite_cone_parity();
    test_megaviews_parity();
    t2 = seconds();
    printf("  %sprocessor time: cut parity %.1f s, splat, refit and MegaViews parity %.1f s\n", label, t1 - t0, t2 - t1);
}

/* The same parity with doubles built from 32-bit integers (f64.glsl):
   the pipelines without shaderFloat64, equal to the CPU all the same. */
static void test_emulated_doubles(void)
{
    mlodvk_context_desc desc = mlodvk_device_context_desc(&device);
    mlod_error e;
    double t0;
    desc.doubles = MLODVK_DOUBLES_EMULATED;
    lean = 1;
    t0 = seconds();
    if (mlodvk_context_create(&desc, &context, &e) != MLOD_OK) {
        CHECK(0, "mlodvk_context_create with MLODVK_DOUBLES_EMULATED on %s: %s", device.name, e.message);
        return;
    }
    CHECK(mlodvk_context_emulates_doubles(context) == 1, "a context asked for MLODVK_DOUBLES_EMULATED emulates them");
    printf("  emulated doubles: processor time: context (pipelines) %.1f s\n", seconds() - t0);
    run_parity("emulated doubles: ");
    lean = 0;
    CHECK(mlodvk_context_device_bytes(context) == 0, "emulated doubles: device memory left: %llu bytes",
          (unsigned long long)mlodvk_context_device_bytes(context));
    mlodvk_context_destroy(context);
    context = NULL;
    check_validation("emulated doubles");
}

int main(int argc, char **argv)
{
    const char *require = getenv("MANYLODS_REQUIRE_VULKAN");
    int required = require && strcmp(require, "1") == 0, native = argc < 2, emulated = argc < 2, i;
    mlodvk_device_desc dd;
    mlodvk_context_desc desc;
    mlod_error e;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "native") == 0) {
            native = 1;
        } else if (strcmp(argv[i], "emulated") == 0) {
            emulated = 1;
        } else {
            fprintf(stderr, "usage: %s [native] [emulated]\n", argv[0]);
            return 2;
        }
    }
    /* before the first Vulkan call: lavapipe reads it once */
    if (emulated && !native) setenv("GALLIVM_PERF", "nopt", 0);
    memset(&dd, 0, sizeof dd);
    dd.get_instance_proc_addr = vkGetInstanceProcAddr;
    dd.validation = 1;
    dd.prefer_cpu = getenv("MANYLODS_VULKAN_GPU") == NULL; /* lavapipe unless asked for the GPU */
    if (mlodvk_device_create(&dd, &device, &e) != MLOD_OK) {
        printf("SKIPPED: no usable Vulkan device with the validation layer: %s\n", e.message);
        if (required) {
            printf("MANYLODS_REQUIRE_VULKAN=1: a skip is a failure\n0 passed, 1 failed\n");
            return 1;
        }
        printf("0 passed, 0 failed\n");
        return 0;
    }
    if (native) {
        desc = mlodvk_device_context_desc(&device);
        if (mlodvk_context_create(&desc, &context, &e) != MLOD_OK) {
            CHECK(0, "mlodvk_context_create on %s: %s", device.name, e.message);
            mlodvk_device_destroy(&device);
            return test_finish();
        }
        printf("  device: %s\n", mlodvk_context_device_name(context));
        check_validation("device and context creation");
        test_validation_reports();
        test_arguments();
        test_refusals();
        test_default_allocator();
        run_parity("");
        {
            double t0 = seconds();
            test_failures();
            printf("  processor time: failure injection %.1f s\n", seconds() - t0);
        }
        CHECK(mlodvk_context_device_bytes(context) == 0, "device memory left: %llu bytes",
              (unsigned long long)mlodvk_context_device_bytes(context));
        mlodvk_context_destroy(context);
        context = NULL;
    }
    if (emulated) {
        const char *perf = getenv("GALLIVM_PERF");
        printf("  emulated doubles on %s%s%s\n", device.name, perf ? ", GALLIVM_PERF=" : "", perf ? perf : "");
        test_emulated_doubles();
    }
    mlodvk_device_destroy(&device);
    check_validation("teardown");
    return test_finish();
}
