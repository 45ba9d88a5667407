/* fuzz/fuzz_pipeline.c - libFuzzer harness: arbitrary bytes become a mesh or
   a point cloud, build options, views, epsilon and modes; the whole pipeline
   runs (build, refit, cut in basic, incremental and lazy modes, splat, ISM,
   hole filling) and every result is checked against the definitions of
   manylods.h, as are the public helpers.  A violation prints what broke and
   aborts, so libFuzzer keeps the input as a crash.

     make fuzz                      (every harness; see fuzz/run_all.sh), or
     fuzz/run.sh build/fuzz/fuzz_pipeline SECONDS WORKDIR   (this one), or
     clang -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
           -fno-sanitize-recover=all -I. fuzz/fuzz_pipeline.c -lm -o fuzz_pipeline
     ./fuzz_pipeline -max_len=4096 CORPUS_DIR
     MANYLODS_FUZZ_VERBOSE=1 ./fuzz_pipeline FILE...   how far each input got

   Checked:
   - a call that fails returns an error code equal to error.code, with a
     non-empty NUL-terminated message, sets its output pointer to NULL,
     leaves the caller's objects as they were (tree after refit, cut after
     an update that refused its input: its lists and its mlod_cut_bytes,
     atlas after hole filling) and holds no block it took (a cut update
     that ran out of memory: the cut reset, no more blocks and bytes than
     before); a call failed by an injected allocation failure
     returns MLOD_ERROR_OUT_OF_MEMORY and is tried again (one failure, or
     with the extension byte up to 16, every k-th allocation);
     input the documentation calls invalid (non-finite or >1e36 coordinates,
     indices out of range, N = 0 or > MANYLODS_MAX_LEAVES, bad radius_scale
     or attributes, strides not 0 or a multiple of 4 of at least 12 (radii:
     a multiple of 4), epsilon <= 0 or NaN, bad views, lazy_steps 0, refit
     of another mesh, a disc_scale outside (0, 1] other than 0 or NaN) never
     succeeds (a bad stride or disc_scale: MLOD_ERROR_INVALID_ARGUMENT), and
     input this harness made sane never fails except as documented
     (MLOD_ERROR_EMPTY for a mesh without area, OUT_OF_MEMORY when a failing
     allocation was injected);
   - after a build or refit: the tree's shape, every float finite, every
     child sphere inside its parent with the documented slack (exact
     arithmetic, tests/exact.h), cones likewise (trees over 16384 nodes:
     the first 8192 nodes and a scattered 1 in node_count / 8192 of the
     rest), unit cone axes; a build
     from strided arrays (NaN between the elements) equals the packed one;
   - after every cut update: each view's cut lists nodes left to right whose
     subtrees partition the leaves exactly once, status counts agree, and on
     sampled nodes c(child) <= c(parent); a basic cut agrees with the
     definition on sampled entries; incremental equals basic node for node
     (from the previous frame's cut, or from the root after mlod_cut_reset);
     lazy is a partition and reaches the basic cut when views stop; the cut
     is the same with and without a parallel-for hook;
   - the atlas is empty when made, keeps the disc_scale given (0: 1) and
     holds no NaN after splat, ISM and hole filling; projections and pixel
     rays give no NaN; on cube maps they follow the Vulkan specification's
     face selection table (face, pixel, depth z along the face's axis,
     inside between the near and far planes; a pixel's ray);
   - the helpers: mlod_view_frame_of agrees with mlod_view_check on every
     view, valid or not, and its frame is orthonormal, the view's (a cube
     map's six faces: the Vulkan table's frames and the 3s x 2s layout),
     and culls only nodes whose criterion is 0; mlod_cut_params_check
     follows the documented rules and mlod_cut_update accepts exactly what
     it accepts;
     mlod_tree_depth_nodes tiles the internal nodes depth by depth in the
     heap layout, for this tree, hostile leaf counts and any depth;
     mlod_refit_check_growth is monotone, within float range, refuses NaN,
     and refuses exactly the growths for which refit gives MLOD_ERROR_RANGE;
     mlod_sample refuses exactly what it documents and gives samples in
     the domain with finite weights, the same with the reversed hook;
   - every block the library allocated is given back.
   Each input stays in the tens of milliseconds: at most 256 vertices, 512
   triangles, 512 points, N = 4096, 8 views, 256-pixel tiles; the large case
   (1 in 16 extension bytes) allows 16384 points, N up to 65536, 64 views and
   2048-pixel tiles, with views x leaves <= 2^16; tiles shrink until leaves x
   tile pixels stays under 2^22.

   Input format: bytes are read in order (little endian) by rd_*; once the
   input is used up they come from a generator seeded by the whole input
   but its extension byte, so short inputs still make whole scenes.  First
   a flags byte:
     bit 0  point cloud (else a mesh)
     bit 1  sane geometry (finite, |x| <= 1e30, indices in range)
     bit 2  sane views, epsilon and options
     bit 3  run tasks through a serial parallel-for hook (reverse order)
     bit 4  fail one allocation (the next byte says which: 1 .. 256)
     bit 5  normals
     bit 6  colours
     bit 7  radii (point clouds)
   then the chaos bytes of geometry and of views: the chance, in 256, that
   a float of a part that is not sane is replaced by a hostile one (NaN,
   infinities, 1e38, denormals, raw bits); then the extension byte (0 when
   the input ends before it, so inputs of the format without it, given a 0
   there, run as they did):
     bit 0  strides: four bytes pick those of positions, normals, colours,
            radii (refit picks its positions' own)
     bit 1  a hostile disc_scale
     bit 2  failures: two bytes, every (2 + low nibble)-th allocation after
            the first (second byte) fails, 1 + high nibble times
     bits 3-6, all four: the large case
     bit 7  the incremental cut is reserved first (mlod_cut_reserve, two
            bytes: the mean cut size, below 2^14)
   then the scene (parse_scene), the build options (parse_build), the views
   (parse_views: every kind, cube maps for kind bytes 0xc0 .. 0xff), the
   rest in the order run_views reads them, and the helpers' arguments.  fuzz/make_corpus.c writes the seeds. */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "fuzz.h"
#include "reader.h"
#include "fz_errors.h"
#include "../tests/exact.h"
#include "../bench/shapes.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FZ_MAX_VERTICES 256u
#define FZ_MAX_TRIANGLES 512u
#define FZ_MAX_POINTS 512u
#define FZ_MAX_SAMPLES 4096u
#define FZ_MAX_VIEWS 8u
#define FZ_MAX_TILE 256u
/* The same with extension bit 3 (large): N, points, views, tile sides. */
#define FZ_LARGE_POINTS 16384u
#define FZ_LARGE_SAMPLES 65536u
#define FZ_LARGE_VIEWS 64u
#define FZ_LARGE_TILE 2048u
/* Bounds on the splat work: leaves x tile pixels, and atlas pixels; on the
   cut work: views x leaves. */
#define FZ_SPLAT_BUDGET ((uint64_t)1 << 22)
#define FZ_ATLAS_PIXELS ((uint64_t)1 << 18)
#define FZ_LARGE_ATLAS_PIXELS ((uint64_t)1 << 22)
#define FZ_CUT_BUDGET ((uint64_t)1 << 16)
/* Strides: at most 16 floats per element. */
#define FZ_MAX_STRIDE_FLOATS 16u
/* Extension byte bits. */
#define FZ_EXT_STRIDES 1u
#define FZ_EXT_DISC_SCALE 2u
#define FZ_EXT_FAILURES 4u
#define FZ_EXT_LARGE 0x78u /* all four bits: the large case stays occasional */
#define FZ_EXT_RESERVE 0x80u
#define FZ_SAMPLED 24u   /* nodes per view checked against the criterion */
#define FZ_LAZY_CALLS 64 /* lazy updates allowed to reach the basic cut */


/* ------------------------------------------------------------- reader */

static uint32_t rng_below_reader(fz_reader *r, uint32_t n) { return (uint32_t)(((uint64_t)rd_u32(r) * n) >> 32); }

/* A hostile float: one of the interesting values, or raw bits. */
static float rd_raw_float(fz_reader *r)
{
    static const uint32_t special[] = {
        0x00000000u, 0x80000000u, 0x7fc00000u, 0xffc00000u, 0x7f800000u, 0xff800000u, 0x7f7fffffu, 0xff7fffffu,
        0x00800000u, 0x00000001u, 0x80000001u, 0x7b40a2f6u /* ~1e36 */, 0x7b40a2f7u /* just above 1e36 */,
        0x3f800000u, 0xbf800000u, 0x33d6bf95u /* 1e-7 */, 0x7149f2cau /* 1e30 */, 0x4b000000u /* 2^23 */,
        0x7e967699u /* 1e38 */, 0x0da24260u /* 1e-30 */, 0x40490fdbu /* pi */, 0x3fc90fdbu /* pi/2 */};
    uint8_t pick = rd_u8(r);
    if (pick < 2 * sizeof special / sizeof special[0]) return bits_float(special[pick / 2]);
    return bits_float(rd_u32(r));
}


/* -------------------------------------------------------- allocator */

/* Injected failures: allocation number fail_at, and (extension bit 2)
   every every_k-th allocation after the first fail_after until fail_left
   more have failed. */
typedef struct fz_counter {
    unsigned long calls, live, fail_at, every_k, fail_after, fail_left;
    unsigned long failed; /* allocations failed on purpose so far */
} fz_counter;

static void *fz_alloc(void *user, size_t bytes)
{
    fz_counter *c = (fz_counter *)user;
    void *p;
    c->calls++;
    if ((c->fail_at && c->calls == c->fail_at) ||
        (c->every_k && c->fail_left && c->calls > c->fail_after && (c->calls - c->fail_after) % c->every_k == 0)) {
        if (!(c->fail_at && c->calls == c->fail_at)) c->fail_left--;
        c->failed++;
        return NULL;
    }
    if (bytes > ((size_t)1 << 30)) return NULL; /* no input here needs that much */
    p = malloc(bytes);
    if (p) c->live++;
    return p;
}

static void fz_free(void *user, void *p)
{
    fz_counter *c = (fz_counter *)user;
    if (!p) return;
    c->live--;
    free(p);
}

static void fz_run_reverse(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    (void)user;
    for (i = count; i-- > 0;) task(context, i);
}

/* ------------------------------------------------------ error checks */

/* An injected allocation failure may turn any call into OUT_OF_MEMORY. */
static int injected_oom(const fz_counter *c, mlod_result res)
{
    return res == MLOD_ERROR_OUT_OF_MEMORY && c->failed;
}

/* A call that failed because an allocation failed on purpose: it is tried
   again while the allocator has failures left; this bounds the tries. */
#define FZ_RETRIES 40

/* Around each call that may allocate: the live blocks before it.  A call
   that fails must give back everything it took. */
static void check_no_leak(const fz_counter *c, unsigned long live_before, const char *what)
{
    FZ_REQUIRE(c->live == live_before, "%s failed but holds %ld blocks more than before", what,
               (long)c->live - (long)live_before);
    FZ_NOTE("fuzz: %s failed (%lu allocations failed on purpose so far), gave back what it took\n", what, c->failed);
}

/* ------------------------------------------------------------ scenes */

typedef struct fz_scene {
    int points;
    uint32_t vertex_count, index_count;
    float positions[3 * FZ_LARGE_POINTS];
    float normals[3 * FZ_LARGE_POINTS];
    float colors[3 * FZ_LARGE_POINTS];
    float radii[FZ_LARGE_POINTS];
    uint32_t indices[3 * FZ_MAX_TRIANGLES];
    int has_normals, has_colors, has_radii;
    double centre[3], radius; /* of the finite positions, for sane views */
    int must_fail;            /* input the documentation calls invalid */
} fz_scene;

typedef struct fz_frame {
    double offset[3], scale[3];
} fz_frame;

/* Where sane coordinates live: an offset (up to 1e30 from the origin), a
   scale (1e-18 .. 1e18) and an aspect per axis (up to 1e6 : 1). */
static void parse_frame(fz_reader *r, fz_frame *f)
{
    double scale = ldexp(1.0, (int)(rd_u8(r) % 121) - 60);
    int k;
    uint8_t far = rd_u8(r);
    for (k = 0; k < 3; k++) {
        double aspect = (rd_u8(r) & 7) == 0 ? ldexp(1.0, -(int)(rd_u8(r) % 21)) : 1.0;
        f->scale[k] = scale * aspect;
        f->offset[k] = far < 32 ? rd_signed(r) * ldexp(1.0, (int)(far % 100)) : rd_signed(r) * 4.0 * scale;
    }
}

static int finite_within(float x, double limit) { return isfinite(x) && fabs(x) <= limit; }

static void parse_vectors(fz_reader *r, float *out, uint32_t count, const fz_frame *f, int unit, int zero_ok)
{
    uint32_t i, k;
    uint8_t dup = rd_u8(r) & 63; /* chance of repeating the previous vector */
    for (i = 0; i < count; i++) {
        if (i > 0 && rd_u8(r) < dup) {
            memcpy(out + 3 * i, out + 3 * (i - 1), 3 * sizeof(float));
            continue;
        }
        for (k = 0; k < 3; k++) {
            double v = unit ? rd_signed(r) : f->offset[k] + f->scale[k] * rd_signed(r);
            if (!zero_ok && unit && k == 2 && v == 0.0) v = 1.0;
            out[3 * i + k] = rd_maybe_raw(r, v);
        }
    }
}

/* Centre and radius of the box around the finite, in-range positions. */
static void scene_bounds(fz_scene *s)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, d2 = 0.0;
    uint32_t i, k, n = s->vertex_count;
    for (i = 0; i < n; i++) {
        const float *p = s->positions + 3 * i;
        if (!finite_within(p[0], 1e36) || !finite_within(p[1], 1e36) || !finite_within(p[2], 1e36)) continue;
        for (k = 0; k < 3; k++) {
            if (p[k] < lo[k]) lo[k] = p[k];
            if (p[k] > hi[k]) hi[k] = p[k];
        }
    }
    for (k = 0; k < 3; k++) {
        if (lo[k] > hi[k]) lo[k] = hi[k] = 0.0;
        s->centre[k] = 0.5 * (lo[k] + hi[k]);
        d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    s->radius = 0.5 * sqrt(d2);
    if (!(s->radius > 0.0)) s->radius = 1e-3 * (fabs(s->centre[0]) + fabs(s->centre[1]) + fabs(s->centre[2])) + 1e-6;
}

/* What the documentation calls invalid in positions, normals, colours and
   radii. */
static int vectors_invalid(const float *v, uint32_t count, double limit)
{
    uint32_t i;
    for (i = 0; i < 3 * count; i++)
        if (!finite_within(v[i], limit)) return 1;
    return 0;
}

