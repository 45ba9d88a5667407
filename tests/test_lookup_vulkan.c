/* tests/test_lookup_vulkan.c - shaders/lookup.glsl on a Vulkan device
   (lavapipe in CI, with the Khronos validation layer) against manylods.h's
   mlod_atlas_lookup and mlod_atlas_shadow: the same bits.

   An atlas of ten views, each of the five kinds (perspective, paraboloid,
   dual paraboloid, orthographic, cube) twice, from two eyes, with random
   depths (some +inf: nothing drawn) and some pixels set just in front of
   or behind a query's point, so that biases decide; then random queries:
   points near and far (outside views, behind them, at the eye), normals
   random, facing the eye, zero or none (has_normal false, C's NULL), and
   params of filter 0, 1, 2, 3, 5 and 16 with random biases and slope
   biases, some refused (filter 17, a negative, infinite or NaN bias: NaN),
   some with another view's tile (a tile of another size than the frame:
   0 and NaN).  tests/lookup_check.comp runs both functions for every query
   on the device, and each result must equal the CPU's bit for bit: the
   return value, pixel, depth and map depth where the lookup returns 1, the
   lit fraction (NaN: both NaN).  With the device's doubles it also
   returns the doubles within, which those floats round away but for a
   rare ulp: frame_project's return value, sub-projection, x, y and depth
   (mlod__frame_project's) and lookup_footprint's (mlod__footprint's), bit
   for bit too.  It runs twice: with the device's doubles (where it has
   shaderFloat64) and with emulated doubles (-DMLOD_F64_EMULATED: f64.glsl;
   that module must declare no Float64, Int64 or Int64Atomics capability);
   and the shader compiles with MLOD_NO_SUBGROUPS too, to a module with
   no subgroup capability (not run).

     test_lookup_vulkan [native] [emulated] [queries]
                     both forms (none named), or those named; 20000
                     queries unless given.  make test runs the two as two
                     programs, side by side.  The emulated form run alone
                     has lavapipe compile without LLVM's optimisation passes
                     (GALLIVM_PERF=nopt, unless the caller set GALLIVM_PERF),
                     as tests/test_vulkan.c does: its pipeline takes
                     about 25 s of processor time either way (NIR, every
                     double operation inlined), its first dispatch
                     (lavapipe's LLVM compile) 27 s with nopt and 72 s
                     without (Mesa 22.3, LLVM 15, no shader cache); the
                     results' bits must be the same either way.

   tests/lookup_check.comp is compiled here, with glslangValidator
   (Debian: glslang-tools; GLSLANG overrides the command).  Without a
   Vulkan device or the compiler it prints why and reports no test (0
   passed, 0 failed), unless MANYLODS_REQUIRE_VULKAN=1 (CI): then a skip is
   a failure.  Run from the repository's root (make test does). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#define MANYLODS_VK_IMPLEMENTATION
#include "../manylods_vk.h"

#include "harness.h"
#include "tempdir.h"
#include "vkcheck.h"

#define VIEWS 10
#define QUERY_WORDS 12  /* three uvec4 per query, as tests/lookup_check.comp reads them */
#define RESULT_WORDS 20 /* five uvec4 per query */

static uint64_t rng_state = 0x5EED100C0ull;

static double rnd(void) /* [0, 1): splitmix64 */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

static float bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static double word_double(const uint32_t *w) /* two words, low first */
{
    uint64_t u = (uint64_t)w[1] << 32 | w[0];
    double d;
    memcpy(&d, &u, 8);
    return d;
}

/* The five kinds around `eye`, looking along `forward` (views v[0 .. 4]),
   tile sizes scaled by `size`. */