static void parse_scene(fz_reader *r, fz_scene *s, uint8_t flags, int sane, int large)
{
    fz_frame frame;
    uint32_t i, triangles, cap = large ? FZ_LARGE_POINTS : FZ_MAX_POINTS;
    memset(s, 0, sizeof *s);
    s->points = flags & 1;
    s->has_normals = (flags >> 5) & 1;
    s->has_colors = (flags >> 6) & 1;
    s->has_radii = s->points && (flags >> 7);
    parse_frame(r, &frame);
    if (s->points) {
        s->vertex_count = sane ? 1 + rd_u16(r) % cap : rd_u16(r) % (cap + 1);
    } else {
        s->vertex_count = sane ? 1 + rd_u16(r) % FZ_MAX_VERTICES : rd_u16(r) % (FZ_MAX_VERTICES + 1);
        triangles = 1 + rd_u16(r) % FZ_MAX_TRIANGLES;
        s->index_count = 3 * triangles;
        for (i = 0; i < s->index_count; i++) {
            uint32_t v = rd_u16(r);
            if (sane || !s->vertex_count)
                s->indices[i] = s->vertex_count ? v % s->vertex_count : v;
            else if (r->chaos && rd_u8(r) < r->chaos / 8)
                s->indices[i] = rd_u8(r) & 1 ? 0xffffffffu : s->vertex_count + (v & 3);
            else
                s->indices[i] = v % s->vertex_count;
            if (s->indices[i] >= s->vertex_count) s->must_fail = 1;
        }
        if (!sane && r->chaos && rd_u8(r) == 0) { /* not a multiple of 3 */
            s->index_count -= 1 + (rd_u8(r) & 1);
            s->must_fail = 1;
        }
    }
    if (s->vertex_count == 0) s->must_fail = 1;
    parse_vectors(r, s->positions, s->vertex_count, &frame, 0, 1);
    if (vectors_invalid(s->positions, s->vertex_count, 1e36)) s->must_fail = 1;
    if (s->has_normals) {
        parse_vectors(r, s->normals, s->vertex_count, &frame, 1, rd_u8(r) < 32);
        if (vectors_invalid(s->normals, s->vertex_count, FLT_MAX)) s->must_fail = 1;
    }
    if (s->has_colors) {
        double range = ldexp(1.0, (int)(rd_u8(r) % 16) - 4);
        for (i = 0; i < 3 * s->vertex_count; i++) s->colors[i] = rd_maybe_raw(r, range * rd_unit(r));
        if (vectors_invalid(s->colors, s->vertex_count, FLT_MAX)) s->must_fail = 1;
    }
    if (s->has_radii) {
        double unit = frame.scale[0] * ldexp(1.0, -(int)(rd_u8(r) % 12));
        for (i = 0; i < s->vertex_count; i++) {
            s->radii[i] = rd_maybe_raw(r, rd_u8(r) < 16 ? 0.0 : unit * rd_unit(r));
            if (!(s->radii[i] >= 0.0f && s->radii[i] <= 1e36f)) s->must_fail = 1;
        }
    }
    scene_bounds(s);
}

static mlod_mesh fz_mesh_of(const fz_scene *s, const float *positions)
{
    mlod_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = positions;
    m.vertex_count = s->vertex_count;
    m.indices = s->indices;
    m.index_count = s->index_count;
    m.normals = s->has_normals ? s->normals : NULL;
    m.colors = s->has_colors ? s->colors : NULL;
    return m;
}

/* ------------------------------------------------------------ strides */

/* Strides of the attributes (extension bit 0), in bytes; 0 is packed.
   Invalid ones (not a multiple of 4, or under 3 floats; radii: not a
   multiple of 4) only where the input is not sane. */
typedef struct fz_strides {
    int on;
    size_t position, normal, color, radius;
    int bad_position, bad_normal, bad_color, bad_radius;
} fz_strides;

static size_t pick_stride(fz_reader *r, int sane, unsigned floats, int *bad)
{
    static const size_t bad3[8] = {1, 4, 8, 11, 13, 14, 15, 50}, bad1[8] = {1, 2, 3, 5, 6, 7, 13, 62};
    uint8_t b = rd_u8(r);
    *bad = 0;
    if (b < 0x20) return 0;
    if (b >= 0xe8 && !sane) {
        *bad = 1;
        return floats == 1 ? bad1[b & 7] : bad3[b & 7];
    }
    return 4 * (floats + b % (FZ_MAX_STRIDE_FLOATS + 1 - floats));
}

static void parse_strides(fz_reader *r, fz_strides *st, int sane)
{
    st->on = 1;
    st->position = pick_stride(r, sane, 3, &st->bad_position);
    st->normal = pick_stride(r, sane, 3, &st->bad_normal);
    st->color = pick_stride(r, sane, 3, &st->bad_color);
    st->radius = pick_stride(r, sane, 1, &st->bad_radius);
}

/* Copies of the arrays at the given strides; the bytes between elements
   are NaN, which the library must never read. */
static float fz_strided[5][FZ_MAX_STRIDE_FLOATS * FZ_LARGE_POINTS + 16];

static const float *strided_copy(int slot, const float *packed, uint32_t count, size_t stride, unsigned floats)
{
    unsigned char *dst = (unsigned char *)fz_strided[slot];
    size_t step = stride ? stride : floats * sizeof(float), i;
    memset(dst, 0xff, count * step + 16);
    for (i = 0; i < count; i++) memcpy(dst + i * step, packed + (size_t)floats * i, floats * sizeof(float));
    return fz_strided[slot];
}

static void stride_mesh(mlod_mesh *m, const fz_strides *st)
{
    if (!st->on) return;
    m->positions = strided_copy(0, m->positions, m->vertex_count, st->position, 3);
    m->position_stride = st->position;
    if (m->normals) m->normals = strided_copy(1, m->normals, m->vertex_count, st->normal, 3);
    m->normal_stride = st->normal;
    if (m->colors) m->colors = strided_copy(2, m->colors, m->vertex_count, st->color, 3);
    m->color_stride = st->color;
}

static int stride_mesh_bad(const mlod_mesh *m, const fz_strides *st)
{
    return st->on && (st->bad_position || (m->normals && st->bad_normal) || (m->colors && st->bad_color));
}

static mlod_points scene_points(const fz_scene *s, const float *positions)
{
    mlod_points p;
    memset(&p, 0, sizeof p);
    p.positions = positions;
    p.count = s->vertex_count;
    p.normals = s->has_normals ? s->normals : NULL;
    p.colors = s->has_colors ? s->colors : NULL;
    p.radii = s->has_radii ? s->radii : NULL;
    return p;
}

static void stride_points(mlod_points *p, const fz_strides *st)
{
    if (!st->on) return;
    p->positions = strided_copy(0, p->positions, p->count, st->position, 3);
    p->position_stride = st->position;
    if (p->normals) p->normals = strided_copy(1, p->normals, p->count, st->normal, 3);
    p->normal_stride = st->normal;
    if (p->colors) p->colors = strided_copy(2, p->colors, p->count, st->color, 3);
    p->color_stride = st->color;
    if (p->radii) p->radii = strided_copy(3, p->radii, p->count, st->radius, 1);
    p->radius_stride = st->radius;
}

static int stride_points_bad(const mlod_points *p, const fz_strides *st)
{
    return st->on && (st->bad_position || (p->normals && st->bad_normal) || (p->colors && st->bad_color) ||
                      (p->radii && st->bad_radius));
}

/* ---------------------------------------------------- build options */

typedef struct fz_build {
    mlod_build_desc desc;
    int must_fail;
} fz_build;

static void parse_build(fz_reader *r, fz_build *b, const fz_scene *s, int sane, int large, const mlod_allocator *a)
{
    uint32_t n = rd_u16(r), cap = FZ_MAX_SAMPLES;
    uint8_t scale = rd_u8(r), attributes = rd_u8(r);
    memset(b, 0, sizeof *b);
    b->desc.allocator = a;
    b->desc.seed = rd_u32(r);
    if (large) { /* up to 8192, 16384, 32768 or 65536: N beyond the usual cap more often than not */
        uint8_t high = rd_u8(r);
        n |= (uint32_t)high << 16;
        cap = FZ_LARGE_SAMPLES >> (high >> 6);
    }
    if (sane) {
        b->desc.sample_count = 1 + n % cap;
    } else if ((n & 0xffff) >= 0xfffd && r->chaos) {
        static const uint32_t huge[3] = {MANYLODS_MAX_LEAVES + 1u, 0xffffffffu, 0u};
        b->desc.sample_count = huge[(n & 0xffff) - 0xfffd];
    } else {
        b->desc.sample_count = n % (cap + 1);
    }
    if (!s->points && (b->desc.sample_count == 0 || b->desc.sample_count > MANYLODS_MAX_LEAVES)) b->must_fail = 1;
    b->desc.radius_scale = scale < 64 ? 0.0f : rd_maybe_raw(r, ldexp(1.0 + (scale & 15) / 16.0, (int)(scale >> 4) - 8));
    if (!(b->desc.radius_scale >= 0.0f) || !isfinite(b->desc.radius_scale)) b->must_fail = 1;
    b->desc.attributes = attributes & 15u;
    if ((attributes & 16u) && (attributes & MLOD_ATTR_REFIT)) b->desc.attributes |= MLOD_ATTR_REFIT_CACHE;
    if (!sane && r->chaos && attributes >= 0xf0) {
        b->desc.attributes = attributes;
        b->must_fail = 1;
    }
    if (sane && !s->has_colors) b->desc.attributes &= ~(uint32_t)MLOD_ATTR_COLOR;
    if ((b->desc.attributes & MLOD_ATTR_COLOR) && !s->has_colors) b->must_fail = 1;
}

/* ------------------------------------------------------------- views */

typedef struct fz_views {
    uint32_t count;
    mlod_view views[FZ_LARGE_VIEWS];
    int must_fail; /* some view is invalid by the documentation */
} fz_views;

static void unit3(double *v, const double *fallback)
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    int k;
    if (!(len > 1e-9) || !isfinite(len)) {
        for (k = 0; k < 3; k++) v[k] = fallback[k];
        return;
    }
    for (k = 0; k < 3; k++) v[k] /= len;
}

static float finite_float(double x)
{
    float f = (float)x;
    return isfinite(f) ? f : (x < 0 ? -FLT_MAX : FLT_MAX);
}

/* One sane view around the scene, then (with chaos) hostile fields.  The
   kind byte: 0xc0 .. 0xff a cube map (a quarter of the views), below that
   kind % 4, so that inputs written before cube maps keep the kinds of their
   other views.  A cube map's tile is 3s x 2s, and its fov_y, half_width
   and half_height, which it never reads, are sometimes hostile even in
   sane views; with chaos, bits 1-3 of the flags byte break one rule of a
   cube map in 3 of 8: 7 keeps the arbitrary tile the other kinds get
   (mostly not 3s x 2s), 6 puts the near plane at or behind the eye, 5
   the far plane on the near one. */
static void parse_view(fz_reader *r, mlod_view *v, const fz_scene *s, int sane, int large)
{
    static const double z[3] = {0.0, 0.0, 1.0}, x[3] = {1.0, 0.0, 0.0};
    double dir[3], eye[3], target[3], f[3], up[3], R = s->radius, dist, dot;
    uint8_t kind = rd_u8(r), place = rd_u8(r), tile_w = rd_u8(r), tile_h = rd_u8(r), flags = rd_u8(r);
    int k;
    memset(v, 0, sizeof *v);
    v->kind = kind >= 0xc0 ? MLOD_VIEW_CUBE : (mlod_view_kind)(kind % 4);
    for (k = 0; k < 3; k++) dir[k] = rd_signed(r);
    unit3(dir, z);
    /* eye from inside the scene (place < 16) to 256 scene radii away */
    dist = place < 16 ? R * 0.01 * (place + 1) : R * ldexp(1.0, (int)(place % 12) - 3);
    for (k = 0; k < 3; k++) {
        eye[k] = s->centre[k] + dist * dir[k];
        target[k] = s->centre[k] + 0.5 * R * rd_signed(r);
    }
    for (k = 0; k < 3; k++) f[k] = target[k] - eye[k];
    if (place >= 240)
        for (k = 0; k < 3; k++) f[k] = rd_signed(r); /* looking anywhere */
    unit3(f, z);
    for (k = 0; k < 3; k++) up[k] = rd_signed(r);
    dot = f[0] * up[0] + f[1] * up[1] + f[2] * up[2];
    for (k = 0; k < 3; k++) up[k] -= dot * f[k];
    unit3(up, fabs(f[0]) < 0.5 ? x : z);
    if (fabs(f[0] * up[0] + f[1] * up[1] + f[2] * up[2]) > 0.5) { /* the fallback was parallel */
        double c[3] = {f[1] * x[2] - f[2] * x[1], f[2] * x[0] - f[0] * x[2], f[0] * x[1] - f[1] * x[0]};
        unit3(c, z);
        for (k = 0; k < 3; k++) up[k] = c[k];
    }
    for (k = 0; k < 3; k++) {
        v->position[k] = rd_maybe_raw(r, finite_float(eye[k]));
        v->forward[k] = rd_maybe_raw(r, f[k]);
        v->up[k] = rd_maybe_raw(r, up[k]);
    }
    if (large) { /* 1 .. 2048 pixels */
        uint8_t low = rd_u8(r);
        v->width = sane || tile_w ? 1u + (((uint32_t)tile_w << 3 | (low & 7u)) % FZ_LARGE_TILE) : 0u;
        v->height = sane || tile_h ? 1u + (((uint32_t)tile_h << 3 | (low >> 5)) % FZ_LARGE_TILE) : 0u;
    } else {
        v->width = sane || tile_w ? 1u + tile_w % FZ_MAX_TILE : 0u;
        v->height = sane || tile_h ? 1u + tile_h % FZ_MAX_TILE : 0u;
    }
    if (v->kind == MLOD_VIEW_CUBE && !(!sane && r->chaos && (flags >> 1 & 7) == 7)) {
        uint32_t side = 1u + v->width % ((large ? FZ_LARGE_TILE : FZ_MAX_TILE) / 3u); /* 3s stays within the cap */
        v->width = 3u * side;
        v->height = 2u * side;
    }
    v->fov_y = rd_maybe_raw(r, 0.01 + 3.1 * rd_unit(r));
    if (v->kind == MLOD_VIEW_ORTHOGRAPHIC) {
        double near = -R * rd_unit(r) * 4.0;
        v->near_plane = rd_maybe_raw(r, finite_float(near));
        v->far_plane = rd_maybe_raw(r, finite_float(near + R * (0.5 + 16.0 * rd_unit(r))));
        v->half_width = rd_maybe_raw(r, finite_float(R * (0.05 + 4.0 * rd_unit(r))));
        v->half_height = rd_maybe_raw(r, finite_float(R * (0.05 + 4.0 * rd_unit(r))));
        if (sane && !(v->far_plane > v->near_plane)) v->far_plane = INFINITY;
        if (sane && !(v->half_width > 0.0f)) v->half_width = FLT_MIN;
        if (sane && !(v->half_height > 0.0f)) v->half_height = FLT_MIN;
    } else {
        uint8_t planes = rd_u8(r);
        double near = R * ldexp(1.0, -(int)(planes % 24));
        v->near_plane = rd_maybe_raw(r, finite_float(near));
        v->far_plane = rd_maybe_raw(r, planes & 0x80 ? INFINITY : finite_float(near + R * (1.0 + (planes & 0x70))));
        if (sane && !(v->near_plane > 0.0f)) v->near_plane = FLT_MIN;
        if (sane && !(v->far_plane > v->near_plane)) v->far_plane = INFINITY;
        v->half_width = rd_maybe_raw(r, 1.0);
        v->half_height = rd_maybe_raw(r, 1.0);
        if (v->kind == MLOD_VIEW_CUBE && (flags & 0x10)) { /* fields a cube map never reads */
            v->fov_y = rd_raw_float(r);
            v->half_width = rd_raw_float(r);
            v->half_height = rd_raw_float(r);
        }
        if (v->kind == MLOD_VIEW_CUBE && !sane && r->chaos && (flags >> 1 & 7) == 6)
            v->near_plane = flags & 0x10 ? -v->near_plane : 0.0f;
        if (v->kind == MLOD_VIEW_CUBE && !sane && r->chaos && (flags >> 1 & 7) == 5) v->far_plane = v->near_plane;
    }
    v->flags = flags & 1u;
    if (!sane && r->chaos) {
        if (kind >= 0xfc) v->kind = (mlod_view_kind)(kind & 7);
        if (flags >= 0xf0) v->flags = flags;
    }
}

static int vec_finite(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* The conditions the documentation makes errors (a subset of them). */
static int view_invalid(const mlod_view *v)
{
    double f2, u2;
    if ((unsigned)v->kind > 4u || !v->width || !v->height || (v->flags & ~1u)) return 1;
    if (!vec_finite(v->position) || !vec_finite(v->forward) || !vec_finite(v->up)) return 1;
    /* only the fields a kind reads count (NaN fails their comparisons below) */
    f2 = (double)v->forward[0] * v->forward[0] + (double)v->forward[1] * v->forward[1] +
         (double)v->forward[2] * v->forward[2];
    u2 = (double)v->up[0] * v->up[0] + (double)v->up[1] * v->up[1] + (double)v->up[2] * v->up[2];
    if (f2 == 0.0 || u2 == 0.0) return 1;
    if (v->kind == MLOD_VIEW_PERSPECTIVE)
        return !(v->fov_y > 0.0f && v->fov_y < 3.14159265f) || !(v->near_plane > 0.0f) || isinf(v->near_plane) ||
               !(v->far_plane > v->near_plane);
    if (v->kind == MLOD_VIEW_ORTHOGRAPHIC)
        return !(v->half_width > 0.0f) || !(v->half_height > 0.0f) || isinf(v->half_width) ||
               isinf(v->half_height) || !isfinite(v->near_plane) || !(v->far_plane > v->near_plane);
    /* a cube map: six s x s faces side by side, three wide and two high;
       its near plane finite and > 0, its far plane beyond (+inf allowed) */
    if (v->kind == MLOD_VIEW_CUBE)
        return v->width % 3 != 0 || v->height % 2 != 0 || v->width / 3 != v->height / 2 || !(v->near_plane > 0.0f) ||
               isinf(v->near_plane) || !(v->far_plane > v->near_plane);
    return 0;
}

/* Whether any of the views is invalid. */
static int views_invalid(const fz_views *vs)
{
    uint32_t v;
    for (v = 0; v < vs->count; v++)
        if (view_invalid(&vs->views[v])) return 1;
    return 0;
}

/* Tiles shrink (halving) until the splat work stays bounded; a cube map's
   3s x 2s tile halves its face side s, down to 3 x 2, and stays a cube
   map's.  Halving may make another tile valid (7 x 4 becomes 3 x 2):
   must_fail is worked out again. */
static void bound_tiles(fz_views *vs, uint32_t leaves, uint64_t atlas_pixels)
{
    for (;;) {
        uint64_t sum = 0, cell_w = 1, cell_h = 1, columns;
        uint32_t v;
        int shrunk = 0;
        for (v = 0; v < vs->count; v++) {
            sum += (uint64_t)vs->views[v].width * vs->views[v].height;
            if (vs->views[v].width > cell_w) cell_w = vs->views[v].width;
            if (vs->views[v].height > cell_h) cell_h = vs->views[v].height;
        }
        columns = (uint64_t)ceil(sqrt((double)vs->count));
        if (sum * leaves <= FZ_SPLAT_BUDGET && cell_w * cell_h * columns * columns <= atlas_pixels) break;
        for (v = 0; v < vs->count; v++) {
            mlod_view *view = &vs->views[v];
            uint32_t w = view->width, h = view->height;
            if (view->kind == MLOD_VIEW_CUBE && h % 2 == 0 && w == h / 2 * 3) {
                uint32_t side = h / 2 > 1 ? h / 4 : 1;
                view->width = 3 * side;
                view->height = 2 * side;
            } else {
                if (view->width > 1) view->width /= 2;
                if (view->height > 1) view->height /= 2;
            }
            shrunk |= view->width != w || view->height != h;
        }
        if (!shrunk) break;
    }
    vs->must_fail = views_invalid(vs);
}

static void parse_views(fz_reader *r, fz_views *vs, const fz_scene *s, int sane, int large, uint32_t leaves)
{
    uint32_t v;
    vs->count = 1 + rd_u8(r) % (large ? FZ_LARGE_VIEWS : FZ_MAX_VIEWS);
    if ((uint64_t)vs->count * leaves > FZ_CUT_BUDGET) vs->count = leaves >= FZ_CUT_BUDGET ? 1 : (uint32_t)(FZ_CUT_BUDGET / leaves);
    vs->must_fail = 0;
    for (v = 0; v < vs->count; v++) {
        parse_view(r, &vs->views[v], s, sane, large);
        if (view_invalid(&vs->views[v])) vs->must_fail = 1;
    }
    if (fz_verbose()) {
        uint32_t kinds[6] = {0, 0, 0, 0, 0, 0}, cubes_valid = 0;
        for (v = 0; v < vs->count; v++) {
            const mlod_view *view = &vs->views[v];
            kinds[(unsigned)view->kind < 5u ? (unsigned)view->kind : 5u]++;
            if (view->kind == MLOD_VIEW_CUBE && !view_invalid(view)) cubes_valid++;
        }
        FZ_NOTE("fuzz: %u views: %u perspective, %u paraboloid, %u dual paraboloid, %u orthographic, "
                "%u cube (%u valid), %u unknown\n",
                vs->count, kinds[0], kinds[1], kinds[2], kinds[3], kinds[4], cubes_valid, kinds[5]);
    }
}

/* The views a moment later: eyes and directions nudged. */
static void move_views(fz_reader *r, const fz_views *from, fz_views *to, double R)
{
    uint32_t v;
    int k;
    *to = *from;
    for (v = 0; v < to->count; v++) {
        mlod_view *view = &to->views[v];
        double step = R * ldexp(1.0, -(int)(rd_u8(r) % 16));
        for (k = 0; k < 3; k++) {
            float p = (float)(view->position[k] + step * rd_signed(r));
            float f = (float)(view->forward[k] + 0.05 * rd_signed(r));
            if (isfinite(p) && isfinite(view->position[k])) view->position[k] = p;
            if (isfinite(f) && isfinite(view->forward[k])) view->forward[k] = f;
        }
        if (!from->must_fail && view_invalid(view)) *view = from->views[v]; /* nudged into parallel vectors */
    }
}

/* ------------------------------------------------------ tree checks */

/* Left-to-right layout: node n covers leaf positions first[n] ..
   first[n] + count[n] - 1. */
typedef struct fz_layout {
    uint32_t leaves, nodes;
    uint32_t first[2 * FZ_LARGE_SAMPLES], count[2 * FZ_LARGE_SAMPLES];
} fz_layout;

static void layout_assign(fz_layout *L, uint32_t n, uint32_t *next)
{
    if (n >= L->leaves - 1) {
        L->first[n] = (*next)++;
        L->count[n] = 1;
        return;
    }
    layout_assign(L, 2 * n + 1, next);
    layout_assign(L, 2 * n + 2, next);
    L->first[n] = L->first[2 * n + 1];
    L->count[n] = L->count[2 * n + 1] + L->count[2 * n + 2];
}

static void layout_init(fz_layout *L, uint32_t leaves)
{
    uint32_t next = 0;
    L->leaves = leaves;
    L->nodes = 2 * leaves - 1;
    layout_assign(L, 0, &next);
}

#define FZ_CONE_SLACK (9.5367431640625e-7L - 1e-15L)
#define FZ_PI 3.14159265358979323846

static void check_tree(const mlod_tree *t, uint32_t leaves, uint32_t attributes, const char *when)
{
    uint32_t n, i;
    FZ_REQUIRE(t->leaf_count == leaves && t->node_count == 2 * leaves - 1, "%s: %u leaves, %u nodes, expected %u", when,
               t->leaf_count, t->node_count, leaves);
    FZ_REQUIRE(t->attributes == attributes, "%s: attributes 0x%x, asked 0x%x", when, t->attributes, attributes);
    FZ_REQUIRE(t->spheres && !t->cones == !(attributes & MLOD_ATTR_CONE) && !t->areas == !(attributes & MLOD_ATTR_AREA) &&
                   !t->colors == !(attributes & MLOD_ATTR_COLOR) && !t->leaf_sources == !(attributes & MLOD_ATTR_REFIT),
               "%s: arrays do not match the attributes", when);
    FZ_REQUIRE(t->bytes >= (size_t)t->node_count * t->bytes_per_node && t->bytes_per_node >= 16, "%s: bytes %zu", when,
               t->bytes);
    FZ_REQUIRE(isfinite(t->area_unit) && t->area_unit > 0.0, "%s: area_unit %g", when, t->area_unit);
    for (n = 0; n < t->node_count; n++) {
        const float *s = t->spheres + 4 * (size_t)n;
        FZ_REQUIRE(exact_finite4(s) && s[3] >= 0.0f, "%s: node %u sphere (%g %g %g r %g)", when, n, s[0], s[1], s[2],
                   s[3]);
        if (t->cones) {
            const float *c = t->cones + 4 * (size_t)n;
            double len = sqrt((double)c[0] * c[0] + (double)c[1] * c[1] + (double)c[2] * c[2]);
            FZ_REQUIRE(exact_finite4(c) && c[3] >= 0.0f && (c[3] >= FZ_PI || fabs(len - 1.0) <= 1e-5),
                       "%s: node %u cone (%g %g %g a %g)", when, n, c[0], c[1], c[2], c[3]);
        }
        if (t->areas) FZ_REQUIRE(isfinite(t->areas[n]) && t->areas[n] >= 0.0f, "%s: node %u area %g", when, n, t->areas[n]);
        if (t->colors)
            for (i = 0; i < 3; i++)
                FZ_REQUIRE(isfinite(t->colors[3 * (size_t)n + i]), "%s: node %u colour %g", when, n,
                           t->colors[3 * (size_t)n + i]);
    }
    for (n = 1; n < t->node_count; n++) {
        uint32_t p = (n - 1) / 2;
        /* large trees: every node of the top 2^13, then one in `every`
           (scattered by a multiplicative hash), in exact arithmetic */
        if (n >= 8192u && t->node_count > 16384u && (uint32_t)(n * 2654435761u) % (t->node_count / 8192u) != 0) continue;
        const float *ps = t->spheres + 4 * (size_t)p, *cs = t->spheres + 4 * (size_t)n;
        FZ_REQUIRE(exact_sphere_contains_filtered(ps, cs),
                   "%s: sphere of node %u (%.9g %.9g %.9g r %.9g) not inside its parent %u (%.9g %.9g %.9g r %.9g) "
                   "with slack 2^-20",
                   when, n, cs[0], cs[1], cs[2], cs[3], p, ps[0], ps[1], ps[2], ps[3]);
        if (t->cones)
            FZ_REQUIRE(exact_cone_contains(t->cones + 4 * (size_t)p, t->cones + 4 * (size_t)n, FZ_CONE_SLACK),
                       "%s: cone of node %u (a %.9g) not inside its parent's (a %.9g) with 2^-20 rad", when, n,
                       t->cones[4 * (size_t)n + 3], t->cones[4 * (size_t)p + 3]);
    }
    if (t->leaf_sources && t->leaf_barycentrics)
        for (i = 0; i < leaves; i++) {
            float s = t->leaf_barycentrics[2 * (size_t)i], u = t->leaf_barycentrics[2 * (size_t)i + 1];
            FZ_REQUIRE(s >= 0.0f && u >= 0.0f && s + u <= 1.0f + 1e-6f && t->leaf_sources[i] < t->triangle_count,
                       "%s: leaf %u source %u (%g, %g)", when, i, t->leaf_sources[i], s, u);
        }
}

/* ------------------------------------------------------- cut checks */

typedef struct fz_rng {
    uint64_t s;
} fz_rng;

static uint32_t rng_below(fz_rng *g, uint32_t n)
{
    g->s = g->s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(((g->s >> 32) * (uint64_t)n) >> 32);
}

/* The status the definition gives a cut node of criterion c (c = 0 may
   also be a sphere of radius 0, drawn). */
static uint8_t status_of(double c, float eps, int leaf)
{
    if (c == 0.0) return MLOD_STATUS_CULLED;
    if (c <= eps) return MLOD_STATUS_DRAWN;
    return leaf ? MLOD_STATUS_OVERSIZE : MLOD_STATUS_COARSE;
}

/* Every view's cut: a left-to-right partition of the leaves with
   consistent counts; c(child) <= c(parent) on sampled nodes; a basic cut
   follows the definition on sampled entries. */
static void check_cut(const mlod_cut *cut, const mlod_tree *t, const fz_layout *L, const fz_views *vs, float eps,
                      int basic, int sampled, fz_rng *g, const char *when)
{
    uint32_t v, i;
    FZ_REQUIRE(mlod_cut_view_count(cut) == vs->count && mlod_cut_bytes(cut) > 0, "%s: cut view count or bytes", when);
    for (v = 0; v < vs->count; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        uint32_t next = 0, by[5] = {0, 0, 0, 0, 0};
        FZ_REQUIRE(cv.count > 0 && cv.nodes && cv.status, "%s: view %u has an empty cut", when, v);
        for (i = 0; i < cv.count; i++) {
            uint32_t n = cv.nodes[i];
            uint8_t st = cv.status[i];
            FZ_REQUIRE(n < t->node_count, "%s: view %u entry %u is node %u of %u", when, v, i, n, t->node_count);
            FZ_REQUIRE(L->first[n] == next, "%s: view %u entry %u (node %u) covers leaves from %u, expected %u: not a "
                                            "left-to-right partition",
                       when, v, i, n, L->first[n], next);
            next += L->count[n];
            FZ_REQUIRE(st >= MLOD_STATUS_DRAWN && st <= MLOD_STATUS_COARSE, "%s: view %u node %u status %u", when, v, n,
                       st);
            FZ_REQUIRE(st != MLOD_STATUS_OVERSIZE || n >= t->leaf_count - 1, "%s: view %u: internal node %u OVERSIZE",
                       when, v, n);
            FZ_REQUIRE(st != MLOD_STATUS_COARSE || (!basic && n < t->leaf_count - 1), "%s: view %u node %u COARSE", when,
                       v, n);
            by[st]++;
        }
        FZ_REQUIRE(next == t->leaf_count, "%s: view %u covers %u of %u leaves", when, v, next, t->leaf_count);
        FZ_REQUIRE(by[1] == cv.drawn && by[2] == cv.culled && by[3] == cv.oversize && by[4] == cv.coarse,
                   "%s: view %u counts %u/%u/%u/%u, list %u/%u/%u/%u", when, v, cv.drawn, cv.culled, cv.oversize,
                   cv.coarse, by[1], by[2], by[3], by[4]);
        for (i = 0; sampled && i < FZ_SAMPLED && t->node_count > 1; i++) {
            uint32_t n = 1 + rng_below(g, t->node_count - 1), p = (n - 1) / 2;
            double cn = mlod_criterion(t, n, &vs->views[v]), cp = mlod_criterion(t, p, &vs->views[v]);
            FZ_REQUIRE(!isnan(cn) && !isnan(cp) && cn >= 0.0 && cp >= 0.0, "%s: view %u: c(%u) = %g, c(%u) = %g", when, v,
                       n, cn, p, cp);
            FZ_REQUIRE(cn <= cp, "%s: view %u: c(child %u) = %.17g > c(parent %u) = %.17g", when, v, n, cn, p, cp);
        }
        for (i = 0; sampled && basic && i < FZ_SAMPLED && i < cv.count; i++) {
            uint32_t k = cv.count <= FZ_SAMPLED ? i : rng_below(g, cv.count), n = cv.nodes[k];
            double c = mlod_criterion(t, n, &vs->views[v]);
            uint8_t want = status_of(c, eps, n >= t->leaf_count - 1);
            if (c == 0.0 && cv.status[k] == MLOD_STATUS_DRAWN) want = MLOD_STATUS_DRAWN; /* radius 0, not culled */
            FZ_REQUIRE(want != MLOD_STATUS_COARSE && cv.status[k] == want,
                       "%s: view %u node %u: c = %.17g, epsilon %g, status %u, the definition gives %u", when, v, n, c,
                       (double)eps, cv.status[k], want);
            if (n > 0) {
                double cp = mlod_criterion(t, (n - 1) / 2, &vs->views[v]);
                FZ_REQUIRE(cp > eps, "%s: view %u node %u in the cut but its parent is valid (c = %.17g <= %g)", when,
                           v, n, cp, (double)eps);
            }
        }
    }
}

/* FNV-1a over view v's list: its count, nodes and statuses. */
static uint64_t list_hash(const mlod_cut *cut, uint32_t v)
{
    mlod_cut_view cv = mlod_cut_get(cut, v);
    uint64_t h = 1469598103934665603ull ^ cv.count;
    uint32_t i;
    for (i = 0; i < cv.count; i++) {
        h = (h ^ cv.nodes[i]) * 1099511628211ull;
        h = (h ^ cv.status[i]) * 1099511628211ull;
    }
    return h;
}

static int same_cut(const mlod_cut *a, const mlod_cut *b, uint32_t views, uint32_t *differs)
{
    uint32_t v;
    for (v = 0; v < views; v++) {
        mlod_cut_view x = mlod_cut_get(a, v), y = mlod_cut_get(b, v);
        if (x.count != y.count || x.drawn != y.drawn || x.culled != y.culled || x.oversize != y.oversize ||
            x.coarse != y.coarse || (x.count && (memcmp(x.nodes, y.nodes, x.count * sizeof(uint32_t)) ||
                                                 memcmp(x.status, y.status, x.count)))) {
            *differs = v;
            return 0;
        }
    }
    return 1;
}

/* A copy of a cut's lists, to see that a failed update changed nothing. */
typedef struct fz_snapshot {
    uint32_t count[FZ_LARGE_VIEWS];
    uint32_t *nodes;
    uint8_t *status;
    size_t total;
} fz_snapshot;

static void snapshot_take(fz_snapshot *s, const mlod_cut *cut, uint32_t views)
{
    uint32_t v;
    size_t at = 0;
    s->total = 0;
    for (v = 0; v < views; v++) s->total += mlod_cut_get(cut, v).count;
    s->nodes = (uint32_t *)malloc((s->total + 1) * sizeof(uint32_t));
    s->status = (uint8_t *)malloc(s->total + 1);
    FZ_REQUIRE(s->nodes && s->status, "snapshot: out of memory");
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        s->count[v] = cv.count;
        if (cv.count) {
            memcpy(s->nodes + at, cv.nodes, cv.count * sizeof(uint32_t));
            memcpy(s->status + at, cv.status, cv.count);
        }
        at += cv.count;
    }
}