static void five_views(const float *eye, const float *forward, const float *up, uint32_t size, mlod_view *v)
{
    uint32_t i;
    memset(v, 0, 5 * sizeof *v);
    for (i = 0; i < 5; i++) {
        memcpy(v[i].position, eye, 12);
        memcpy(v[i].forward, forward, 12);
        memcpy(v[i].up, up, 12);
    }
    v[0].kind = MLOD_VIEW_PERSPECTIVE;
    v[0].width = 12 * size;
    v[0].height = 8 * size + 1;
    v[0].fov_y = 1.1f;
    v[0].near_plane = 0.05f;
    v[0].far_plane = INFINITY;
    v[1].kind = MLOD_VIEW_PARABOLOID;
    v[1].width = v[1].height = 16 * size;
    v[2].kind = MLOD_VIEW_DUAL_PARABOLOID;
    v[2].width = 20 * size;
    v[2].height = 10 * size;
    v[3].kind = MLOD_VIEW_ORTHOGRAPHIC;
    v[3].width = 10 * size + 1;
    v[3].height = 14 * size;
    v[3].half_width = 2.0f;
    v[3].half_height = 3.0f;
    v[3].near_plane = -1.0f;
    v[3].far_plane = 6.0f;
    v[4].kind = MLOD_VIEW_CUBE;
    v[4].width = 24 * size;
    v[4].height = 16 * size;
    v[4].near_plane = 0.05f;
    v[4].far_plane = 50.0f;
}

typedef struct query {
    float point[3], normal[3];
    int has_normal;
    uint32_t view, tile; /* tile: the view whose tile the device gets (another: a tile of another size) */
    mlod_shadow_params params;
} query;

typedef struct expected {
    int inside;
    float pixel[2], depth, map_depth, lit;
    /* the doubles within: mlod__frame_project's, and mlod__footprint's
       where the point lies in the frame's tile (in_tile; else 0) */
    int projected, sub, in_tile;
    double x, y, z, footprint;
} expected;

static uint64_t double_bits(double d)
{
    uint64_t u;
    memcpy(&u, &d, 8);
    return u;
}

/* Whether the two words at w (low first) are the double's bits. */
static int same_double(const uint32_t *w, double d)
{
    return ((uint64_t)w[1] << 32 | w[0]) == double_bits(d);
}

/* Query i: a point around the eye of view v (or exactly at it), a normal,
   params; sometimes another view's tile.  The filter width is the same for
   64 queries in a row (a workgroup of lookup_check.comp): a SIMD device
   (lavapipe) runs each lane of a subgroup through the widest filter's
   loop of any, which with emulated doubles costs seconds. */
static void make_query(const mlod_view *views, const mlod_atlas *atlas, uint32_t i, uint32_t v, query *q)
{
    static const uint32_t filters[8] = {0, 0, 1, 1, 2, 3, 5, 16};
    const float *eye = views[v].position;
    double reach, r = rnd(), t;
    int k;
    memset(q, 0, sizeof *q);
    q->view = q->tile = v;
    reach = r < 0.02 ? 0.0 : r < 0.2 ? 0.02 : r < 0.9 ? 6.0 : 100.0;
    for (k = 0; k < 3; k++) q->point[k] = (float)(eye[k] + reach * (2.0 * rnd() - 1.0));
    t = rnd();
    if (t < 0.2) {
        q->has_normal = 0; /* C: NULL; the device must not read these */
        for (k = 0; k < 3; k++) q->normal[k] = (float)(2.0 * rnd() - 1.0);
    } else if (t < 0.25) {
        q->has_normal = 1; /* zero: slope NaN, clamped to the maximum */
    } else if (t < 0.4) {
        double s = 0.1 + 3.0 * rnd(); /* facing the eye: tan 0 (or rounded past it) */
        q->has_normal = 1;
        for (k = 0; k < 3; k++) q->normal[k] = (float)(s * ((double)eye[k] - q->point[k]));
    } else {
        q->has_normal = 1;
        for (k = 0; k < 3; k++) q->normal[k] = (float)(2.0 * rnd() - 1.0);
    }
    q->params.filter = filters[(i / 64) % 8];
    q->params.bias = rnd() < 0.3 ? 0.0f : (float)(0.1 * rnd());
    q->params.slope_bias = rnd() < 0.3 ? 0.0f : (float)(2.0 * rnd());
    t = rnd();
    if (t < 0.01) {
        q->params.filter = MLOD_SHADOW_MAX_FILTER + 1;
    } else if (t < 0.02) {
        q->params.bias = -0.25f;
    } else if (t < 0.025) {
        q->params.bias = INFINITY;
    } else if (t < 0.03) {
        q->params.slope_bias = NAN;
    } else if (t < 0.035) {
        q->params.slope_bias = -FLT_MAX;
    } else if (t < 0.04) {
        q->params.bias = -0.0f; /* accepted: -0 >= 0 */
    } else if (t < 0.06) {
        /* another view's tile, of another size than this view's frame */
        uint32_t other = (v + 1 + (uint32_t)(rnd() * (VIEWS - 1))) % VIEWS;
        if (atlas->tiles[4 * other + 2] != atlas->tiles[4 * v + 2] || atlas->tiles[4 * other + 3] != atlas->tiles[4 * v + 3])
            q->tile = other;
    }
}