static int snapshot_same(const fz_snapshot *s, const mlod_cut *cut, uint32_t views)
{
    uint32_t v;
    size_t at = 0;
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        if (cv.count != s->count[v]) return 0;
        if (cv.count && (memcmp(s->nodes + at, cv.nodes, cv.count * sizeof(uint32_t)) ||
                         memcmp(s->status + at, cv.status, cv.count)))
            return 0;
        at += cv.count;
    }
    return 1;
}

static void snapshot_free(fz_snapshot *s)
{
    free(s->nodes);
    free(s->status);
}

/* ------------------------------------------------------------ context */

typedef struct fz_ctx {
    fz_counter counter;
    mlod_allocator alloc;
    mlod_parallel hook;
    const mlod_parallel *parallel;
    fz_rng rng;
    int sane_geometry, sane_views;
    uint8_t ext;         /* the extension byte: FZ_EXT_* */
    fz_strides strides;  /* extension bit 0 */
} fz_ctx;

/* A failed update gives back what it grew: the cut holds no more bytes
   than before (the same where it failed before any work).
   (-DFZ_NO_CUT_BYTES_CHECK turns this off.) */
#ifndef FZ_NO_CUT_BYTES_CHECK
#define FZ_CUT_BYTES_CHECK(before, after, what)                                                                        \
    FZ_REQUIRE((after) <= (before), "%s failed but the cut grew from %zu to %zu bytes", what, (size_t)(before),       \
               (size_t)(after))
#else
#define FZ_CUT_BYTES_CHECK(before, after, what) ((void)0)
#endif

/* One cut update, checked: on failure an error with a message; the cut
   unchanged where the input was refused, reset (no entries in any view)
   where an injected allocation failure stopped it, which is retried (up
   to FZ_RETRIES times).  Returns the result. */
static mlod_result cut_update(fz_ctx *c, mlod_cut *cut, const mlod_tree *t, const fz_views *vs,
                              const mlod_cut_params *p, int must_fail, int may_fail, const char *what)
{
    fz_snapshot snap;
    mlod_error e;
    mlod_result res;
    unsigned long live;
    size_t bytes;
    int tries = 0;
    memset(&e, 0, sizeof e);
    snapshot_take(&snap, cut, vs->count);
retry:
    live = c->counter.live;
    bytes = mlod_cut_bytes(cut);
    res = mlod_cut_update(cut, t, vs->views, p, &e);
    if (res != MLOD_OK) {
        if (injected_oom(&c->counter, res)) FZ_NOTE("fuzz: %s: injected allocation failure, retrying\n", what);
        FZ_NOTE("fuzz: %s: %s: %s\n", what, mlod_result_name(res), e.message);
        fz_where = what;
        check_error(res, &e);
        if (res == MLOD_ERROR_OUT_OF_MEMORY) {
            uint32_t v;
            for (v = 0; v < vs->count; v++)
                FZ_REQUIRE(mlod_cut_get(cut, v).count == 0, "%s: ran out of memory but view %u kept a cut", what, v);
            FZ_REQUIRE(c->counter.live <= live, "%s failed but holds %ld blocks more than before", what,
                       (long)c->counter.live - (long)live);
        } else {
            FZ_REQUIRE(snapshot_same(&snap, cut, vs->count), "%s: failed with %s but changed the cut", what,
                       mlod_result_name(res));
            check_no_leak(&c->counter, live, what);
        }
        FZ_CUT_BYTES_CHECK(bytes, mlod_cut_bytes(cut), what);
        if (injected_oom(&c->counter, res) && tries++ < FZ_RETRIES) goto retry;
        FZ_REQUIRE(res != MLOD_ERROR_OUT_OF_MEMORY, "%s: out of memory without an injected failure", what);
        FZ_REQUIRE(must_fail || may_fail, "%s: valid input failed with %s: %s", what, mlod_result_name(res), e.message);
    } else {
        FZ_REQUIRE(!must_fail, "%s: invalid input (views or epsilon) succeeded", what);
        FZ_REQUIRE(e.code == MLOD_OK, "%s: success with error.code %d", what, (int)e.code);
    }
    snapshot_free(&snap);
    return res;
}

static void check_atlas(const mlod_atlas *a, const char *when)
{
    size_t i, pixels = (size_t)a->width * a->height;
    for (i = 0; i < pixels; i++) {
        FZ_REQUIRE(!isnan(a->depth[i]), "%s: atlas depth NaN at pixel %zu (%zu, %zu)", when, i, i % a->width,
                   i / a->width);
        if (a->normal)
            FZ_REQUIRE(!isnan(a->normal[3 * i]) && !isnan(a->normal[3 * i + 1]) && !isnan(a->normal[3 * i + 2]),
                       "%s: atlas normal NaN at pixel %zu", when, i);
        if (a->color)
            FZ_REQUIRE(!isnan(a->color[3 * i]) && !isnan(a->color[3 * i + 1]) && !isnan(a->color[3 * i + 2]),
                       "%s: atlas colour NaN at pixel %zu", when, i);
    }
}