int main(int argc, char **argv)
{
    uint32_t n = 20000u, i, v, form;
    int forms[2] = {1, 1}, arg;
    static const char *form_names[2] = {"the device's doubles", "emulated doubles (-DMLOD_F64_EMULATED)"};
    static const char *form_flags[2] = {"", "-DMLOD_F64_EMULATED"};
    static const float eye_a[3] = {0.5f, -0.25f, 1.0f}, eye_b[3] = {-3.0f, 2.0f, 0.125f};
    static const float fwd_a[3] = {0.3f, -0.2f, 1.0f}, fwd_b[3] = {-1.0f, 0.5f, -0.25f};
    static const float up_a[3] = {0.1f, 1.0f, 0.0f}, up_b[3] = {0.0f, 0.0f, 1.0f};
    mlod_view views[VIEWS];
    mlod_view_frame frames[VIEWS];
    mlod_atlas *atlas = NULL;
    mlod_atlas_desc ad;
    mlodvk_device device;
    mlodvk_context *ctx = NULL;
    mlod_error e;
    char why[1200];
    query *queries;
    expected *want;
    size_t pixels, p;
    uint32_t counts[8] = {0}; /* inside, lit 0, lit 1, between, NaN, outside views (lit 1, lookup 0), footprints > 0, 0 */
    int ran = 0;

    for (arg = 1; arg < argc; arg++) {
        if (strcmp(argv[arg], "native") == 0 || strcmp(argv[arg], "emulated") == 0) {
            if (forms[0] && forms[1]) forms[0] = forms[1] = 0; /* the first form named: only those named */
            forms[strcmp(argv[arg], "emulated") == 0] = 1;
        } else if (argv[arg][0] >= '1' && argv[arg][0] <= '9') {
            n = (uint32_t)strtoul(argv[arg], NULL, 10);
        } else {
            fprintf(stderr, "usage: %s [native] [emulated] [queries]\n", argv[0]);
            return 2;
        }
    }
    /* before the first Vulkan call: lavapipe reads it once */
    if (forms[1] && !forms[0]) setenv("GALLIVM_PERF", "nopt", 0);
    /* the module of each form, and of MLOD_NO_SUBGROUPS (compiled only) */
    {
        size_t bytes = 0;
        uint32_t *words =
            vkc_compile("tests/lookup_check.comp", "-DMLOD_NO_SUBGROUPS -DMLOD_F64_EMULATED", &bytes, why, sizeof why);
        if (!words) return vkc_skip(why);
        CHECK(vkc_wide_capabilities(words, bytes / 4, 1) == 0,
              "lookup_check.comp with MLOD_NO_SUBGROUPS and MLOD_F64_EMULATED declares no Float64, Int64, Int64Atomics "
              "or subgroup capability (found %d)",
              vkc_wide_capabilities(words, bytes / 4, 1));
        free(words);
    }

    /* the atlas: random depths, one pixel in ten empty */
    five_views(eye_a, fwd_a, up_a, 2, views);
    five_views(eye_b, fwd_b, up_b, 3, views + 5);
    memset(&ad, 0, sizeof ad);
    if (mlod_atlas_create(views, VIEWS, &ad, NULL, &atlas, &e) != MLOD_OK) {
        CHECK(0, "mlod_atlas_create: %s", e.message);
        return test_finish();
    }
    for (v = 0; v < VIEWS; v++)
        if (mlod_view_frame_of(&views[v], &frames[v], &e) != MLOD_OK) {
            CHECK(0, "mlod_view_frame_of(view %u): %s", v, e.message);
            mlod_atlas_destroy(atlas);
            return test_finish();
        }
    pixels = (size_t)atlas->width * atlas->height;
    for (p = 0; p < pixels; p++) atlas->depth[p] = rnd() < 0.1 ? INFINITY : (float)(0.2 + 8.0 * rnd());

    /* the queries; for one in three inside its view, its pixel's depth set
       just in front of or behind it (later queries may set it again: the
       atlas is read only once all are made) */
    queries = calloc(n, sizeof *queries);
    want = calloc(n, sizeof *want);
    if (!queries || !want) {
        CHECK(0, "out of memory for %u queries", n);
        free(queries);
        free(want);
        mlod_atlas_destroy(atlas);
        return test_finish();
    }
    for (i = 0; i < n; i++) {
        float pixel[2], depth;
        query *q = &queries[i];
        make_query(views, atlas, i, i % VIEWS, q);
        if (i % 3 == 0 && mlod_atlas_lookup(atlas, q->view, &frames[q->view], q->point, pixel, &depth, NULL)) {
            const uint32_t *t = atlas->tiles + 4 * (size_t)q->view;
            atlas->depth[((size_t)t[1] + (size_t)pixel[1]) * atlas->width + t[0] + (size_t)pixel[0]] =
                (float)(depth * (1.0 + 0.02 * (2.0 * rnd() - 1.0)));
        }
    }
    for (i = 0; i < n; i++) {
        const query *q = &queries[i];
        expected *w = &want[i];
        w->inside = mlod_atlas_lookup(atlas, q->tile, &frames[q->view], q->point, w->pixel, &w->depth, &w->map_depth);
        w->lit = mlod_atlas_shadow(atlas, q->tile, &frames[q->view], q->point, q->has_normal ? q->normal : NULL,
                                   &q->params);
        {
            const mlod_view_frame *f = &frames[q->view];
            w->projected = mlod__frame_project(f, q->point, &w->sub, &w->x, &w->y, &w->z);
            w->in_tile = w->projected == 1 && w->x >= 0.0 && w->x < f->width && w->y >= 0.0 && w->y < f->height;
            if (w->in_tile) {
                double c[4], e[3];
                int k;
                mlod__lookup_sub_pixels(&f->subs[w->sub], c);
                for (k = 0; k < 3; k++) e[k] = (double)q->point[k] - f->eye[k];
                w->footprint = mlod__footprint(&f->subs[w->sub], c, e, w->x, w->y);
                counts[6] += w->footprint > 0.0;
                counts[7] += w->footprint == 0.0; /* neither neighbour has a ray */
            }
        }
        counts[0] += w->inside != 0;
        counts[1] += w->lit == 0.0f;
        counts[2] += w->lit == 1.0f;
        counts[3] += w->lit > 0.0f && w->lit < 1.0f;
        counts[4] += w->lit != w->lit;
        counts[5] += !w->inside && w->lit == 1.0f;
    }
    printf("  %u queries on %u views (%u x %u atlas): %u inside a tile; lit 0: %u, 1: %u, between: %u, NaN: %u; "
           "footprints > 0: %u, 0: %u\n",
           n, VIEWS, atlas->width, atlas->height, counts[0], counts[1], counts[2], counts[3], counts[4], counts[6],
           counts[7]);
    /* the test tests what it says */
    CHECK(counts[0] > n / 4 && counts[1] > n / 40 && counts[3] > n / 20 && counts[4] > n / 100 && counts[5] > n / 20,
          "the queries cover inside and outside, lit, shadowed, partly lit and refused (%u, %u, %u, %u, %u of %u)",
          counts[0], counts[1], counts[3], counts[4], counts[5], n);

    {
        int opened = vkc_open(&device, &ctx, why, sizeof why);
        if (opened <= 0) {
            free(queries);
            free(want);
            mlod_atlas_destroy(atlas);
            return opened == 0 ? vkc_skip(why) : test_finish();
        }
    }
    {
        const char *perf = getenv("GALLIVM_PERF");
        printf("  device: %s%s%s\n", mlodvk_context_device_name(ctx), perf ? ", GALLIVM_PERF=" : "", perf ? perf : "");
    }

    for (form = 0; form < 2; form++) {
        /* bindings: the frames, the atlas's depth, its tiles, the queries, the results */
        VkDeviceSize sizes[5];
        vkc_program program;
        mlod_result res;
        size_t bytes = 0;
        uint32_t *words, wrong[8] = {0}, first = 0, k;
        clock_t t0;
        if (!forms[form]) continue;
        if (form == 0 && mlodvk_context_emulates_doubles(ctx)) {
            printf("  %s: not run (%s has no shaderFloat64, shaderInt64 and shaderBufferInt64Atomics)\n", form_names[0],
                   device.name);
            continue;
        }
        words = vkc_compile("tests/lookup_check.comp", form_flags[form], &bytes, why, sizeof why);
        CHECK(words != NULL, "%s", why);
        if (!words) continue;
        if (form == 1)
            CHECK(vkc_wide_capabilities(words, bytes / 4, 0) == 0,
                  "lookup_check.comp with MLOD_F64_EMULATED declares no Float64, Int64 or Int64Atomics capability (found %d)",
                  vkc_wide_capabilities(words, bytes / 4, 0));
        memset(&program, 0, sizeof program);
        sizes[0] = sizeof frames;
        sizes[1] = 4 * (VkDeviceSize)pixels;
        sizes[2] = 16 * VIEWS;
        sizes[3] = 4 * QUERY_WORDS * (VkDeviceSize)n;
        sizes[4] = 4 * RESULT_WORDS * (VkDeviceSize)n;
        t0 = clock();
        res = vkc_program_create(ctx, words, bytes, sizes, 5, 8, &program, &e);
        CHECK(res == MLOD_OK, "%s: the test pipeline and buffers: %s", form_names[form], e.message);
        if (res == MLOD_OK) {
            mlodvk__buffer *buffers = program.buffers;
            uint32_t *in = buffers[3].mapped, *tiles = buffers[2].mapped, push[2];
            printf("  %s: pipeline %.1f s of processor time\n", form_names[form], (double)(clock() - t0) / CLOCKS_PER_SEC);
            memcpy(buffers[0].mapped, frames, sizeof frames); /* 296 doubles a view, as manylods_vk.h uploads them */
            memcpy(buffers[1].mapped, atlas->depth, 4 * pixels);
            memcpy(tiles, atlas->tiles, 16 * VIEWS);
            for (i = 0; i < n; i++) {
                const query *q = &queries[i];
                uint32_t *w = in + QUERY_WORDS * (size_t)i;
                for (k = 0; k < 3; k++) {
                    w[k] = float_bits(q->point[k]);
                    w[4 + k] = float_bits(q->normal[k]);
                }
                w[3] = q->view;
                w[7] = (uint32_t)q->has_normal;
                w[8] = q->tile;
                w[9] = q->params.filter;
                w[10] = float_bits(q->params.bias);
                w[11] = float_bits(q->params.slope_bias);
            }
            memset(buffers[4].mapped, 0xAB, 4 * RESULT_WORDS * (size_t)n);
            push[0] = n;
            push[1] = atlas->width;
            t0 = clock();
            res = vkc_program_run(ctx, &program, push, (n + 63) / 64, &e);
            CHECK(res == MLOD_OK, "%s: the dispatch of %u queries: %s", form_names[form], n, e.message);
        }
        if (res == MLOD_OK) {
            const uint32_t *out = program.buffers[4].mapped;
            for (i = 0; i < n; i++) {
                const uint32_t *r = out + RESULT_WORDS * (size_t)i;
                const expected *w = &want[i];
                float lit = bits_float(r[5]);
                int bad_inside = r[0] != (uint32_t)w->inside;
                int bad_pixel = !bad_inside && w->inside &&
                                (r[1] != float_bits(w->pixel[0]) || r[2] != float_bits(w->pixel[1]));
                int bad_depth = !bad_inside && w->inside && r[3] != float_bits(w->depth);
                int bad_map = !bad_inside && w->inside && r[4] != float_bits(w->map_depth);
                int bad_lit = w->lit != w->lit ? lit == lit : r[5] != float_bits(w->lit);
                int within = form == 0; /* (lookup_check.comp writes them with the device's doubles only) */
                int bad_projected = within && r[8] != (uint32_t)w->projected;
                int bad_xyz = within && !bad_projected && w->projected >= 0 &&
                              (r[9] != (uint32_t)w->sub || !same_double(r + 10, w->x) || !same_double(r + 12, w->y) ||
                               !same_double(r + 14, w->z));
                int bad_footprint =
                    within && (r[18] != (uint32_t)w->in_tile || (w->in_tile && !same_double(r + 16, w->footprint)));
                wrong[0] += bad_inside;
                wrong[1] += bad_pixel;
                wrong[2] += bad_depth;
                wrong[3] += bad_map;
                wrong[4] += bad_lit;
                wrong[5] += bad_projected;
                wrong[6] += bad_xyz;
                wrong[7] += bad_footprint;
                if ((bad_inside || bad_pixel || bad_depth || bad_map || bad_lit || bad_projected || bad_xyz ||
                     bad_footprint) &&
                    !first++) {
                    const query *q = &queries[i];
                    fprintf(stderr,
                            "%s: first difference: query %u (view %u, tile %u, point %.9g %.9g %.9g, normal %d %.9g "
                            "%.9g %.9g, filter %u, bias %.9g, slope bias %.9g): device %u (%.9g, %.9g) depth %.9g map "
                            "%.9g lit %.9g (0x%08x); CPU %d (%.9g, %.9g) depth %.9g map %.9g lit %.9g (0x%08x); "
                            "frame_project: device %d sub %u (%.17g, %.17g) %.17g, CPU %d sub %d (%.17g, %.17g) "
                            "%.17g; footprint: device %.17g, CPU %.17g\n",
                            form_names[form], i, q->view, q->tile, q->point[0], q->point[1], q->point[2], q->has_normal,
                            q->normal[0], q->normal[1], q->normal[2], q->params.filter, q->params.bias,
                            q->params.slope_bias, r[0], bits_float(r[1]), bits_float(r[2]), bits_float(r[3]),
                            bits_float(r[4]), lit, r[5], w->inside, w->pixel[0], w->pixel[1], w->depth, w->map_depth,
                            w->lit, float_bits(w->lit), (int)r[8], r[9], word_double(r + 10), word_double(r + 12),
                            word_double(r + 14), w->projected, w->sub, w->x, w->y, w->z, word_double(r + 16),
                            w->footprint);
                }
            }
            printf("  %s: %u queries in %.1f s of processor time; differences: lookup %u, pixel %u, depth %u, map "
                   "depth %u, shadow %u",
                   form_names[form], n, (double)(clock() - t0) / CLOCKS_PER_SEC, wrong[0], wrong[1], wrong[2],
                   wrong[3], wrong[4]);
            if (form == 0)
                printf("; within: frame_project %u, its x, y, depth %u, footprint %u\n", wrong[5], wrong[6], wrong[7]);
            else
                printf("\n");
            CHECK(wrong[0] == 0, "%s: mlod_atlas_lookup's return value differs on %u of %u queries", form_names[form],
                  wrong[0], n);
            CHECK(wrong[1] == 0, "%s: mlod_atlas_lookup's pixel differs on %u of %u queries", form_names[form], wrong[1],
                  n);
            CHECK(wrong[2] == 0, "%s: mlod_atlas_lookup's depth differs on %u of %u queries", form_names[form], wrong[2],
                  n);
            CHECK(wrong[3] == 0, "%s: mlod_atlas_lookup's map depth differs on %u of %u queries", form_names[form],
                  wrong[3], n);
            CHECK(wrong[4] == 0, "%s: mlod_atlas_shadow differs on %u of %u queries", form_names[form], wrong[4], n);
            CHECK(wrong[5] + wrong[6] == 0, "%s: frame_project differs from mlod__frame_project on %u of %u queries",
                  form_names[form], wrong[5] + wrong[6], n);
            CHECK(wrong[7] == 0, "%s: lookup_footprint differs from mlod__footprint on %u of %u queries",
                  form_names[form], wrong[7], n);
            ran++;
        }
        vkc_program_destroy(ctx, &program);
        free(words);
    }
    CHECK(ran > 0 || (!forms[1] && mlodvk_context_emulates_doubles(ctx)), "no form of lookup.glsl ran");
    CHECK(device.validation_messages == 0, "%u validation message(s), the last: %s", device.validation_messages,
          device.last_message);
    mlodvk_context_destroy(ctx);
    mlodvk_device_destroy(&device);
    free(queries);
    free(want);
    mlod_atlas_destroy(atlas);
    return test_finish();
}