/* A hash of the atlas's images, to see that a failed call changed nothing. */
static uint64_t atlas_hash(const mlod_atlas *a)
{
    size_t pixels = (size_t)a->width * a->height, i;
    uint64_t h = 1469598103934665603ull;
    const float *arrays[3];
    size_t sizes[3];
    int k;
    arrays[0] = a->depth;
    sizes[0] = pixels;
    arrays[1] = a->normal;
    sizes[1] = a->normal ? 3 * pixels : 0;
    arrays[2] = a->color;
    sizes[2] = a->color ? 3 * pixels : 0;
    for (k = 0; k < 3; k++)
        for (i = 0; i < sizes[k]; i++) {
            uint32_t bits;
            memcpy(&bits, arrays[k] + i, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
    return h;
}

/* Hole filling, checked: a failure is an injected OUT_OF_MEMORY that
   changes nothing and leaks nothing, tried again. */
static void fill_holes(fz_ctx *c, mlod_atlas *atlas, const char *when)
{
    int may_fail = c->counter.fail_at || c->counter.every_k, tries;
    for (tries = 0;; tries++) {
        uint64_t before = may_fail ? atlas_hash(atlas) : 0;
        unsigned long live = c->counter.live;
        mlod_error e;
        mlod_result res = mlod_atlas_fill_holes(atlas, c->parallel, &e);
        if (res == MLOD_OK) break;
        fz_where = "mlod_atlas_fill_holes";
        check_error(res, &e);
        FZ_REQUIRE(injected_oom(&c->counter, res), "mlod_atlas_fill_holes failed with %s", mlod_result_name(res));
        FZ_REQUIRE(atlas_hash(atlas) == before, "mlod_atlas_fill_holes failed but changed the atlas");
        check_no_leak(&c->counter, live, "mlod_atlas_fill_holes");
        if (tries >= FZ_RETRIES) return;
    }
    check_atlas(atlas, when);
}

/* A hostile disc_scale (extension bit 1). */
static float rd_disc_scale(fz_reader *r)
{
    static const uint32_t bits[16] = {
        0x7fc00000u /* NaN */, 0xffc00000u /* -NaN */, 0xbf800000u /* -1 */, 0x80000001u /* -denormal */,
        0x7f800000u /* inf */, 0xff800000u /* -inf */, 0x3f800001u /* 1 + ulp */, 0x40000000u /* 2 */,
        0x7f7fffffu /* FLT_MAX */, 0x00000001u /* denormal: valid */, 0x3f800000u /* 1 */, 0x00000000u /* 0: 1 */,
        0x80000000u /* -0: 1 */, 0x3f7fffffu /* 1 - ulp */, 0x3c23d70au /* 0.01 */, 0x7f800001u /* signalling NaN */};
    uint8_t b = rd_u8(r);
    return b < 0xf0 ? bits_float(bits[b & 15]) : bits_float(rd_u32(r));
}

/* Atlas, splat, ISM, hole filling. */
static void run_splat(fz_ctx *c, fz_reader *r, const mlod_tree *t, const mlod_cut *cut, const fz_views *vs)
{
    mlod_atlas_desc desc;
    mlod_atlas *atlas = (mlod_atlas *)&desc;
    mlod_error e;
    mlod_result res;
    uint8_t channels = rd_u8(r);
    int mismatch, bad_disc, bad_channels, bad_splat, bad_order = 0, tries = 0;
    uint32_t *order = NULL, v;
    memset(&desc, 0, sizeof desc);
    desc.columns = rd_u8(r) % 10;
    desc.channels = channels & 3u;
    /* the cells' order (no byte of its own): columns 1, 4, 7 reversed, 8 with a view twice (refused) */
    if (desc.columns % 3 == 1 || (desc.columns == 8 && vs->count > 1)) {
        order = (uint32_t *)malloc(sizeof *order * vs->count);
        if (!order) return;
        for (v = 0; v < vs->count; v++) order[v] = vs->count - 1 - v;
        if (desc.columns == 8) order[vs->count - 1] = order[0];
        bad_order = desc.columns == 8;
        desc.order = order;
    }
    desc.disc_scale = (float)((channels >> 2) & 7u) / 7.0f; /* 0 (whole discs), 1/7 .. 1 */
    /* the reconstruction: auto, sphere or tangent discs; hostile, one that is none */
    desc.splat = (channels >> 5) % 4u == 3u ? (r->chaos ? 3u + (channels >> 7) * 0x7ffffffcu : 0u) : (channels >> 5) % 4u;
    if (!c->sane_views && r->chaos && channels >= 0xf8) desc.channels = channels;
    if (c->ext & FZ_EXT_DISC_SCALE) desc.disc_scale = rd_disc_scale(r);
    /* the documentation: outside (0, 1] other than 0, or NaN, is invalid */
    bad_disc = !(desc.disc_scale >= 0.0f && desc.disc_scale <= 1.0f);
    bad_channels = (desc.channels & ~3u) != 0;
    bad_splat = desc.splat > MLOD_SPLAT_TANGENT;
retry:
    {
        unsigned long live = c->counter.live;
        atlas = (mlod_atlas *)&desc;
        res = mlod_atlas_create(vs->views, vs->count, &desc, &c->alloc, &atlas, &e);
        if (res != MLOD_OK) {
            fz_where = "mlod_atlas_create";
            check_error(res, &e);
            FZ_REQUIRE(atlas == NULL, "mlod_atlas_create failed but left *out_atlas set");
            check_no_leak(&c->counter, live, "mlod_atlas_create");
            FZ_REQUIRE(injected_oom(&c->counter, res) || bad_channels || bad_disc || bad_order || bad_splat,
                       "mlod_atlas_create failed with %s for valid tiles and options: %s", mlod_result_name(res),
                       e.message);
            FZ_REQUIRE(!bad_disc || bad_channels || res == MLOD_ERROR_INVALID_ARGUMENT,
                       "mlod_atlas_create refused disc_scale %g with %s, not MLOD_ERROR_INVALID_ARGUMENT",
                       (double)desc.disc_scale, mlod_result_name(res));
            FZ_REQUIRE(!bad_order || bad_channels || bad_disc || injected_oom(&c->counter, res) ||
                           res == MLOD_ERROR_INVALID_ARGUMENT,
                       "mlod_atlas_create refused an order with a view twice with %s, not MLOD_ERROR_INVALID_ARGUMENT",
                       mlod_result_name(res));
            FZ_REQUIRE(!bad_splat || bad_channels || bad_disc || bad_order || injected_oom(&c->counter, res) ||
                           res == MLOD_ERROR_INVALID_ARGUMENT,
                       "mlod_atlas_create refused splat %u with %s, not MLOD_ERROR_INVALID_ARGUMENT", desc.splat,
                       mlod_result_name(res));
            if (injected_oom(&c->counter, res) && !bad_channels && !bad_disc && !bad_order && !bad_splat &&
                tries++ < FZ_RETRIES)
                goto retry;
            free(order);
            return;
        }
    }
    FZ_REQUIRE(!bad_order, "mlod_atlas_create accepted an order with a view twice");
    for (v = 0; order && v < vs->count; v++) {
        const uint32_t *tile = atlas->tiles + 4 * (size_t)order[v];
        FZ_REQUIRE(tile[0] == (v % atlas->columns) * atlas->cell_width && tile[1] == (v / atlas->columns) * atlas->cell_height,
                   "desc.order: view %u is not in cell %u", order[v], v);
    }
    free(order);
    FZ_REQUIRE(!bad_channels, "mlod_atlas_create accepted unknown channel bits 0x%x", desc.channels);
    FZ_REQUIRE(!bad_disc, "mlod_atlas_create accepted disc_scale %g", (double)desc.disc_scale);
    FZ_REQUIRE(!bad_splat && atlas->splat == desc.splat, "mlod_atlas_create accepted splat %u as %u", desc.splat,
               atlas->splat);
    FZ_REQUIRE(atlas->disc_scale == (desc.disc_scale == 0.0f ? 1.0f : desc.disc_scale),
               "atlas disc_scale %g for desc.disc_scale %g", (double)atlas->disc_scale, (double)desc.disc_scale);
    {
        size_t i, pixels = (size_t)atlas->width * atlas->height;
        for (i = 0; i < pixels; i++)
            FZ_REQUIRE(atlas->depth[i] == INFINITY && (!atlas->normal || atlas->normal[3 * i] == 0.0f) &&
                           (!atlas->color || atlas->color[3 * i] == 0.0f),
                       "a new atlas is not empty at pixel %zu", i);
    }
    mismatch = (atlas->normal && !t->cones) || (atlas->color && !t->colors) ||
               (atlas->splat == MLOD_SPLAT_TANGENT && !t->cones);
    res = mlod_splat(atlas, t, cut, vs->views, c->parallel, &e);
    if (res != MLOD_OK) {
        fz_where = "mlod_splat";
        check_error(res, &e);
        FZ_REQUIRE(mismatch, "mlod_splat failed with %s: %s", mlod_result_name(res), e.message);
    } else {
        FZ_REQUIRE(!mismatch, "mlod_splat accepted atlas channels the tree lacks");
        check_atlas(atlas, "after mlod_splat");
        fill_holes(c, atlas, "after mlod_atlas_fill_holes (splat)");
    }
    res = mlod_splat_ism(atlas, t, vs->views, rd_u8(r) % 64, rd_u32(r), c->parallel, &e);
    if (res != MLOD_OK) {
        fz_where = "mlod_splat_ism";
        check_error(res, &e);
        FZ_REQUIRE(mismatch, "mlod_splat_ism failed with %s: %s", mlod_result_name(res), e.message);
    } else {
        check_atlas(atlas, "after mlod_splat_ism");
        fill_holes(c, atlas, "after mlod_atlas_fill_holes (ISM)");
    }
    FZ_NOTE("fuzz: %u views, every cut mode, splat, ISM and hole filling checked\n", vs->count);
    mlod_atlas_destroy(atlas);
}

/* The atlas that follows the incremental cut from frame to frame
   (mlod_splat keeps the tiles that show what it would draw) against a new
   atlas drawn whole from the basic cut of the same frame: the same bits.
   follow_begin draws frame 1 (NULL where that fails: an injected
   allocation failure, a cut that failed); follow_check frame 2. */
static mlod_atlas *follow_begin(fz_ctx *c, const mlod_tree *t, const mlod_cut *cut, const fz_views *vs, uint32_t fill)
{
    mlod_atlas_desc desc;
    mlod_atlas *a = NULL;
    mlod_error e;
    memset(&desc, 0, sizeof desc);
    desc.channels = (t->cones ? (uint32_t)MLOD_ATLAS_NORMAL : 0u) | (t->colors ? (uint32_t)MLOD_ATLAS_COLOR : 0u);
    desc.fill_holes = fill;
    if (mlod_atlas_create(vs->views, vs->count, &desc, &c->alloc, &a, &e) != MLOD_OK) return NULL;
    if (mlod_splat(a, t, cut, vs->views, c->parallel, &e) != MLOD_OK) {
        check_error(e.code, &e);
        mlod_atlas_destroy(a);
        return NULL;
    }
    FZ_REQUIRE(a->redrawn == vs->count, "a new atlas drew %u of %u tiles", a->redrawn, vs->count);
    return a;
}

static void follow_check(fz_ctx *c, mlod_atlas *a, const mlod_tree *t, mlod_cut *cut, const mlod_cut *basic,
                         const fz_views *vs, const mlod_cut_params *p)
{
    mlod_atlas_desc desc;
    mlod_atlas *fresh = NULL;
    mlod_error e;
    mlod_result res;
    if (!a) return;
    res = mlod_splat(a, t, cut, vs->views, c->parallel, &e);
    if (res != MLOD_OK) { /* other tile sizes, a failed update, an injected failure filling holes */
        fz_where = "mlod_splat (the atlas kept from frame 1)";
        check_error(res, &e);
        FZ_REQUIRE(res == MLOD_ERROR_MISMATCH || injected_oom(&c->counter, res),
                   "mlod_splat into the atlas of frame 1 failed with %s: %s", mlod_result_name(res), e.message);
        return;
    }
    memset(&desc, 0, sizeof desc);
    desc.channels = a->channels;
    desc.fill_holes = a->fill_holes;
    if (mlod_atlas_create(vs->views, vs->count, &desc, &c->alloc, &fresh, &e) != MLOD_OK) return;
    if (mlod_splat(fresh, t, basic, vs->views, c->parallel, &e) == MLOD_OK) {
        FZ_REQUIRE(fz_same_atlas(a, fresh),
                   "the atlas kept from frame 1 (%u of %u tiles redrawn, %u patched) differs from a full redraw of frame 2",
                   a->redrawn, vs->count, a->patched);
        FZ_NOTE("fuzz: the atlas kept from frame 1 redrew %u of %u tiles and patched %u, equal to a full redraw\n",
                a->redrawn, vs->count, a->patched);
        /* the same views again, the tree as it is: the cut keeps its lists
           and versions, and the splat every tile, with the same bits */
        if (cut_update(c, cut, t, vs, p, 0, 0, "incremental update, frame 2 again") == MLOD_OK &&
            mlod_splat(a, t, cut, vs->views, c->parallel, &e) == MLOD_OK) {
            FZ_REQUIRE(a->redrawn == 0 && a->patched == 0, "nothing changed, yet mlod_splat redrew %u of %u tiles and patched %u",
                       a->redrawn, vs->count, a->patched);
            FZ_REQUIRE(fz_same_atlas(a, fresh), "nothing changed, yet the kept atlas differs from a full redraw");
        }
    }
    mlod_atlas_destroy(fresh);
}

/* The deformed scene of a frame later, for refit. */
static void perturb(fz_reader *r, const fz_scene *s, float *out, int sane)
{
    uint8_t how = rd_u8(r);
    double scale = (how & 3) == 0 ? ldexp(1.0, (int)(rd_u8(r) % 41) - 20) : 1.0;
    double jitter = s->radius * ldexp(1.0, -(int)(rd_u8(r) % 24));
    uint32_t i;
    int k;
    for (i = 0; i < s->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            double p = s->positions[3 * i + k];
            double moved = s->centre[k] + (p - s->centre[k]) * scale + jitter * rd_signed(r);
            out[3 * i + k] = isfinite(p) ? (float)moved : s->positions[3 * i + k];
            if (!sane && r->chaos && rd_u8(r) < r->chaos / 16) out[3 * i + k] = rd_raw_float(r);
        }
}

/* MLOD_ATTR_REFIT_CACHE on hostile motion: after a refit to `moved`, a
   second refit where a fuzzed subset of the vertices moved (by an ulp or
   by fuzzed amounts, normals sometimes dropped) computes only the leaves
   of triangles whose corners changed; computing everything again from
   the same mesh (the revision counted up by hand, so that the refit
   trusts nothing it kept) must give the same bits.  Then back to
   `moved`, as the caller expects. */
static void refit_cache_check(fz_reader *r, const fz_scene *s, mlod_tree *t, const float *moved,
                              const mlod_parallel *parallel)
{
    size_t n = t->node_count, i;
    float *again = (float *)malloc(sizeof(float) * 3 * (s->vertex_count + 1));
    float *keep = (float *)malloc(sizeof(float) * 12 * n);
    uint8_t share = rd_u8(r), how = rd_u8(r);
    mlod_mesh mesh = fz_mesh_of(s, moved);
    mlod_error e;
    FZ_REQUIRE(again && keep, "out of memory");
    memcpy(again, moved, sizeof(float) * 3 * s->vertex_count);
    for (i = 0; i < 3 * (size_t)s->vertex_count; i++)
        if (rd_u8(r) < share) {
            float x = again[i], y = how & 1 ? nextafterf(x, INFINITY) : x + (float)(s->radius * ldexp(rd_signed(r), -(int)(how % 24)));
            if (isfinite(y) && fabsf(y) < 1e30f) again[i] = y;
        }
    mesh.positions = again;
    if (how & 0x80) mesh.normals = NULL;
    if (mlod_refit_mesh(t, &mesh, parallel, &e) == MLOD_OK) { /* a growth out of range may refuse it */
        memcpy(keep, t->spheres, sizeof(float) * 4 * n);
        if (t->cones) memcpy(keep + 4 * n, t->cones, sizeof(float) * 4 * n);
        if (t->colors) memcpy(keep + 8 * n, t->colors, sizeof(float) * 3 * n);
        if (t->areas) memcpy(keep + 11 * n, t->areas, sizeof(float) * n);
        t->revision++;
        fz_where = "refit with MLOD_ATTR_REFIT_CACHE";
        FZ_REQUIRE(mlod_refit_mesh(t, &mesh, parallel, &e) == MLOD_OK, "the same refit computed whole failed: %s",
                   e.message);
        FZ_REQUIRE(memcmp(keep, t->spheres, sizeof(float) * 4 * n) == 0 &&
                       (!t->cones || memcmp(keep + 4 * n, t->cones, sizeof(float) * 4 * n) == 0) &&
                       (!t->colors || memcmp(keep + 8 * n, t->colors, sizeof(float) * 3 * n) == 0) &&
                       (!t->areas || memcmp(keep + 11 * n, t->areas, sizeof(float) * n) == 0),
                   "a refit that kept the leaves of unchanged triangles differs from one that computed them all");
    }
    mesh.positions = moved;
    mesh.normals = s->has_normals ? s->normals : NULL;
    FZ_REQUIRE(mlod_refit_mesh(t, &mesh, parallel, &e) == MLOD_OK, "the refit to the same mesh again failed: %s",
               e.message);
    free(again);
    free(keep);
}

/* ------------------------------------------------------- cube maps */

/* The Vulkan specification's cube map face selection ("Cube Map Face
   Selection"): the layer of a direction (rx, ry, rz) is that of its
   major axis, and within it sc and tc are these components, each times a
   sign; the face coordinates are s = (sc / |rc| + 1) / 2 and
   t = (tc / |rc| + 1) / 2, t growing downwards.  The view's cube is that
   table over X = u, Y = v, Z = -w of its frame (manylods.h, CUBE MAPS),
   face i the s x s square at (s (i mod 3), s (i div 3)) of its tile.
   Written from the specification, not from the library's table. */
typedef struct fz_cube_face {
    int axis, sign;       /* major axis (0 x, 1 y, 2 z) and its sign */
    int sc_axis, sc_sign; /* sc = sc_sign * r[sc_axis] */
    int tc_axis, tc_sign; /* tc = tc_sign * r[tc_axis] */
} fz_cube_face;

static const fz_cube_face fz_cube[6] = {
    {0, +1, 2, -1, 1, -1}, /* +X: sc = -rz, tc = -ry */
    {0, -1, 2, +1, 1, -1}, /* -X: sc = +rz, tc = -ry */
    {1, +1, 0, +1, 2, +1}, /* +Y: sc = +rx, tc = +rz */
    {1, -1, 0, +1, 2, -1}, /* -Y: sc = +rx, tc = -rz */
    {2, +1, 0, +1, 1, -1}, /* +Z: sc = +rx, tc = -ry */
    {2, -1, 0, -1, 1, -1}, /* -Z: sc = -rx, tc = -ry */
};

/* v / |v| for any v != 0 of float components (in double their squares
   neither overflow nor underflow; unit3's threshold is for sane views). */
static void normalize3(double *v)
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    int k;
    for (k = 0; k < 3; k++) v[k] /= len;
}

/* The view's frame as the documentation defines it, in double: w along
   forward, u = forward x up, v = u x w, all unit; then the cube's world
   axes X = u, Y = v, Z = -w.  (Valid views only: forward and up not
   zero, nor parallel.) */
static void cube_axes(const mlod_view *view, double axes[3][3])
{
    double w[3], up[3], u[3], v[3];
    int k;
    for (k = 0; k < 3; k++) {
        w[k] = view->forward[k];
        up[k] = view->up[k];
    }
    normalize3(w);
    normalize3(up);
    u[0] = w[1] * up[2] - w[2] * up[1];
    u[1] = w[2] * up[0] - w[0] * up[2];
    u[2] = w[0] * up[1] - w[1] * up[0];
    normalize3(u);
    v[0] = u[1] * w[2] - u[2] * w[1];
    v[1] = u[2] * w[0] - u[0] * w[2];
    v[2] = u[0] * w[1] - u[1] * w[0];
    for (k = 0; k < 3; k++) {
        axes[0][k] = u[k];
        axes[1][k] = v[k];
        axes[2][k] = -w[k];
    }
}

/* A valid cube map: mlod_view_project of a point whose major axis is clear
   lands where the specification puts it, with depth |rc| (z along the
   face's axis), and answers 1 exactly when near <= |rc| <= far (away from
   those planes); mlod_view_pixel_ray from the eye at a position inside a
   face (away from its edges) goes along the specification's direction of
   that face position. */
static void check_cube(uint32_t index, const mlod_view *view, const float *point, float x, float y)
{
    double axes[3][3], d[3], rr[3], side = view->height / 2, scale, size = 0.0;
    float pixel[2], depth, origin[3], dir[3];
    int k, a, i, inside;
    cube_axes(view, axes);
    for (k = 0; k < 3; k++) {
        d[k] = (double)point[k] - view->position[k];
        size += fabs((double)point[k]) + fabs((double)view->position[k]);
    }
    for (a = 0; a < 3; a++) rr[a] = axes[a][0] * d[0] + axes[a][1] * d[1] + axes[a][2] * d[2];
    a = fabs(rr[0]) >= fabs(rr[1]) && fabs(rr[0]) >= fabs(rr[2]) ? 0 : fabs(rr[1]) >= fabs(rr[2]) ? 1 : 2;
    inside = mlod_view_project(view, point, pixel, &depth);
    if (fabs(rr[a]) > (1.0 + 1e-6) * fabs(rr[(a + 1) % 3]) && fabs(rr[a]) > (1.0 + 1e-6) * fabs(rr[(a + 2) % 3])) {
        double ma = fabs(rr[a]), sc, tc, want[2], tol = 1e-5 * view->width + 1e-4, near = view->near_plane;
        for (i = 0; i < 6; i++)
            if (fz_cube[i].axis == a && fz_cube[i].sign == (rr[a] > 0.0 ? 1 : -1)) break;
        sc = fz_cube[i].sc_sign * rr[fz_cube[i].sc_axis];
        tc = fz_cube[i].tc_sign * rr[fz_cube[i].tc_axis];
        want[0] = side * (i % 3) + side * 0.5 * (sc / ma + 1.0);
        want[1] = side * (i / 3) + side * 0.5 * (tc / ma + 1.0);
        FZ_REQUIRE(fabs(pixel[0] - want[0]) <= tol && fabs(pixel[1] - want[1]) <= tol && fabs(depth - ma) <= 1e-6 * ma,
                   "cube view %u (face side %g): mlod_view_project(%.9g %.9g %.9g) gave pixel (%.9g, %.9g) depth %.9g; "
                   "the Vulkan table: face %d, pixel (%.9g, %.9g), depth %.9g",
                   index, side, point[0], point[1], point[2], pixel[0], pixel[1], depth, i, want[0], want[1], ma);
        scale = 1e-6 * (size + near);
        if (fabs(ma - near) > scale && (!isfinite(view->far_plane) || fabs(ma - view->far_plane) > scale + 1e-6 * ma)) {
            int want_inside = ma > near && ma < view->far_plane;
            FZ_REQUIRE(inside == want_inside,
                       "cube view %u: mlod_view_project gave %d for depth %.9g, near %.9g, far %.9g", index, inside, ma,
                       near, (double)view->far_plane);
        }
    }
    if (x < (float)view->width && y < (float)view->height) {
        double fx = floor(x / side), fy = floor(y / side), sc, tc, r3[3], want[3], len = 0.0, edge = 1e-4 * side;
        int face = (int)fx + 3 * (int)fy;
        FZ_REQUIRE(mlod_view_pixel_ray(view, x, y, origin, dir) == 1,
                   "cube view %u: no ray at (%.9g, %.9g) in the tile", index, x, y);
        FZ_REQUIRE(origin[0] == view->position[0] && origin[1] == view->position[1] && origin[2] == view->position[2],
                   "cube view %u: the ray at (%.9g, %.9g) starts at (%.9g %.9g %.9g), not at the eye", index, x, y,
                   origin[0], origin[1], origin[2]);
        if (x - fx * side > edge && (fx + 1) * side - x > edge && y - fy * side > edge && (fy + 1) * side - y > edge) {
            sc = 2.0 * (x - fx * side) / side - 1.0;
            tc = 2.0 * (y - fy * side) / side - 1.0;
            r3[fz_cube[face].axis] = fz_cube[face].sign;
            r3[fz_cube[face].sc_axis] = fz_cube[face].sc_sign * sc;
            r3[fz_cube[face].tc_axis] = fz_cube[face].tc_sign * tc;
            for (k = 0; k < 3; k++) {
                want[k] = r3[0] * axes[0][k] + r3[1] * axes[1][k] + r3[2] * axes[2][k];
                len += want[k] * want[k];
            }
            len = sqrt(len);
            for (k = 0; k < 3; k++)
                FZ_REQUIRE(fabs(dir[k] - want[k] / len) <= 1e-5,
                           "cube view %u: the ray at (%.9g, %.9g) (face %d) goes along (%.9g %.9g %.9g), the Vulkan "
                           "table says (%.9g %.9g %.9g)",
                           index, x, y, face, dir[0], dir[1], dir[2], want[0] / len, want[1] / len, want[2] / len);
        }
    }
}

/* Projection, pixel rays and the suggested N on valid views: no NaN where
   they answer, N within range; a cube map's against the Vulkan table. */
static void check_projection(fz_reader *r, const mlod_tree *t, const fz_scene *s, const fz_views *vs, float eps)
{
    uint32_t v, n;
    for (v = 0; v < vs->count; v++) {
        const mlod_view *view = &vs->views[v];
        const float *p = t->spheres + 4 * (size_t)rng_below_reader(r, t->node_count);
        float pixel[2], depth, origin[3], dir[3], x = (float)(view->width * rd_unit(r)), y = (float)(view->height * rd_unit(r));
        if (mlod_view_project(view, p, pixel, &depth))
            FZ_REQUIRE(!isnan(pixel[0]) && !isnan(pixel[1]) && !isnan(depth), "view %u: mlod_view_project gave NaN", v);
        if (mlod_view_pixel_ray(view, x, y, origin, dir)) {
            double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
            FZ_REQUIRE(!isnan(origin[0]) && !isnan(origin[1]) && !isnan(origin[2]) && fabs(len - 1.0) < 1e-5,
                       "view %u: mlod_view_pixel_ray(%g, %g): origin (%g %g %g), |direction| %g", v, x, y, origin[0],
                       origin[1], origin[2], len);
        }
        if (view->kind == MLOD_VIEW_CUBE) check_cube(v, view, p, x, y);
    }
    n = mlod_suggest_sample_count(ldexp(s->radius * s->radius, (int)(rd_u8(r) % 9) - 4), vs->views, vs->count, eps,
                                  t->radius_scale, s->radius * ldexp(1.0, -(int)(rd_u8(r) % 20)));
    FZ_REQUIRE(n <= MANYLODS_MAX_LEAVES, "mlod_suggest_sample_count gave %u", n);
    if (!s->points) {
        mlod_mesh mesh = fz_mesh_of(s, s->positions);
        double area = mlod_mesh_area(&mesh);
        FZ_REQUIRE(area >= 0.0 && !isnan(area), "mlod_mesh_area gave %g", area);
    }
}

/* ------------------------------------------------------ the helpers */

/* mlod_tree_depth_nodes(leaves, d): the ranges of depths 0, 1, ... tile
   the internal nodes 0 .. leaves - 2 in order; depth d's range holds 2^d
   nodes (the last range fewer), the parents (heap layout: (n - 1) / 2) of
   its ends lie in depth d - 1's range; past them, and at any depth from 32
   on (node 2^32 - 1 is beyond every tree), there is none. */
static void check_depth_nodes(uint32_t leaves, uint32_t hostile_depth)
{
    static const uint32_t far[5] = {32u, 33u, 63u, 64u, 0xffffffffu};
    uint32_t d, prev_first = 0, prev_last = 0, f, l;
    uint64_t next = 0;
    int k;
    for (d = 0; d < 36; d++) {
        int has;
        f = l = 0xdeadbeefu;
        has = mlod_tree_depth_nodes(leaves, d, &f, &l);
        if (leaves < 2 || next > (uint64_t)leaves - 2) {
            FZ_REQUIRE(!has, "mlod_tree_depth_nodes(%u, %u) gave %u .. %u past the last internal node", leaves, d, f, l);
            continue;
        }
        FZ_REQUIRE(has, "mlod_tree_depth_nodes(%u, %u) gave none, node %llu is internal", leaves, d,
                   (unsigned long long)next);
        FZ_REQUIRE(f == next && l >= f && l <= leaves - 2, "mlod_tree_depth_nodes(%u, %u) gave %u .. %u, expected from %llu",
                   leaves, d, f, l, (unsigned long long)next);
        FZ_REQUIRE((uint64_t)l - f + 1 == ((uint64_t)1 << d) || l == leaves - 2,
                   "mlod_tree_depth_nodes(%u, %u): %u .. %u is not 2^%u nodes nor the last depth", leaves, d, f, l, d);
        if (d > 0)
            FZ_REQUIRE((f - 1) / 2 == prev_first && (l - 1) / 2 >= prev_first && (l - 1) / 2 <= prev_last,
                       "mlod_tree_depth_nodes(%u, %u): parents of %u .. %u not in depth %u's %u .. %u", leaves, d, f, l,
                       d - 1, prev_first, prev_last);
        prev_first = f;
        prev_last = l;
        next = (uint64_t)l + 1;
    }
    FZ_REQUIRE(leaves < 2 || next == (uint64_t)leaves - 1, "mlod_tree_depth_nodes(%u, ...) covers %llu of %u internal nodes",
               leaves, (unsigned long long)next, leaves - 1);
    for (k = 0; k < 6; k++) {
        uint32_t depth = k < 5 ? far[k] : hostile_depth;
        if (depth < 32) continue;
        FZ_REQUIRE(!mlod_tree_depth_nodes(leaves, depth, &f, &l), "mlod_tree_depth_nodes(%u, %u) gave %u .. %u", leaves,
                   depth, f, l);
    }
}

static uint32_t rd_leaf_count(fz_reader *r)
{
    uint8_t b = rd_u8(r);
    switch (b % 8) {
    case 0: return b / 8; /* 0 .. 31 */
    case 1: return (uint32_t)1 << (b / 8);
    case 2: return ((uint32_t)1 << (b / 8)) + 1;
    case 3: return ((uint32_t)1 << (b / 8)) - 1;
    case 4: return 0xffffffffu - b / 8;
    case 5: return MANYLODS_MAX_LEAVES + b / 8 - 16;
    default: return rd_u32(r);
    }
}

/* mlod_cut_params_check on fuzzed parameters: it follows the documented
   rules, and mlod_cut_update (valid views) fails exactly when it does,
   with the same code; a cut it accepts is checked like the others. */
static void check_params(fz_ctx *c, fz_reader *r, mlod_cut *cut, const mlod_tree *t, const fz_views *vs,
                         const fz_layout *L)
{
    mlod_cut_params q;
    mlod_error e;
    mlod_result res, upd;
    uint8_t b = rd_u8(r);
    int bad_mode, bad_eps, bad_lazy;
    memset(&q, 0, sizeof q);
    q.mode = (mlod_cut_mode)((b & 0xc0) == 0xc0 ? rd_u8(r) : b % 3u);
    q.epsilon = (b & 0x30) == 0x30 ? rd_raw_float(r) : (float)ldexp(1.0, (int)(rd_u8(r) % 24) - 8);
    q.lazy_steps = (b & 0x0c) == 0x0c ? 0u : (b & 0x0c) == 0x08 ? rd_u32(r) : 1u + (b & 3u);
    q.parallel = c->parallel;
    q.budget = (b & 0x03) == 0x03 ? (uint64_t)rd_u32(r) << (rd_u8(r) % 33) : 0u; /* (refused outside lazy mode) */
    bad_mode = (unsigned)q.mode > (unsigned)MLOD_CUT_LAZY;
    bad_eps = !(q.epsilon > 0.0f);
    bad_lazy = (q.mode == MLOD_CUT_LAZY && q.lazy_steps == 0) || (!bad_mode && q.mode != MLOD_CUT_LAZY && q.budget);
    memset(&e, 0, sizeof e);
    res = mlod_cut_params_check(&q, &e);
    fz_where = "mlod_cut_params_check";
    if (bad_mode || bad_eps || bad_lazy) {
        check_error(res, &e);
        FZ_REQUIRE(bad_mode || bad_lazy || res == MLOD_ERROR_BAD_EPSILON, "epsilon %g refused with %s", (double)q.epsilon,
                   mlod_result_name(res));
        FZ_REQUIRE(bad_eps || res == MLOD_ERROR_INVALID_ARGUMENT, "mode %u, lazy_steps %u refused with %s",
                   (unsigned)q.mode, q.lazy_steps, mlod_result_name(res));
        FZ_REQUIRE(res == MLOD_ERROR_BAD_EPSILON || res == MLOD_ERROR_INVALID_ARGUMENT, "params refused with %s",
                   mlod_result_name(res));
    } else {
        FZ_REQUIRE(res == MLOD_OK && e.code == MLOD_OK, "mlod_cut_params_check refused mode %u, epsilon %g, lazy_steps %u: %s",
                   (unsigned)q.mode, (double)q.epsilon, q.lazy_steps, e.message);
    }
    res = mlod_cut_params_check(NULL, &e);
    check_error(res, &e);
    FZ_REQUIRE(res == MLOD_ERROR_INVALID_ARGUMENT, "mlod_cut_params_check(NULL) gave %s", mlod_result_name(res));
    res = mlod_cut_params_check(&q, NULL); /* error may be NULL */
    FZ_NOTE("fuzz: fuzzed params: mode %u, epsilon %g, lazy_steps %u: %s\n", (unsigned)q.mode, (double)q.epsilon,
            q.lazy_steps, mlod_result_name(res));
    if (vs->must_fail) return;
    upd = cut_update(c, cut, t, vs, &q, res != MLOD_OK, 0, "update with fuzzed params");
    FZ_REQUIRE(upd == res, "mlod_cut_update gave %s where mlod_cut_params_check gave %s", mlod_result_name(upd),
               mlod_result_name(res));
    if (upd == MLOD_OK) check_cut(cut, t, L, vs, q.epsilon, q.mode != MLOD_CUT_LAZY, 1, &c->rng, "cut with fuzzed params");
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* mlod_view_frame_of agrees with mlod_view_check on every view, valid or
   not; a frame it gives is the view's (eye, kind, tile, flags), with 1 to
   6 sub-projections, each with a positive scale, a sub-tile inside the
   tile and an orthonormal frame, the first one along the view's forward
   and up (a cube map's +X face: its right and up); a node that a plane
   of every sub-projection puts clearly outside has criterion 0. */
static void check_frames(fz_reader *r, const mlod_tree *t, const fz_views *vs)
{
    uint32_t v, i;
    mlod_view_frame f;
    mlod_error e1, e2;
    mlod_result r1;
    r1 = mlod_view_frame_of(vs->views, NULL, &e1);
    fz_where = "mlod_view_frame_of(view, NULL)";
    check_error(r1, &e1);
    for (v = 0; v < vs->count; v++) {
        const mlod_view *view = &vs->views[v];
        double fw[3], vu[3], x[3], len;
        int k, j, s;
        memset(&f, 0, sizeof f);
        r1 = mlod_view_frame_of(view, &f, &e1);
        FZ_REQUIRE(r1 == mlod_view_check(view, &e2), "view %u: mlod_view_frame_of gave %s, mlod_view_check %s", v,
                   mlod_result_name(r1), mlod_result_name(e2.code));
        if (r1 != MLOD_OK) {
            fz_where = "mlod_view_frame_of";
            check_error(r1, &e1);
            FZ_REQUIRE(e1.code == e2.code, "view %u: codes differ", v);
            continue;
        }
        FZ_REQUIRE(!view_invalid(view), "view %u: mlod_view_frame_of accepted an invalid view", v);
        for (k = 0; k < 3; k++) {
            FZ_REQUIRE(f.eye[k] == (double)view->position[k], "view %u: frame eye differs from the position", v);
            fw[k] = view->forward[k];
            vu[k] = view->up[k];
        }
        FZ_REQUIRE(f.kind == (uint32_t)view->kind && f.cull_backfaces == (view->flags & 1u) &&
                       f.width == (double)view->width && f.height == (double)view->height && f.sub_count >= 1 &&
                       f.sub_count <= MLOD_VIEW_MAX_SUBS,
                   "view %u: frame kind %g, culling %g, tile %g x %g, %g sub-projections", v, f.kind, f.cull_backfaces,
                   f.width, f.height, f.sub_count);
        len = sqrt(dot3(fw, fw));
        for (s = 0; s < (int)f.sub_count; s++) {
            const mlod_view_sub *sub = &f.subs[s];
            FZ_REQUIRE(isfinite(sub->scale) && sub->scale > 0.0 && sub->plane_count <= 6,
                       "view %u sub %d: scale %g, %g planes", v, s, sub->scale, sub->plane_count);
            FZ_REQUIRE(sub->x >= 0.0 && sub->y >= 0.0 && sub->width > 0.0 && sub->height > 0.0 &&
                           sub->x + sub->width <= f.width && sub->y + sub->height <= f.height,
                       "view %u sub %d: sub-tile %g,%g %gx%g outside the tile", v, s, sub->x, sub->y, sub->width,
                       sub->height);
            FZ_REQUIRE(fabs(dot3(sub->forward, sub->forward) - 1.0) < 1e-9 &&
                           fabs(dot3(sub->right, sub->right) - 1.0) < 1e-9 && fabs(dot3(sub->up, sub->up) - 1.0) < 1e-9,
                       "view %u sub %d: frame axes not unit", v, s);
            FZ_REQUIRE(fabs(dot3(sub->forward, sub->up)) < 1e-9 && fabs(dot3(sub->forward, sub->right)) < 1e-9 &&
                           fabs(dot3(sub->up, sub->right)) < 1e-9,
                       "view %u sub %d: frame axes not orthogonal", v, s);
            for (j = 0; j < (int)sub->plane_count; j++)
                for (k = 0; k < 5; k++) FZ_REQUIRE(!isnan(sub->planes[j][k]), "view %u sub %d: plane %d is NaN", v, s, j);
        }
        /* the first sub-projection looks along the view (a cube map's +X
           face along its right) with right = forward x up */
        {
            const mlod_view_sub *sub = &f.subs[0];
            const double *axis = view->kind == MLOD_VIEW_CUBE ? sub->right : sub->forward;
            FZ_REQUIRE(dot3(axis, fw) >= len * (1.0 - 1e-9), "view %u: frame forward not along the view's", v);
            FZ_REQUIRE(dot3(sub->up, vu) > 0.0, "view %u: frame up against the view's", v);
            x[0] = fw[1] * vu[2] - fw[2] * vu[1];
            x[1] = fw[2] * vu[0] - fw[0] * vu[2];
            x[2] = fw[0] * vu[1] - fw[1] * vu[0];
            if (view->kind != MLOD_VIEW_CUBE)
                FZ_REQUIRE(dot3(x, sub->right) > 0.0, "view %u: frame right is not along forward x up", v);
        }
        /* a cube map: six sub-projections, face i in the s x s square at
           (s (i mod 3), s (i div 3)), looking along the Vulkan table's major
           axis, its pixel x along sc, its pixel y (upwards) against tc */
        if (view->kind == MLOD_VIEW_CUBE) {
            double axes[3][3], side = view->height / 2;
            cube_axes(view, axes);
            FZ_REQUIRE(f.sub_count == 6, "cube view %u: %g sub-projections", v, f.sub_count);
            for (s = 0; s < 6; s++) {
                const mlod_view_sub *sub = &f.subs[s];
                const fz_cube_face *c = &fz_cube[s];
                FZ_REQUIRE(sub->kind == MLOD_VIEW_PERSPECTIVE && sub->x == side * (s % 3) && sub->y == side * (s / 3) &&
                               sub->width == side && sub->height == side && sub->scale == 0.5 * side,
                           "cube view %u face %d: kind %g, sub-tile %g,%g %gx%g, scale %g; expected a perspective "
                           "%gx%g at %g,%g with focal length %g",
                           v, s, sub->kind, sub->x, sub->y, sub->width, sub->height, sub->scale, side, side,
                           side * (s % 3), side * (s / 3), 0.5 * side);
                for (k = 0; k < 3; k++)
                    FZ_REQUIRE(fabs(sub->forward[k] - c->sign * axes[c->axis][k]) < 1e-9 &&
                                   fabs(sub->right[k] - c->sc_sign * axes[c->sc_axis][k]) < 1e-9 &&
                                   fabs(sub->up[k] + c->tc_sign * axes[c->tc_axis][k]) < 1e-9,
                               "cube view %u (forward %.9g %.9g %.9g, up %.9g %.9g %.9g) face %d: right, up, "
                               "forward (%g %g %g) (%g %g %g) (%g %g %g), not the Vulkan table's (%g %g %g) "
                               "(%g %g %g) (%g %g %g)",
                               v, view->forward[0], view->forward[1], view->forward[2], view->up[0], view->up[1],
                               view->up[2], s, sub->right[0], sub->right[1], sub->right[2], sub->up[0], sub->up[1],
                               sub->up[2], sub->forward[0], sub->forward[1], sub->forward[2],
                               c->sc_sign * axes[c->sc_axis][0], c->sc_sign * axes[c->sc_axis][1],
                               c->sc_sign * axes[c->sc_axis][2], -c->tc_sign * axes[c->tc_axis][0],
                               -c->tc_sign * axes[c->tc_axis][1], -c->tc_sign * axes[c->tc_axis][2],
                               c->sign * axes[c->axis][0], c->sign * axes[c->axis][1], c->sign * axes[c->axis][2]);
            }
        }
        /* a node that some sub-projection's plane puts clearly outside, in
           every sub-projection, has criterion 0 */
        for (i = 0; i < 4 && t->node_count; i++) {
            uint32_t n = rng_below_reader(r, t->node_count), outside = 0;
            const float *sp = t->spheres + 4 * (size_t)n;
            for (s = 0; s < (int)f.sub_count; s++)
                for (j = 0; j < (int)f.subs[s].plane_count; j++) {
                    const double *pl = f.subs[s].planes[j];
                    double nc = pl[0] * sp[0] + pl[1] * sp[1] + pl[2] * sp[2], lr = pl[4] * sp[3];
                    double slack = 1e-6 * (fabs(pl[0] * sp[0]) + fabs(pl[1] * sp[1]) + fabs(pl[2] * sp[2]) + fabs(lr) +
                                           fabs(pl[3]));
                    if (isfinite(pl[3]) && nc + lr < pl[3] - slack) {
                        outside++;
                        break;
                    }
                }
            if (outside == (uint32_t)f.sub_count) {
                double crit = mlod_criterion(t, n, view);
                FZ_REQUIRE(crit == 0.0, "view %u: node %u is outside every sub-projection but c = %g", v, n, crit);
            }
        }
    }
}

/* mlod_refit_check_growth on fuzzed arguments: OK or RANGE; what it
   accepts keeps radius_scale sqrt(area_unit growth) and growth x
   leaf_count within float range; it accepts when both are far inside
   (<= 1e30); it is monotone in growth; it refuses a NaN growth. */
static void check_growth(fz_reader *r, const mlod_tree *t)
{
    uint8_t b = rd_u8(r);
    float rs = (b & 1) ? rd_raw_float(r) : t->radius_scale;
    double au = (b & 2) ? (double)rd_raw_float(r) * ldexp(1.0, (int)(rd_u8(r) % 200) - 100) : t->area_unit;
    uint32_t leaves = (b & 4) ? rd_leaf_count(r) : t->leaf_count;
    double g = (b & 8) ? (double)rd_raw_float(r) : ldexp(rd_unit(r), (int)(rd_u8(r) % 240) - 120);
    double radius = rs * sqrt(au * g), sum = g * leaves;
    mlod_error e;
    mlod_result res = mlod_refit_check_growth(rs, au, leaves, g, &e);
    fz_where = "mlod_refit_check_growth";
    if (res != MLOD_OK) {
        check_error(res, &e);
        FZ_REQUIRE(res == MLOD_ERROR_RANGE, "mlod_refit_check_growth gave %s", mlod_result_name(res));
        FZ_REQUIRE(!(radius >= 0.0 && radius <= 1e30 && sum >= 0.0 && sum <= 1e30),
                   "mlod_refit_check_growth(%g, %g, %u, %g) refused radius %g, sum %g", (double)rs, au, leaves, g, radius,
                   sum);
    } else {
        FZ_REQUIRE(radius <= FLT_MAX && sum <= FLT_MAX, "mlod_refit_check_growth(%g, %g, %u, %g) accepted radius %g, sum %g",
                   (double)rs, au, leaves, g, radius, sum);
        if (g > 0.0)
            FZ_REQUIRE(mlod_refit_check_growth(rs, au, leaves, 0.5 * g, NULL) == MLOD_OK,
                       "mlod_refit_check_growth accepts growth %g but not %g", g, 0.5 * g);
    }
    FZ_REQUIRE(mlod_refit_check_growth(rs, au, leaves, NAN, NULL) == MLOD_ERROR_RANGE,
               "mlod_refit_check_growth accepted a NaN growth");
}

/* mlod_sample on hostile importances (D <= 64), sample counts, methods
   and chain lengths: it fails exactly for what its documentation refuses
   (a NaN or infinite importance, a negative one, an unknown method,
   weights beyond float range), with the outputs untouched; otherwise every
   sample is in the domain with a finite weight >= 0, a sample of
   importance 0 only with weight 0 (and from the inverse transform only
   where every importance is 0), and the same result with the reversed
   hook.  The inverse transform's table comes from the counting allocator,
   its failures injected as elsewhere. */
static void check_sample(fz_reader *r, fz_counter *counter, const mlod_allocator *alloc)
{
    enum { MAX_D = 64, MAX_N = 300 };
    static uint32_t samples[MAX_N], again[MAX_N];
    static float weights[MAX_N], again_weights[MAX_N];
    float importance[MAX_D];
    uint32_t d = 1 + rd_u8(r) % MAX_D, n = 1 + rd_u16(r) % MAX_N, j;
    uint8_t form = rd_u8(r);
    double total = 0.0, largest = 0.0, smallest = INFINITY;
    int finite = 1, negative = 0, known;
    mlod_sample_params p;
    mlod_parallel reverse = {fz_run_reverse, NULL};
    mlod_error e;
    mlod_result res;
    unsigned long live = counter->live;
    memset(&p, 0, sizeof p);
    p.method = (mlod_sampler)(form & 1);
    if (form & 2) p.method = (mlod_sampler)(rd_u8(r) % 4); /* 2 and 3: unknown */
    p.chain_length = (form & 4) ? rd_u8(r) : 0;
    p.seed = rd_u32(r);
    p.allocator = alloc;
    known = p.method == MLOD_SAMPLER_INVERSE_TRANSFORM || p.method == MLOD_SAMPLER_METROPOLIS;
    for (j = 0; j < d; j++) {
        double f;
        importance[j] = (form & 8) ? rd_raw_float(r) : (rd_u8(r) < 64 ? 0.0f : (float)rd_unit(r));
        f = importance[j];
        if (!isfinite(f)) finite = 0;
        else if (f < 0.0) negative = 1;
        else {
            total += f;
            if (f > largest) largest = f;
            if (f > 0.0 && f < smallest) smallest = f;
        }
    }
    memset(samples, 0xab, sizeof samples);
    memset(weights, 0xab, sizeof weights);
    fz_where = "mlod_sample";
    res = mlod_sample(importance, d, n, &p, samples, weights, &e);
    if (res != MLOD_OK) {
        uint32_t untouched = 1;
        check_error(res, &e);
        for (j = 0; j < n; j++) untouched &= samples[j] == 0xababababu;
        FZ_REQUIRE(untouched, "mlod_sample failed (%s) and wrote samples", mlod_result_name(res));
        FZ_REQUIRE(!known || !finite || negative || injected_oom(counter, res) ||
                       (res == MLOD_ERROR_RANGE && total > 0.0 &&
                        (p.method == MLOD_SAMPLER_INVERSE_TRANSFORM ? total : d * largest) / smallest > 1e37),
                   "mlod_sample refused valid input: %s (%s)", mlod_result_name(res), e.message);
    } else {
        FZ_REQUIRE(known && finite && !negative, "mlod_sample accepted invalid input (method %d)", (int)p.method);
        for (j = 0; j < n; j++) {
            FZ_REQUIRE(samples[j] < d && isfinite(weights[j]) && weights[j] >= 0.0f,
                       "mlod_sample: sample %u is %u of %u, weight %g", j, samples[j], d, (double)weights[j]);
            if (importance[samples[j]] == 0.0f)
                FZ_REQUIRE(weights[j] == 0.0f && (p.method == MLOD_SAMPLER_METROPOLIS || total == 0.0),
                           "mlod_sample: sample %u has importance 0 and weight %g", j, (double)weights[j]);
        }
        p.parallel = &reverse;
        p.allocator = NULL;
        FZ_REQUIRE(mlod_sample(importance, d, n, &p, again, again_weights, &e) == MLOD_OK &&
                       memcmp(samples, again, n * sizeof *again) == 0 &&
                       memcmp(weights, again_weights, n * sizeof *again_weights) == 0,
                   "mlod_sample differs with the reversed hook");
    }
    check_no_leak(counter, live, "mlod_sample");
}

/* The largest growth of a triangle of the mesh between the build's
   positions and new ones (triangles of zero area at build: none); the
   build keeps each triangle's own area, however small against the total
   (fuzz/crashes/pipeline/refit-growth-of-a-triangle-lost-in-the-area-sum). */

static double largest_growth(const fz_scene *s, const float *moved)
{
    double g = 0.0;
    uint32_t i;
    for (i = 0; i + 3 <= s->index_count; i += 3) {
        double n[3], before = shape_triangle_area(s->positions, s->indices, i / 3, n);
        double after = shape_triangle_area(moved, s->indices, i / 3, n);
        if (before > 0.0 && after / before > g) g = after / before;
    }
    return g;
}

/* Cut, refit, cut again in every mode, splat. */
/* mlod_cut_reserve on a new cut: it then holds at most mlod_cut_bound, or
   fails only with an injected failure, holding what it held. */
static void reserve_cut(fz_ctx *c, mlod_cut *cut, uint32_t views, uint32_t mean)
{
    unsigned long live = c->counter.live;
    size_t before = mlod_cut_bytes(cut);
    mlod_error e;
    mlod_result res;
    fz_where = "mlod_cut_reserve";
    res = mlod_cut_reserve(cut, mean, &e);
    FZ_NOTE("mlod_cut_reserve(%u views, %u nodes): %s\n", views, mean, mlod_result_name(res));
    if (res != MLOD_OK) {
        check_error(res, &e);
        FZ_REQUIRE(injected_oom(&c->counter, res), "mlod_cut_reserve(%u views, %u nodes) failed: %s", views, mean,
                   e.message);
        FZ_REQUIRE(mlod_cut_bytes(cut) == before, "a failed reserve changed the cut's bytes: %zu, was %zu",
                   mlod_cut_bytes(cut), before);
        check_no_leak(&c->counter, live, "mlod_cut_reserve");
        return;
    }
    FZ_REQUIRE(mlod_cut_bytes(cut) <= mlod_cut_bound(views, mean),
               "a new cut reserved for %u views of %u nodes holds %zu bytes, the bound is %zu", views, mean,
               mlod_cut_bytes(cut), mlod_cut_bound(views, mean));
}

static void run_views(fz_ctx *c, fz_reader *r, mlod_tree *t, const fz_scene *s, uint32_t leaves)
{
    static fz_layout layout;
    static float moved[3 * (FZ_LARGE_POINTS + 1)];
    fz_views v1, v2;
    mlod_cut *basic = NULL, *incremental = NULL, *lazy = NULL;
    mlod_atlas *follow = NULL; /* follows the incremental cut from frame 1 to frame 2 */
    mlod_cut_params p;
    mlod_error e;
    mlod_result res;
    float eps;
    uint8_t eps_byte;
    int bad_eps, lazy_bad, call, refit_must_fail = 0;
    uint32_t differs = 0;

    int large = (c->ext & FZ_EXT_LARGE) == FZ_EXT_LARGE;
    parse_views(r, &v1, s, c->sane_views, large, leaves);
    bound_tiles(&v1, leaves, large ? FZ_LARGE_ATLAS_PIXELS : FZ_ATLAS_PIXELS);
    move_views(r, &v1, &v2, s->radius);
    eps_byte = rd_u8(r);
    if (eps_byte >= 200 && !c->sane_views)
        eps = rd_raw_float(r);
    else if (eps_byte % 8 < 2)
        eps = eps_byte % 8 ? 1e-6f : INFINITY;
    else
        eps = (float)ldexp(1.0 + (eps_byte & 15) / 16.0, (int)(eps_byte % 24) - 8); /* 1/256 .. 2^16 */
    bad_eps = !(eps > 0.0f);
    memset(&p, 0, sizeof p);
    p.epsilon = eps;
    p.parallel = c->parallel;
    p.lazy_steps = 1 + rd_u8(r) % 4;
    lazy_bad = !c->sane_views && r->chaos && rd_u8(r) < 8;
    layout_init(&layout, leaves);

    for (call = 0; call < 3; call++) {
        mlod_cut **cut = call == 0 ? &basic : call == 1 ? &incremental : &lazy;
        int tries = 0;
        unsigned long live;
    create:
        live = c->counter.live;
        *cut = (mlod_cut *)&p;
        res = mlod_cut_create(v1.count, &c->alloc, cut, &e);
        if (res != MLOD_OK) {
            fz_where = "mlod_cut_create";
            check_error(res, &e);
            FZ_REQUIRE(*cut == NULL && injected_oom(&c->counter, res), "mlod_cut_create(%u) failed: %s", v1.count,
                       e.message);
            check_no_leak(&c->counter, live, "mlod_cut_create");
            if (tries++ < FZ_RETRIES && (c->ext & FZ_EXT_FAILURES)) goto create;
            goto done;
        }
        FZ_REQUIRE(mlod_cut_get(*cut, 0).count == 0, "a new cut is not empty");
        if (call == 1 && (c->ext & FZ_EXT_RESERVE)) reserve_cut(c, *cut, v1.count, rd_u16(r) & 0x3fffu);
    }

    /* frame 1: basic from the root; incremental and lazy from nothing */
    p.mode = MLOD_CUT_BASIC;
    if (cut_update(c, basic, t, &v1, &p, v1.must_fail || bad_eps, !c->sane_views, "basic update, frame 1") != MLOD_OK)
        goto done;
    check_cut(basic, t, &layout, &v1, eps, 1, 1, &c->rng, "basic cut, frame 1");
    check_projection(r, t, s, &v1, eps);
    p.mode = MLOD_CUT_INCREMENTAL;
    cut_update(c, incremental, t, &v1, &p, 0, 0, "incremental update, frame 1");
    FZ_REQUIRE(same_cut(basic, incremental, v1.count, &differs), "frame 1: incremental cut differs from basic in view %u",
               differs);
    follow = follow_begin(c, t, incremental, &v1, p.lazy_steps & 1u);
    p.mode = MLOD_CUT_LAZY;
    cut_update(c, lazy, t, &v1, &p, 0, 0, "lazy update, frame 1");
    check_cut(lazy, t, &layout, &v1, eps, 0, 1, &c->rng, "lazy cut, frame 1");
    if (lazy_bad) {
        p.lazy_steps = 0;
        cut_update(c, lazy, t, &v1, &p, 1, 0, "lazy update with lazy_steps 0");
        p.lazy_steps = 1;
    }

    /* refit: the scene deforms */
    {
        mlod_mesh mesh;
        mlod_points points;
        size_t floats = 4 * (size_t)t->node_count;
        float *before = (float *)malloc(floats * sizeof(float));
        uint8_t other = rd_u8(r);
        int sane_refit;
        FZ_REQUIRE(before != NULL, "out of memory");
        memcpy(before, t->spheres, floats * sizeof(float));
        perturb(r, s, moved, c->sane_geometry);
        memcpy(moved + 3 * s->vertex_count, s->positions, 3 * sizeof(float)); /* a vertex past the end, below */
        sane_refit = !vectors_invalid(moved, s->vertex_count, 1e36);
        if (!sane_refit || !(t->attributes & MLOD_ATTR_REFIT)) refit_must_fail = 1;
        memset(&e, 0, sizeof e);
        if (s->points) {
            points = scene_points(s, moved);
            if (r->chaos && other < 4 && points.count > 1) { /* another point cloud */
                points.count -= 1;
                refit_must_fail = 1;
            }
            if (c->strides.on) { /* strides of their own: the tree does not keep the build's */
                fz_strides st = c->strides;
                st.position = pick_stride(r, c->sane_geometry, 3, &st.bad_position);
                stride_points(&points, &st);
                if (stride_points_bad(&points, &st)) refit_must_fail = 1;
            }
            res = mlod_refit_points(t, &points, c->parallel, &e);
        } else {
            mesh = fz_mesh_of(s, moved);
            if (r->chaos && other < 4) { /* another mesh */
                if (other & 1)
                    mesh.vertex_count += 1;
                else
                    mesh.index_count = mesh.index_count > 3 ? mesh.index_count - 3 : mesh.index_count;
                refit_must_fail |= mesh.index_count != s->index_count || mesh.vertex_count != s->vertex_count;
            }
            if (c->strides.on) {
                fz_strides st = c->strides;
                st.position = pick_stride(r, c->sane_geometry, 3, &st.bad_position);
                stride_mesh(&mesh, &st);
                if (stride_mesh_bad(&mesh, &st)) refit_must_fail = 1;
            }
            res = mlod_refit_mesh(t, &mesh, c->parallel, &e);
            if (!refit_must_fail) {
                /* refit refuses a growth exactly when mlod_refit_check_growth
                   does (where halving or doubling it does not change the
                   answer) */
                double g = largest_growth(s, moved);
                mlod_result lo = mlod_refit_check_growth(t->radius_scale, t->area_unit, t->leaf_count, 0.5 * g, NULL);
                mlod_result hi = mlod_refit_check_growth(t->radius_scale, t->area_unit, t->leaf_count, 2.0 * g, NULL);
                FZ_NOTE("fuzz: refit %s, largest growth %g\n", mlod_result_name(res), g);
                if (lo == hi)
                    FZ_REQUIRE((res == MLOD_ERROR_RANGE) == (lo == MLOD_ERROR_RANGE),
                               "refit gave %s for largest growth %g, mlod_refit_check_growth %s", mlod_result_name(res), g,
                               mlod_result_name(lo));
            }
        }
        if (res != MLOD_OK) {
            fz_where = "refit";
            check_error(res, &e);
            /* MLOD_ERROR_RANGE: the deformation grew radii or areas past
               float range, which the library refuses before touching the tree */
            FZ_REQUIRE(refit_must_fail || res == MLOD_ERROR_RANGE, "refit of a valid deformation failed with %s: %s",
                       mlod_result_name(res), e.message);
            FZ_REQUIRE(memcmp(before, t->spheres, floats * sizeof(float)) == 0, "refit failed with %s but changed the tree",
                       mlod_result_name(res));
        } else {
            FZ_REQUIRE(!refit_must_fail, "refit accepted invalid input (positions, another mesh, or no MLOD_ATTR_REFIT)");
            check_tree(t, leaves, t->attributes, "after refit");
            if (!s->points && !c->strides.on && (t->attributes & MLOD_ATTR_REFIT_CACHE))
                refit_cache_check(r, s, t, moved, c->parallel);
        }
        free(before);
    }

    /* frame 2: moved views on the refitted tree (sometimes the incremental
       cut forgets frame 1 and starts from the root) */
    if (rd_u8(r) < 32) mlod_cut_reset(incremental);
    p.mode = MLOD_CUT_BASIC;
    if (cut_update(c, basic, t, &v2, &p, v2.must_fail || bad_eps, !c->sane_views, "basic update, frame 2") != MLOD_OK)
        goto done;
    check_cut(basic, t, &layout, &v2, eps, 1, 1, &c->rng, "basic cut, frame 2");
    p.mode = MLOD_CUT_INCREMENTAL;
    cut_update(c, incremental, t, &v2, &p, 0, 0, "incremental update, frame 2");
    check_cut(incremental, t, &layout, &v2, eps, 1, 1, &c->rng, "incremental cut, frame 2");
    FZ_REQUIRE(same_cut(basic, incremental, v2.count, &differs),
               "frame 2: incremental cut (from frame 1's) differs from basic in view %u", differs);
    follow_check(c, follow, t, incremental, basic, &v2, &p);
    p.mode = MLOD_CUT_LAZY;
    {
        /* a budget of node-views, any size: never over it; views left out
           keep their list entry for entry; every list a partition (statuses
           of the views left out are from frame 1) */
        uint8_t pick = rd_u8(r);
        if (pick < 96) {
            uint64_t spent = 0, *was = (uint64_t *)malloc(sizeof(uint64_t) * v2.count);
            uint32_t v, bad = 0;
            FZ_REQUIRE(was != NULL, "out of memory");
            p.budget = pick < 32   ? 1u + rd_u8(r)
                       : pick < 64 ? 1u + 256u * rd_u8(r) + rd_u8(r)
                                   : (uint64_t)rd_u32(r) << (pick % 12);
            if (p.budget == 0) p.budget = 1;
            for (v = 0; v < v2.count; v++) was[v] = list_hash(lazy, v);
            cut_update(c, lazy, t, &v2, &p, 0, 0, "lazy update with a budget, frame 2");
            check_cut(lazy, t, &layout, &v2, eps, 0, 0, &c->rng, "lazy cut with a budget, frame 2");
            for (v = 0; v < v2.count; v++) {
                mlod_cut_view a = mlod_cut_get(lazy, v);
                spent += a.evaluated;
                if (a.deferred) bad += a.evaluated != 0 || list_hash(lazy, v) != was[v];
            }
            free(was);
            FZ_REQUIRE(spent <= p.budget, "a lazy update spent %llu node-views, its budget %llu",
                       (unsigned long long)spent, (unsigned long long)p.budget);
            FZ_REQUIRE(bad == 0, "%u views a budget deferred changed their list or were evaluated", bad);
            FZ_NOTE("fuzz: budget %llu, spent %llu\n", (unsigned long long)p.budget, (unsigned long long)spent);
            p.budget = 0;
        }
    }
    for (call = 0; call < FZ_LAZY_CALLS; call++) {
        cut_update(c, lazy, t, &v2, &p, 0, 0, "lazy update, frame 2");
        check_cut(lazy, t, &layout, &v2, eps, 0, call == 0, &c->rng, "lazy cut, frame 2");
        if (same_cut(basic, lazy, v2.count, &differs)) break;
    }
    FZ_REQUIRE(call < FZ_LAZY_CALLS, "lazy cut (q = %u) still differs from basic after %d updates, view %u",
               p.lazy_steps, FZ_LAZY_CALLS, differs);
    /* basic through the hook and without: identical */
    if (c->parallel) {
        p.mode = MLOD_CUT_BASIC;
        p.parallel = NULL;
        cut_update(c, lazy, t, &v2, &p, 0, 0, "basic update without the hook");
        FZ_REQUIRE(same_cut(basic, lazy, v2.count, &differs), "basic cut differs with and without the hook, view %u",
                   differs);
        p.parallel = c->parallel;
    }
    run_splat(c, r, t, basic, &v2);
    check_params(c, r, lazy, t, &v2, &layout);
done:
    /* the public helpers, on this tree and these views (valid or not) and
       on hostile arguments */
    check_frames(r, t, &v1);
    check_frames(r, t, &v2);
    check_depth_nodes(t->leaf_count, rd_u32(r));
    check_depth_nodes(rd_leaf_count(r), rd_u32(r));
    check_growth(r, t);
    check_sample(r, &c->counter, &c->alloc);
    mlod_atlas_destroy(follow);
    mlod_cut_destroy(basic);
    mlod_cut_destroy(incremental);
    mlod_cut_destroy(lazy);
}

/* The tree built again from packed arrays, without injected failures:
   strides change nothing. */
static void check_same_as_packed(const mlod_tree *t, const fz_scene *s, const fz_build *b)
{
    mlod_build_desc desc = b->desc;
    mlod_tree *packed = NULL;
    mlod_error e;
    mlod_result res;
    size_t n;
    desc.allocator = NULL;
    if (s->points) {
        mlod_points points = scene_points(s, s->positions);
        res = mlod_build_points(&points, &desc, &packed, &e);
    } else {
        mlod_mesh mesh = fz_mesh_of(s, s->positions);
        res = mlod_build_mesh(&mesh, &desc, &packed, &e);
    }
    FZ_REQUIRE(res == MLOD_OK, "the packed build failed (%s) where the strided one succeeded", mlod_result_name(res));
    n = packed->node_count;
    FZ_REQUIRE(packed->node_count == t->node_count && !memcmp(packed->spheres, t->spheres, 4 * n * sizeof(float)) &&
                   (!t->cones || !memcmp(packed->cones, t->cones, 4 * n * sizeof(float))) &&
                   (!t->areas || !memcmp(packed->areas, t->areas, n * sizeof(float))) &&
                   (!t->colors || !memcmp(packed->colors, t->colors, 3 * n * sizeof(float))),
               "strides gave another tree than packed arrays");
    mlod_tree_destroy(packed);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_scene scene;
    fz_reader r;
    fz_ctx c;
    fz_build b;
    mlod_tree *t = NULL;
    mlod_error e;
    mlod_result res;
    uint64_t h = 1469598103934665603ull;
    uint8_t flags, chaos, view_chaos;
    size_t i, ext_at;
    int sane, large, must_fail, tries = 0;
    unsigned long live;
    /* the generator's seed: every byte but the extension byte, so that an
       input of the format before it, given a 0 there, runs as it did */
    ext_at = size && (data[0] & 16) ? 4 : 3;
    for (i = 0; i < size; i++)
        if (i != ext_at) h = (h ^ data[i]) * 1099511628211ull;
    memset(&r, 0, sizeof r);
    r.data = data;
    r.size = size;
    r.state = h;
    memset(&c, 0, sizeof c);
    c.alloc.alloc = fz_alloc;
    c.alloc.free = fz_free;
    c.alloc.user = &c.counter;
    c.hook.run = fz_run_reverse;
    c.rng.s = h;

    flags = rd_u8(&r);
    c.sane_geometry = (flags >> 1) & 1;
    c.sane_views = (flags >> 2) & 1;
    c.parallel = (flags & 8) ? &c.hook : NULL;
    if (flags & 16) c.counter.fail_at = 1 + rd_u8(&r);
    chaos = rd_u8(&r);
    view_chaos = rd_u8(&r);
    c.ext = r.at < r.size ? rd_u8(&r) : 0; /* an input that ends before it has none */
    large = (c.ext & FZ_EXT_LARGE) == FZ_EXT_LARGE;
    if (c.ext & FZ_EXT_FAILURES) { /* after allocation s, every k-th fails, 1 .. 16 times */
        uint8_t m = rd_u8(&r);
        c.counter.every_k = 2 + (m & 15u);
        c.counter.fail_left = 1 + (m >> 4);
        c.counter.fail_after = rd_u8(&r);
    }
    r.chaos = c.sane_geometry ? 0 : chaos;
    sane = c.sane_geometry;
    if (c.ext & FZ_EXT_STRIDES) parse_strides(&r, &c.strides, sane);
    parse_scene(&r, &scene, flags, sane, large);
    parse_build(&r, &b, &scene, sane, large, &c.alloc);
    if (scene.points && b.desc.sample_count == 0) b.desc.sample_count = 1; /* ignored for points */
    memset(&e, 0, sizeof e);
    for (;;) {
        live = c.counter.live;
        t = (mlod_tree *)&c;
        if (scene.points) {
            mlod_points points = scene_points(&scene, scene.positions);
            stride_points(&points, &c.strides);
            must_fail = stride_points_bad(&points, &c.strides);
            res = mlod_build_points(&points, &b.desc, &t, &e);
        } else {
            mlod_mesh mesh = fz_mesh_of(&scene, scene.positions);
            stride_mesh(&mesh, &c.strides);
            must_fail = stride_mesh_bad(&mesh, &c.strides);
            res = mlod_build_mesh(&mesh, &b.desc, &t, &e);
        }
        if (res == MLOD_OK || !injected_oom(&c.counter, res) || !(c.ext & FZ_EXT_FAILURES) || tries++ >= FZ_RETRIES)
            break;
        fz_where = "build";
        check_error(res, &e);
        FZ_REQUIRE(t == NULL, "build failed with %s but left *out_tree set", mlod_result_name(res));
        check_no_leak(&c.counter, live, "build");
    }
    must_fail |= scene.must_fail || b.must_fail;
    FZ_NOTE("fuzz: %s, %u %s, N %u, attributes 0x%x, radius_scale %g, scene centre (%g %g %g) radius %g: %s\n",
            scene.points ? "points" : "mesh", scene.vertex_count, scene.points ? "points" : "vertices",
            b.desc.sample_count, b.desc.attributes, (double)b.desc.radius_scale, scene.centre[0], scene.centre[1],
            scene.centre[2], scene.radius, mlod_result_name(res));
    if (res != MLOD_OK) {
        fz_where = "build";
        check_error(res, &e);
        FZ_REQUIRE(t == NULL, "build failed with %s but left *out_tree set", mlod_result_name(res));
        check_no_leak(&c.counter, live, "build");
        /* MLOD_ERROR_RANGE: radius_scale times the leaf spacing overflows */
        FZ_REQUIRE(must_fail || injected_oom(&c.counter, res) || (!scene.points && res == MLOD_ERROR_EMPTY) ||
                       res == MLOD_ERROR_RANGE,
                   "build of valid input failed with %s: %s", mlod_result_name(res), e.message);
        FZ_REQUIRE(scene.must_fail || b.must_fail || !must_fail || res == MLOD_ERROR_INVALID_ARGUMENT,
                   "build refused a bad stride with %s, not MLOD_ERROR_INVALID_ARGUMENT", mlod_result_name(res));
    } else {
        uint32_t leaves = scene.points ? scene.vertex_count : b.desc.sample_count;
        FZ_REQUIRE(!must_fail, "build accepted invalid input (scene %d, options %d, strides %d)", scene.must_fail,
                   b.must_fail, must_fail);
        FZ_REQUIRE(e.code == MLOD_OK && t != NULL && t != (mlod_tree *)&c, "build succeeded without a tree or with error.code %d",
                   (int)e.code);
        check_tree(t, leaves, b.desc.attributes, "after build");
        if (c.strides.on) check_same_as_packed(t, &scene, &b);
        r.chaos = c.sane_views ? 0 : view_chaos;
        run_views(&c, &r, t, &scene, leaves);
        FZ_NOTE("fuzz: pipeline done (%u leaves, %lu allocations, %lu failed on purpose)\n", leaves, c.counter.calls,
                c.counter.failed);
        mlod_tree_destroy(t);
    }
    FZ_REQUIRE(c.counter.live == 0, "%lu blocks not given back", c.counter.live);
    return 0;
}
