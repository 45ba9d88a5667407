/* fuzz/fuzz_megaviews.c - libFuzzer harness of MANY VIEWS AT ONCE and of
   the helpers around it: arbitrary bytes become a small scene (points or a
   mesh, with cones and colours or without), 1 to 64 views, sometimes up
   to 256 (duplicates, directions, fields of view; hostile ones too: NaN,
   huge, zero-length directions, bad strides), a view tree (built, then refitted to moved
   views), MegaViews parameters (hostile epsilon, delta, group_radius,
   flags, resolutions up to 2^32 - 1; the maps' orientation, refused ones
   too) and an atlas; then the render, the
   unfused maps and their queries, hole filling and mlod_sample, each result
   checked against what manylods.h promises.  A broken promise prints what
   broke and aborts, so libFuzzer keeps the input.

     make fuzz                      (every harness; see fuzz/run_all.sh), or
     fuzz/run.sh build/fuzz/fuzz_megaviews SECONDS WORKDIR   (this one)
     MANYLODS_FUZZ_VERBOSE=1 build/fuzz/fuzz_megaviews FILE...   how far each input got

   Every block the library takes comes from a counting allocator that
   refuses what would hold more than 64 MiB at once (FZ_CAP: a resolution
   of 46341 must fail, never allocate gigabytes) and, when the input asks,
   fails one allocation (the n-th of the run; the call is then tried again).
   Checked:
   - every failed call returns error.code with a message, leaves its
     output pointer NULL and holds no byte more than before; a call fails
     with MLOD_ERROR_OUT_OF_MEMORY only where the allocator refused one;
   - the view tree: built exactly for the view sets mlod_view_set documents
     as valid (finite eyes within 1e36, strides 0 or multiples of 4 of at
     least 12, directions finite and of non-zero length, half fields of
     view in (0, pi], half_fov 0 or in (0, pi]); leaf j holds view
     leaf_sources[j]'s eye exactly with radius 0, every sphere holds its
     children's with the slack 2^-20 (exact arithmetic, tests/exact.h), cones
     likewise (2^-20 rad), half_fovs are the children's smallest and
     largest, every eye below a node lies at least floors[2i] above its
     centre along its axis; tree->bytes is what the allocator holds for it
     and its peak stays within mlod_build_points_bound + the struct + 4
     (+ 32) bytes per view; a refit allocates nothing, succeeds exactly for valid sets of
     the same count and kind and on failure leaves the tree as it was;
   - mlod_megaviews_check refuses exactly the documented parameters, with
     the documented codes where one field is bad; render and render_maps
     return its code first; mlod_megaviews_view's tile is 2R x R (0 wide past
     2^31 - 1), forward +z, up +y, and mlod_megaviews_view_oriented's the
     same with the params' axes (none: mlod_megaviews_view's); mlod_megaviews_bound is 0 for no views or a resolution the
     render refuses, (size_t)-1 for unbounded pairs, no smaller for more
     pairs;
   - mlod_megaviews_render: refused calls (NULLs, parameters, an atlas of
     another view count, tile size or channels) leave the atlas untouched,
     bit for bit; maps that do not fit size_t are MLOD_ERROR_OVERFLOW;
     failed allocations leave every tile empty; on success stats add up
     (pairs, culled, draws, shared leaves, levels, node_pairs <= the
     scene's nodes), stats.peak_bytes equals the allocator's real peak
     during the call and stays within mlod_megaviews_bound(views, R,
     stats.node_pairs); every drawn pixel holds a node (colours are set to
     node indices) at the distance from its view's eye to the node's
     centre, with that node's cone axis as normal; pixels outside the tiles
     are untouched; the same atlas without the hook as with it, and with
     stats NULL; params.allocator NULL takes the atlas's, one without
     functions the default; the render's private variants (walks from any
     level, tiny first list and descent rooms, the exact path instead of
     the float filter, as tests/test_megaviews.c calls them) give the same
     atlas and statistics, their peak within mlod__mv_bound;
   - delta = 0 and no groups: the atlas equals, bit for bit, each view's
     basic cut (mlod_cut_update) and mlod_splat of its
     mlod_megaviews_view_oriented in the params' orientation,
     less what its field of view culls where the views have directions
     (as tests/test_megaviews.c draws it), but for pixels where two nodes
     lie at exactly one depth (the manual's exception: the depth equal,
     the node may differ), and with distinct eyes nothing is shared and
     the leaf draws are the cuts' drawn nodes;
   - mlod_megaviews_render_maps: the same refusals; stats.peak_bytes equals
     the allocator's peak (the maps returned included) and the maps'
     mlod_megaviews_maps_bytes what the allocator holds for them; the same
     statistics as the fused render; mlod_megaviews_query of every pixel
     (at most FZ_QUERIES of them) equals the fused atlas (disc_scale 1):
     hit where drawn, the same depth bits and node; 0 out of range, for
     NULLs and for a view tree or scene of other counts;
   - mlod_atlas_fill_holes on the MegaViews atlas and on atlases of odd
     tile sizes with random sparse content: drawn pixels keep their bits,
     each empty pixel gets the pull-push value of a double-precision
     reference (relative 1e-5 of the tile's largest value), tiles with
     nothing drawn stay empty, pixels outside tiles are untouched, a second
     call changes nothing; a failed call changes nothing;
   - mlod_sample on hostile importances (zeros, NaN, inf, FLT_MAX,
     denormals, negatives), sizes (0 included), methods and NULLs: it
     fails exactly for what it documents, with the documented code where
     one thing is wrong, samples and weights untouched; otherwise samples
     lie in the domain with finite weights >= 0, weight 0 at importance 0
     and everywhere when all importances are 0, the inverse transform's
     weight is F / f exactly; the same with the reversed hook; the
     allocator's peak is mlod_sample_bound(D, method) (none for
     Metropolis), and a failed table allocation is MLOD_ERROR_OUT_OF_MEMORY;
   - at the end every block given back.
   Each input stays in the tens of milliseconds: at most 300 points or 64
   triangles sampled 512 times, 256 views, views x 2 R^2 <= 2^17 pixels but
   for the hostile resolutions (refused, or failed by the cap).

   Input format: bytes in order (little endian, fuzz/reader.h); past the
   end, bytes of a generator seeded by the whole input.  First a flags
   byte:
     bit 0  a mesh (else a point cloud)
     bit 1  normals (scene cones)
     bit 2  colours (the scene's colours become its node indices)
     bit 3  run tasks through a serial parallel-for hook (reverse order)
     bit 4  fail one allocation (the next byte says which: 1 .. 256)
     bit 5  the views have directions
     bit 6  the views have per-view half fields of view
     bit 7  hostile (the next byte: the chance, in 256, that a field is
            hostile)
   then the scene (build_scene), the views (parse_views), the parameters
   and atlas of each frame (run_frame), the refit and its moved views, the
   atlases of fill_other and mlod_sample's arguments (check_sample), each
   in the order read.  fuzz/make_megaviews_corpus.sh writes the seeds. */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "fuzz.h"
#include "reader.h"
#include "fz_errors.h"
#include "../tests/exact.h"
#include "../tests/mv_reference.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FZ_MAX_POINTS 300u
#define FZ_MAX_VERTICES 48u
#define FZ_MAX_TRIANGLES 64u
#define FZ_MAX_SAMPLES 512u
#define FZ_MAX_VIEWS 256u /* 1 .. 64 mostly; more for view trees the render walks */
#define FZ_PIXEL_BUDGET ((uint64_t)1 << 17) /* views x 2 R^2 of a render */
#define FZ_CAP ((size_t)64 << 20)           /* the most the allocator holds at once */
#define FZ_HEADER 16u                       /* the allocator's block header: its size */
#define FZ_QUERIES 2048u
#define FZ_FILL_VIEWS 8u
#define FZ_FILL_SIDE 40u
#define FZ_SAMPLE_DOMAIN 320u
#define FZ_SAMPLE_COUNT 512u
#define FZ_PI 3.14159265358979323846
#define FZ_CONE_SLACK (9.5367431640625e-7L - 1e-15L)

enum {
    FZ_MESH = 1,
    FZ_NORMALS = 2,
    FZ_COLORS = 4,
    FZ_HOOK = 8,
    FZ_FAIL = 16,
    FZ_DIRECTIONS = 32,
    FZ_FOVS = 64,
    FZ_HOSTILE = 128
};

/* ------------------------------------------------------------- reader */

/* A hostile float: one of the interesting values, or raw bits. */
static float rd_raw_float(fz_reader *r)
{
    static const uint32_t special[] = {
        0x00000000u, 0x80000000u, 0x7fc00000u, 0xffc00000u, 0x7f800000u, 0xff800000u, 0x7f7fffffu, 0xff7fffffu,
        0x00800000u, 0x00000001u, 0x80000001u, 0x7b40a2f6u /* ~1e36 */, 0x7b40a2f7u /* just above 1e36 */,
        0x3f800000u, 0xbf800000u, 0x33d6bf95u /* 1e-7 */, 0x7149f2cau /* 1e30 */, 0x4b000000u /* 2^23 */,
        0x7e967699u /* 1e38 */, 0x0da24260u /* 1e-30 */, 0x40490fdbu /* pi, rounded up */,
        0x40490fdcu /* just above */, 0x3fc90fdbu /* pi/2 */, 0x3f000000u /* 0.5 */, 0x4735e500u /* 46341 */,
        0x7f800001u /* signalling NaN */};
    uint8_t pick = rd_u8(r);
    if (pick < 2 * sizeof special / sizeof special[0]) return bits_float(special[pick / 2]);
    return bits_float(rd_u32(r));
}

/* With the reader's chaos: whether this field is hostile. */
static int rd_hostile(fz_reader *r) { return r->chaos && rd_u8(r) < r->chaos; }

/* -------------------------------------------------------- allocator */

/* Every block with its size in a header; refuses what would hold more
   than cap at once, and fails allocation number fail_at. */
typedef struct fz_mem {
    size_t live, peak, cap;
    unsigned long calls, blocks, fail_at;
    unsigned long failed, capped; /* refused on purpose, refused over the cap */
} fz_mem;

static void *fz_alloc(void *user, size_t bytes)
{
    fz_mem *m = (fz_mem *)user;
    unsigned char *p;
    m->calls++;
    if (m->fail_at && m->calls == m->fail_at) {
        m->failed++;
        return NULL;
    }
    if (bytes > m->cap - m->live) {
        m->capped++;
        return NULL;
    }
    p = (unsigned char *)malloc(bytes + FZ_HEADER);
    if (!p) {
        m->capped++;
        return NULL;
    }
    memcpy(p, &bytes, sizeof bytes);
    m->live += bytes;
    m->blocks++;
    if (m->live > m->peak) m->peak = m->live;
    return p + FZ_HEADER;
}

static void fz_free(void *user, void *q)
{
    fz_mem *m = (fz_mem *)user;
    unsigned char *p;
    size_t bytes;
    if (!q) return;
    p = (unsigned char *)q - FZ_HEADER;
    memcpy(&bytes, p, sizeof bytes);
    FZ_REQUIRE(m->blocks > 0 && bytes <= m->live, "a block freed that the allocator does not hold");
    m->live -= bytes;
    m->blocks--;
    free(p);
}

/* The allocator before a call; the peak restarts from there. */
typedef struct fz_mark {
    size_t live;
    unsigned long blocks, calls, failed, capped;
} fz_mark;

static fz_mark fz_mark_now(fz_mem *m)
{
    fz_mark k;
    k.live = m->live;
    k.blocks = m->blocks;
    k.calls = m->calls;
    k.failed = m->failed;
    k.capped = m->capped;
    m->peak = m->live;
    return k;
}

/* Whether the allocator refused something since the mark. */
static int fz_refused(const fz_mem *m, const fz_mark *k) { return m->failed > k->failed || m->capped > k->capped; }

/* Whether it failed one on purpose since (trying again may succeed). */
static int fz_injected(const fz_mem *m, const fz_mark *k) { return m->failed > k->failed; }

static size_t fz_peak(const fz_mem *m, const fz_mark *k) { return m->peak - k->live; }

static void fz_holds_as_before(const fz_mem *m, const fz_mark *k, const char *what)
{
    FZ_REQUIRE(m->live == k->live && m->blocks == k->blocks,
               "%s failed but holds %ld bytes in %ld blocks more than before", what, (long)(m->live - k->live),
               (long)m->blocks - (long)k->blocks);
}

/* ------------------------------------------------------------ context */

typedef struct fz_ctx {
    fz_reader r;
    fz_mem mem;
    mlod_allocator alloc;
    mlod_parallel hook;
    const mlod_parallel *parallel;
    uint8_t flags;
    mlod_tree *scene;
    double centre[3], radius; /* of the scene's root sphere (radius > 0) */
    uint64_t hash;            /* of the whole input */
} fz_ctx;

static void fz_run_reverse(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    (void)user;
    for (i = count; i-- > 0;) task(context, i);
}

/* -------------------------------------------------------------- scene */

/* Points or a mesh of sane coordinates (scale 2^-10 .. 2^10, maybe off
   the origin), cones and colours as the flags say; colours then become
   node indices, so that an atlas's colour channel names its nodes.  NULL
   for a mesh without area. */
static mlod_tree *build_scene(fz_ctx *c)
{
    static float positions[3 * FZ_MAX_POINTS], normals[3 * FZ_MAX_POINTS], colors[3 * FZ_MAX_POINTS],
        radii[FZ_MAX_POINTS];
    static uint32_t indices[3 * FZ_MAX_TRIANGLES];
    fz_reader *r = &c->r;
    double scale = ldexp(1.0, (int)(rd_u8(r) % 21) - 10), offset[3];
    uint8_t far = rd_u8(r), dup = rd_u8(r) & 63, with_radii = rd_u8(r);
    int mesh = c->flags & FZ_MESH, k;
    uint32_t n, i, triangles = 0;
    mlod_build_desc desc;
    mlod_tree *t = NULL;
    mlod_error e;
    mlod_result res;
    for (k = 0; k < 3; k++) offset[k] = far < 32 ? scale * 8.0 * rd_signed(r) : 0.0;
    memset(&desc, 0, sizeof desc);
    desc.attributes = ((c->flags & FZ_NORMALS) ? (uint32_t)MLOD_ATTR_CONE : 0u) |
                      ((c->flags & FZ_COLORS) ? (uint32_t)MLOD_ATTR_COLOR : 0u);
    desc.seed = rd_u8(r);
    desc.parallel = c->parallel;
    n = mesh ? 3 + rd_u8(r) % (FZ_MAX_VERTICES - 2) : 1 + rd_u16(r) % FZ_MAX_POINTS;
    for (i = 0; i < n; i++) {
        double len = 0.0;
        if (i > 0 && rd_u8(r) < dup) {
            memcpy(positions + 3 * i, positions + 3 * (i - 1), 3 * sizeof(float));
        } else {
            for (k = 0; k < 3; k++) positions[3 * i + k] = (float)(offset[k] + scale * rd_signed(r));
        }
        for (k = 0; k < 3; k++) {
            normals[3 * i + k] = (float)rd_signed(r);
            len += (double)normals[3 * i + k] * normals[3 * i + k];
            colors[3 * i + k] = (float)rd_unit(r);
        }
        if (len == 0.0) normals[3 * i + 2] = 1.0f;
        radii[i] = (float)(scale * 0.2 * rd_unit(r));
    }
    if (mesh) {
        mlod_mesh m;
        triangles = 1 + rd_u8(r) % FZ_MAX_TRIANGLES;
        for (i = 0; i < 3 * triangles; i++) indices[i] = rd_u8(r) % n;
        memset(&m, 0, sizeof m);
        m.positions = positions;
        m.vertex_count = n;
        m.indices = indices;
        m.index_count = 3 * triangles;
        m.normals = (c->flags & FZ_NORMALS) ? normals : NULL;
        m.colors = (c->flags & FZ_COLORS) ? colors : NULL;
        desc.sample_count = 1 + rd_u16(r) % FZ_MAX_SAMPLES;
        res = mlod_build_mesh(&m, &desc, &t, &e);
    } else {
        mlod_points p;
        memset(&p, 0, sizeof p);
        p.positions = positions;
        p.count = n;
        p.normals = (c->flags & FZ_NORMALS) ? normals : NULL;
        p.colors = (c->flags & FZ_COLORS) ? colors : NULL;
        p.radii = with_radii < 64 ? radii : NULL;
        res = mlod_build_points(&p, &desc, &t, &e);
    }
    FZ_NOTE("fuzz: scene of %u %s (%u triangles): %s\n", n, mesh ? "vertices" : "points", triangles,
            mlod_result_name(res));
    if (res != MLOD_OK) {
        FZ_REQUIRE(mesh && res == MLOD_ERROR_EMPTY, "the scene's build failed: %s", e.message);
        return NULL;
    }
    for (k = 0; k < 3; k++) c->centre[k] = t->spheres[k];
    c->radius = t->spheres[3] > 0.0f ? t->spheres[3] : scale * 1e-3;
    if (t->colors)
        for (i = 0; i < t->node_count; i++) {
            t->colors[3 * (size_t)i] = (float)i;
            t->colors[3 * (size_t)i + 1] = t->colors[3 * (size_t)i + 2] = 0.0f;
        }
    return t;
}

/* -------------------------------------------------------------- views */

typedef struct fz_views {
    uint32_t count;
    float eyes[5 * FZ_MAX_VIEWS + 5], directions[5 * FZ_MAX_VIEWS + 5], fovs[2 * FZ_MAX_VIEWS + 2];
    mlod_view_set set;
    int valid; /* what the documentation of mlod_view_set accepts */
    /* each view as read through the strides: eye, direction, half field
       of view in effect (valid sets) */
    float eye[FZ_MAX_VIEWS][3], direction[FZ_MAX_VIEWS][3], fov[FZ_MAX_VIEWS];
} fz_views;

/* A stride of 3 to 5 floats (in bytes: 0 packed, 12, 16, 20), or (hostile)
   one the documentation refuses. */
static size_t rd_stride(fz_reader *r, uint32_t *floats)
{
    static const size_t bad[4] = {4, 8, 13, 2};
    uint8_t b = rd_u8(r);
    if (rd_hostile(r)) {
        *floats = 5; /* never read: refused first */
        return bad[b & 3];
    }
    *floats = (b & 3) ? 2 + (b & 3) : 3;
    return (b & 3) ? 4 * (size_t)*floats : 0;
}

static int stride_ok(size_t stride) { return stride == 0 || (stride >= 12 && stride % 4 == 0); }

/* A view set: from scratch, or (moved) the eyes of `from` moved by up to
   `jitter` times the scene's radius and new directions.  Hostile fields
   with the reader's chaos. */
static void parse_views(fz_ctx *c, fz_views *v, const fz_views *from)
{
    fz_reader *r = &c->r;
    uint8_t place = rd_u8(r), dup = rd_u8(r) & 63, global = rd_u8(r);
    double jitter = c->radius * ldexp(1.0, -(int)(rd_u8(r) % 24)), len;
    uint32_t i, k, eye_floats, dir_floats, fov_floats = 1;
    int dirs = (c->flags & FZ_DIRECTIONS) != 0, per_view = (c->flags & FZ_FOVS) != 0;
    float plane = (float)(c->centre[1] + c->radius * (0.5 + rd_unit(r)));
    memset(v, 0, sizeof *v);
    v->count = from ? from->count : rd_u8(r) < 16 ? 65 + rd_u8(r) % (FZ_MAX_VIEWS - 64) : 1 + rd_u8(r) % 64;
    if (rd_hostile(r)) v->count = from ? (v->count > 1 ? v->count - 1 : 2) : 0;
    if (from && rd_hostile(r)) dirs = !dirs; /* another kind: refit refuses it */
    v->set.eye_stride = rd_stride(r, &eye_floats);
    v->set.direction_stride = rd_stride(r, &dir_floats);
    v->set.half_fov_stride = (rd_u8(r) & 1) ? 4 * (size_t)(fov_floats = 2) : 0;
    if (rd_hostile(r)) v->set.half_fov_stride = 2 + 4 * (rd_u8(r) & 1); /* not a multiple of 4 */
    v->valid = v->count >= 1 && stride_ok(v->set.eye_stride);
    for (i = 0; i < v->count; i++) {
        float *e = v->eyes + eye_floats * i, *d = v->directions + dir_floats * i;
        double dir[3];
        if (from && i < from->count) {
            for (k = 0; k < 3; k++) e[k] = (float)(from->eye[i][k] + jitter * rd_signed(r));
        } else if (i > 0 && rd_u8(r) < dup) {
            memcpy(e, v->eyes + eye_floats * (i - 1), 3 * sizeof(float));
        } else {
            for (k = 0; k < 3; k++) {
                double s = rd_signed(r), at;
                switch (place >> 5) {
                case 0: case 1: at = c->centre[k] + c->radius * s; break;     /* among the scene */
                case 2: case 3: at = c->centre[k] + 4.0 * c->radius * s; break; /* around it */
                case 4: at = c->centre[k] + ldexp(c->radius, (int)(place % 40)) * s; break; /* far */
                case 5: at = k == 1 ? plane : c->centre[k] + c->radius * s; break;          /* lights on a plane */
                case 6: at = c->centre[k] + c->radius * 0.3; break;                         /* all at one point */
                default: at = c->centre[k] + c->radius * 1e-6 * s; break;                   /* a tiny cluster */
                }
                e[k] = (float)at;
            }
        }
        for (k = 0; k < 3; k++) e[k] = rd_maybe_raw(r, e[k]);
        for (k = 0; k < 3; k++) {
            dir[k] = rd_signed(r);
            if ((place >> 5) == 5) dir[k] = k == 1 ? -1.0 : 0.3 * dir[k]; /* facing down */
            d[k] = (float)ldexp(dir[k], (int)(rd_u8(r) % 41) - 20);
            if (rd_hostile(r)) d[k] = (rd_u8(r) & 1) ? 0.0f : rd_raw_float(r);
        }
        v->fovs[fov_floats * i] = rd_u8(r) < 16 ? (float)FZ_PI : (float)(0.05 + rd_unit(r) * (FZ_PI - 0.05));
        if (rd_hostile(r)) v->fovs[fov_floats * i] = rd_raw_float(r);
    }
    v->set.eyes = v->eyes;
    v->set.count = v->count;
    v->set.directions = dirs ? v->directions : NULL;
    v->set.half_fovs = dirs && per_view ? v->fovs : NULL;
    v->set.half_fov = global < 128 ? 0.0f : (float)(rd_unit(r) * FZ_PI);
    if (rd_hostile(r)) v->set.half_fov = rd_raw_float(r);
    if (!v->valid) return;
    /* what mlod_view_set documents: eyes finite within 1e36; with
       directions, directions finite and not of zero length, and half
       fields of view in (0, pi] (strides as for mlod_points; half_fovs: a
       multiple of 4), half_fov 0 or in (0, pi] */
    for (i = 0; i < v->count; i++) {
        const float *e = (const float *)((const char *)v->eyes + (v->set.eye_stride ? v->set.eye_stride : 12) * i);
        for (k = 0; k < 3; k++) {
            v->eye[i][k] = e[k];
            if (!(fabsf(e[k]) <= 1e36f)) v->valid = 0;
        }
    }
    if (!dirs) return;
    if (!stride_ok(v->set.direction_stride) || (per_view && v->set.half_fov_stride % 4)) {
        v->valid = 0;
        return;
    }
    for (i = 0; i < v->count; i++) {
        const float *d = (const float *)((const char *)v->directions +
                                         (v->set.direction_stride ? v->set.direction_stride : 12) * i);
        float h = per_view ? *(const float *)((const char *)v->fovs + (v->set.half_fov_stride ? v->set.half_fov_stride : 4) * i)
                           : v->set.half_fov == 0.0f ? (float)(0.5 * FZ_PI) : v->set.half_fov;
        for (len = 0.0, k = 0; k < 3; k++) {
            v->direction[i][k] = d[k];
            if (!isfinite(d[k])) v->valid = 0;
            len += (double)d[k] * d[k];
        }
        if (!(len > 0.0) || !(h > 0.0f && h <= (float)FZ_PI)) v->valid = 0;
        v->fov[i] = h;
    }
}

/* ---------------------------------------------------------- view tree */

static int below(uint32_t node, uint32_t ancestor)
{
    while (node > ancestor) node = (node - 1) / 2;
    return node == ancestor;
}

static void check_view_tree(const mlod_view_tree *t, const fz_views *v, const char *when)
{
    const mlod_tree *eyes = t->eyes;
    uint32_t n = v->count, i, j, k;
    static unsigned char seen[FZ_MAX_VIEWS];
    FZ_REQUIRE(t->view_count == n && eyes && eyes->leaf_count == n && eyes->node_count == 2 * n - 1 && eyes->leaf_sources,
               "%s: a view tree of %u views has %u views, %u leaves", when, n, t->view_count, eyes ? eyes->leaf_count : 0);
    FZ_REQUIRE(!t->half_fovs == !v->set.directions && !t->floors == !v->set.directions && !eyes->cones == !v->set.directions,
               "%s: cones, half_fovs and floors only with directions", when);
    memset(seen, 0, sizeof seen);
    for (j = 0; j < n; j++) {
        uint32_t s = eyes->leaf_sources[j];
        const float *sp = eyes->spheres + 4 * (size_t)(n - 1 + j);
        FZ_REQUIRE(s < n && !seen[s], "%s: leaf %u holds view %u (twice, or out of range)", when, j, s);
        seen[s] = 1;
        FZ_REQUIRE(sp[0] == v->eye[s][0] && sp[1] == v->eye[s][1] && sp[2] == v->eye[s][2] && sp[3] == 0.0f,
                   "%s: leaf %u (%g %g %g r %g) is not view %u's eye (%g %g %g)", when, j, sp[0], sp[1], sp[2], sp[3],
                   s, v->eye[s][0], v->eye[s][1], v->eye[s][2]);
        if (t->half_fovs)
            FZ_REQUIRE(t->half_fovs[2 * (size_t)(n - 1 + j)] == v->fov[s] && t->half_fovs[2 * (size_t)(n - 1 + j) + 1] == v->fov[s],
                       "%s: leaf %u's half fields of view %g, %g, view %u's %g", when, j,
                       t->half_fovs[2 * (size_t)(n - 1 + j)], t->half_fovs[2 * (size_t)(n - 1 + j) + 1], s, v->fov[s]);
    }
    for (i = 1; i < eyes->node_count; i++) {
        uint32_t p = (i - 1) / 2;
        FZ_REQUIRE(exact_sphere_contains_filtered(eyes->spheres + 4 * (size_t)p, eyes->spheres + 4 * (size_t)i),
                   "%s: view node %u's sphere not inside its parent's with slack 2^-20", when, i);
        if (eyes->cones)
            FZ_REQUIRE(exact_cone_contains(eyes->cones + 4 * (size_t)p, eyes->cones + 4 * (size_t)i, FZ_CONE_SLACK),
                       "%s: view node %u's cone not inside its parent's with 2^-20 rad", when, i);
    }
    if (!t->half_fovs) return;
    for (i = 0; i + 1 < n; i++) {
        const float *a = t->half_fovs + 2 * (2 * (size_t)i + 1), *b = a + 2, *f = t->half_fovs + 2 * (size_t)i;
        FZ_REQUIRE(f[0] == (a[0] < b[0] ? a[0] : b[0]) && f[1] == (a[1] > b[1] ? a[1] : b[1]),
                   "%s: view node %u's half fields of view are not its children's smallest and largest", when, i);
    }
    for (i = 0; i < eyes->node_count; i++) {
        const float *s = eyes->spheres + 4 * (size_t)i, *cone = eyes->cones + 4 * (size_t)i;
        long double axis_len = sqrtl((long double)cone[0] * cone[0] + (long double)cone[1] * cone[1] +
                                     (long double)cone[2] * cone[2]);
        float floor_ = t->floors[2 * (size_t)i];
        FZ_REQUIRE(!isnan(floor_) && floor_ < INFINITY && t->floors[2 * (size_t)i + 1] >= 0.0f &&
                       t->floors[2 * (size_t)i + 1] < INFINITY,
                   "%s: view node %u's floor %g, spread %g", when, i, floor_, t->floors[2 * (size_t)i + 1]);
        if (floor_ == -INFINITY) continue;
        for (j = 0; j < n; j++) {
            const float *e = eyes->spheres + 4 * (size_t)(n - 1 + j);
            long double h = 0.0L, size = fabsl((long double)floor_);
            if (!below(n - 1 + j, i)) continue;
            for (k = 0; k < 3; k++) {
                h += ((long double)e[k] - s[k]) * cone[k] / axis_len;
                size += fabsl((long double)e[k]) + fabsl((long double)s[k]);
            }
            FZ_REQUIRE(h >= (long double)floor_ - 1e-15L * size,
                       "%s: an eye below view node %u lies %Lg along its axis, under its floor %g", when, i, h, floor_);
        }
    }
}

/* Build the view tree: exactly the valid sets succeed (an injected
   failure is tried again); tree->bytes is what it holds, its peak within
   the documented bound.  NULL when it failed. */
static mlod_view_tree *build_view_tree(fz_ctx *c, const fz_views *v)
{
    int tries;
    for (tries = 0;; tries++) {
        fz_mark k = fz_mark_now(&c->mem);
        mlod_view_tree *t = (mlod_view_tree *)&k;
        mlod_error e;
        mlod_result res = mlod_view_tree_build(&v->set, &c->alloc, c->parallel, &t, &e);
        fz_where = "mlod_view_tree_build";
        if (res == MLOD_OK) {
            uint32_t attributes = MLOD_ATTR_REFIT | (v->set.directions ? (uint32_t)MLOD_ATTR_CONE : 0u);
            size_t bound = mlod_build_points_bound(v->count, attributes) + sizeof(mlod_view_tree) +
                           4 * (size_t)v->count + (v->set.directions ? 32 * (size_t)v->count : 0);
            FZ_REQUIRE(v->valid, "mlod_view_tree_build accepted an invalid view set");
            FZ_REQUIRE(t && t != (mlod_view_tree *)&k && e.code == MLOD_OK, "view tree build: no tree or error.code %d",
                       (int)e.code);
            FZ_REQUIRE(t->bytes == c->mem.live - k.live, "the view tree reports %zu bytes, holds %zu", t->bytes,
                       c->mem.live - k.live);
            FZ_REQUIRE(fz_peak(&c->mem, &k) <= bound, "the view tree's build held %zu bytes, bound %zu",
                       fz_peak(&c->mem, &k), bound);
            FZ_NOTE("fuzz: view tree of %u views%s: %zu bytes\n", v->count,
                    v->set.directions ? " with directions" : "", t->bytes);
            check_view_tree(t, v, "after the view tree's build");
            return t;
        }
        check_error(res, &e);
        FZ_REQUIRE(t == NULL, "mlod_view_tree_build failed (%s) but left *out set", mlod_result_name(res));
        fz_holds_as_before(&c->mem, &k, "mlod_view_tree_build");
        FZ_NOTE("fuzz: view tree: %s (%s)\n", mlod_result_name(res), e.message);
        FZ_REQUIRE(!v->valid || (res == MLOD_ERROR_OUT_OF_MEMORY && fz_refused(&c->mem, &k)),
                   "mlod_view_tree_build refused a valid view set: %s", e.message);
        if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) return NULL;
    }
}

/* ------------------------------------------------------------- params */

static const mlod_allocator fz_no_allocator; /* NULL functions: the default */

typedef struct fz_params {
    mlod_megaviews_params p;
    int uncounted;       /* the render's scratch from the default allocator */
    mlod_result check;   /* what mlod_megaviews_check must return: MLOD_OK, or with one field bad its code */
    int bad;             /* fields the documentation refuses */
} fz_params;

static const uint32_t fz_hostile_resolutions[] = {0u,          46340u,      46341u,      65535u,     65536u,
                                                   1u << 20,    0x7fffffffu, 0x80000000u, 0xffffffffu};

/* The maps' orientation (params.forward, up), from bits 1 to 7 of the
   flags byte and the input's hash: no byte of its own, so every input
   reads its fields as before.  fb below 128: none (the default); else
   down (ceiling lights), along the axes, the default's at other lengths,
   nearly parallel, tiny, or an oblique frame from the hash; hostile
   inputs get, one in eight, a frame mlod_megaviews_check refuses
   (parallel, opposite, a zero axis, NaN, infinite). */
static void parse_orientation(const fz_ctx *c, uint8_t fb, fz_params *fp)
{
    static const float frames[8][6] = {{0, -1, 0, 0, 0, 1},        {0, 1, 0, 1, 0, 0},     {1, 0, 0, 0, 1, 0},
                                       {0, 0, -1, 0, -1, 0},       {0, 0, 2, 0, 5, 0},     {1, 1, 1, 0, 1, 0},
                                       {0, 1, 0, 1e-3f, 1, 0},     {1e-30f, 0, 0, 0, 1e-30f, 0}};
    static const float refused[7][6] = {{0, -1, 0, 0, 2, 0},     {1, 1, 0, -3, -3, 0},      {0, 0, 0, 0, 1, 0},
                                        {0, -1, 0, 0, 0, 0},     {0, NAN, 0, 0, 0, 1},      {0, -1, 0, INFINITY, 0, 1},
                                        {1e-30f, 0, 0, 1e-30f, 0, 1e-37f}};
    const float *pick;
    float oblique[6];
    uint64_t h = c->hash * 0x9E3779B97F4A7C15ull + fb;
    uint32_t o = fb >> 1, k;
    if (o < 64) return;
    o -= 64;
    if (c->r.chaos && o % 8 == 7) {
        pick = refused[(h >> 40) % 7];
        fp->bad++;
        fp->check = isfinite(pick[1]) && isfinite(pick[3]) ? MLOD_ERROR_BAD_VIEW : MLOD_ERROR_NON_FINITE;
    } else if (o < 24) {
        pick = frames[o % 8];
    } else { /* oblique: components in [-1, 1) from the hash; a frame only where clearly one */
        double f[3], u[3], x[3], lf, lu;
        for (k = 0; k < 6; k++) oblique[k] = (float)((int8_t)(h >> (8 * k)) / 128.0);
        for (k = 0; k < 3; k++) f[k] = oblique[k], u[k] = oblique[3 + k];
        x[0] = f[1] * u[2] - f[2] * u[1];
        x[1] = f[2] * u[0] - f[0] * u[2];
        x[2] = f[0] * u[1] - f[1] * u[0];
        lf = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        pick = lf > 0.1 && lu > 0.1 && sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 0.1 * lf * lu ? oblique
                                                                                                     : frames[o % 8];
    }
    memcpy(fp->p.forward, pick, 12);
    memcpy(fp->p.up, pick + 3, 12);
}

static void parse_params(fz_ctx *c, uint32_t views, fz_params *fp)
{
    fz_reader *r = &c->r;
    uint8_t eb = rd_u8(r), db = rd_u8(r), rb = rd_u8(r), fb = rd_u8(r), gb = rd_u8(r);
    mlod_megaviews_params *p = &fp->p;
    memset(fp, 0, sizeof *fp);
    p->epsilon = eb < 224 ? (float)ldexp(1.0 + (eb & 7) / 8.0, (int)((eb >> 3) % 8) - 3) : INFINITY;
    p->delta = db < 100 ? 0.0f : db < 140 ? MLOD_MEGAVIEWS_DELTA : (float)(4.0 * rd_unit(r));
    if (rb < 170)
        p->resolution = 1 + rb % 12;
    else
        p->resolution = 13 + rd_u8(r) % 52;
    while (p->resolution > 1 && (uint64_t)views * 2 * p->resolution * p->resolution > FZ_PIXEL_BUDGET) p->resolution--;
    p->flags = fb & 1u;
    parse_orientation(c, fb, fp);
    p->group_radius = gb < 180 ? 0.0f : (float)(c->radius * ldexp(rd_unit(r), (int)(gb % 8) - 4));
    p->parallel = c->parallel;
    /* NULL: the atlas's (the same counter); an allocator without
       functions: the default (not counted) */
    fp->uncounted = rd_u8(r) % 8 == 7;
    p->allocator = fp->uncounted ? &fz_no_allocator : (rb & 1) ? &c->alloc : NULL;
    /* hostile fields, and the code mlod_megaviews_check gives when only
       that one is bad */
    if (rd_hostile(r)) {
        p->epsilon = rd_raw_float(r);
        if (!(p->epsilon > 0.0f)) fp->bad++, fp->check = MLOD_ERROR_BAD_EPSILON;
    }
    if (rd_hostile(r)) {
        p->delta = rd_raw_float(r);
        if (!(p->delta >= 0.0f && p->delta < INFINITY))
            fp->bad++, fp->check = isnan(p->delta) ? MLOD_ERROR_NON_FINITE : MLOD_ERROR_INVALID_ARGUMENT;
    }
    if (rd_hostile(r)) {
        p->group_radius = rd_raw_float(r);
        if (!(p->group_radius >= 0.0f && p->group_radius < INFINITY))
            fp->bad++, fp->check = isnan(p->group_radius) ? MLOD_ERROR_NON_FINITE : MLOD_ERROR_INVALID_ARGUMENT;
    }
    if (rb >= 250 || rd_hostile(r)) { /* 46341 and above: refused, or failed by the cap */
        p->resolution = fz_hostile_resolutions[rd_u8(r) % (sizeof fz_hostile_resolutions / sizeof fz_hostile_resolutions[0])];
        if (p->resolution == 0 || p->resolution > 0x7fffffffu) fp->bad++, fp->check = MLOD_ERROR_INVALID_ARGUMENT;
    }
    if (rd_hostile(r)) {
        p->flags = rd_u32(r);
        if (p->flags & ~(uint32_t)MLOD_VIEW_CULL_BACKFACES) fp->bad++, fp->check = MLOD_ERROR_BAD_VIEW;
    }
    if (fp->bad != 1) fp->check = fp->bad ? MLOD_ERROR_INVALID_ARGUMENT : MLOD_OK; /* several: some error */
}

static void check_params(const fz_params *fp)
{
    mlod_error e;
    mlod_result res = mlod_megaviews_check(&fp->p, &e);
    fz_where = "mlod_megaviews_check";
    if (!fp->bad) {
        FZ_REQUIRE(res == MLOD_OK && e.code == MLOD_OK, "mlod_megaviews_check refused valid parameters: %s", e.message);
        return;
    }
    check_error(res, &e);
    FZ_REQUIRE(mlod_megaviews_check(NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "mlod_megaviews_check(NULL)");
    res = mlod_megaviews_check(&fp->p, &e);
    FZ_REQUIRE(fp->bad > 1 || res == fp->check,
               "mlod_megaviews_check: %s for epsilon %g delta %g group_radius %g resolution %u flags 0x%x, expected %s",
               mlod_result_name(res), (double)fp->p.epsilon, (double)fp->p.delta, (double)fp->p.group_radius,
               fp->p.resolution, fp->p.flags, mlod_result_name(fp->check));
}

/* Whether the maps of a render at this resolution cannot fit size_t (one
   map per view node at most, 8 bytes a pixel): MLOD_ERROR_OVERFLOW, and
   whether they could (then the cap makes it MLOD_ERROR_OUT_OF_MEMORY). */
static int maps_overflow(uint32_t resolution, uint32_t nodes) { return 16.0 * resolution * resolution * nodes >= 0x1p64; }
static int maps_fit(uint32_t resolution, uint32_t nodes) { return 16.0 * resolution * resolution * nodes < 0x1p63; }

/* -------------------------------------------------------------- atlas */

typedef struct fz_image {
    float *depth, *normal, *color;
    size_t pixels;
} fz_image;

static float *copy_floats(const float *a, size_t n)
{
    float *b;
    if (!a) return NULL;
    b = (float *)malloc(n * sizeof(float) + 1);
    FZ_REQUIRE(b != NULL, "out of memory (harness)");
    memcpy(b, a, n * sizeof(float));
    return b;
}

static void image_save(fz_image *im, const mlod_atlas *a)
{
    im->pixels = (size_t)a->width * a->height;
    im->depth = copy_floats(a->depth, im->pixels);
    im->normal = copy_floats(a->normal, 3 * im->pixels);
    im->color = copy_floats(a->color, 3 * im->pixels);
}

static void image_free(fz_image *im)
{
    free(im->depth);
    free(im->normal);
    free(im->color);
    memset(im, 0, sizeof *im);
}

static int image_same(const fz_image *im, const mlod_atlas *a)
{
    return !memcmp(im->depth, a->depth, im->pixels * sizeof(float)) &&
           (!a->normal || !memcmp(im->normal, a->normal, 3 * im->pixels * sizeof(float))) &&
           (!a->color || !memcmp(im->color, a->color, 3 * im->pixels * sizeof(float)));
}

/* The view whose tile holds pixel `at`, or -1 outside every tile. */
static int32_t tile_of(const mlod_atlas *a, size_t at)
{
    uint32_t x = (uint32_t)(at % a->width), y = (uint32_t)(at / a->width), cell, v;
    cell = (y / a->cell_height) * a->columns + x / a->cell_width;
    for (v = 0; v < a->view_count; v++) { /* the cell's view: the one whose tile starts in it */
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        if (t[0] / a->cell_width + (t[1] / a->cell_height) * a->columns != cell) continue;
        return x >= t[0] && x < t[0] + t[2] && y >= t[1] && y < t[1] + t[3] ? (int32_t)v : -1;
    }
    return -1;
}

/* Pixels outside every tile equal those saved. */
static void check_outside_tiles(const mlod_atlas *a, const fz_image *im, const char *when)
{
    size_t i;
    for (i = 0; i < im->pixels; i++) {
        if (tile_of(a, i) >= 0) continue;
        FZ_REQUIRE(!memcmp(&im->depth[i], &a->depth[i], 4) && (!a->normal || !memcmp(im->normal + 3 * i, a->normal + 3 * i, 12)) &&
                       (!a->color || !memcmp(im->color + 3 * i, a->color + 3 * i, 12)),
                   "%s: pixel %zu, outside every tile, changed", when, i);
    }
}

/* Something in every pixel, so that what a call leaves shows. */
static void paint(mlod_atlas *a, uint64_t seed)
{
    size_t i, n = (size_t)a->width * a->height;
    for (i = 0; i < n; i++) {
        uint64_t h = (seed + i) * 0x9e3779b97f4a7c15ull;
        float value = (float)((h >> 40) % 1000) * 0.25f;
        a->depth[i] = (h >> 60) < 4 ? INFINITY : value;
        if (a->normal) a->normal[3 * i] = a->normal[3 * i + 1] = a->normal[3 * i + 2] = -value;
        if (a->color) a->color[3 * i] = a->color[3 * i + 1] = a->color[3 * i + 2] = value + 1.0f;
    }
}

/* Create an atlas with the counter: an injected failure is tried again;
   NULL when the allocator refused it (the cap) or the desc is refused. */
static mlod_atlas *create_atlas(fz_ctx *c, const mlod_view *views, uint32_t count, const mlod_atlas_desc *desc,
                                const char *what)
{
    int tries;
    for (tries = 0;; tries++) {
        fz_mark k = fz_mark_now(&c->mem);
        mlod_atlas *a = (mlod_atlas *)&k;
        mlod_error e;
        mlod_result res = mlod_atlas_create(views, count, desc, &c->alloc, &a, &e);
        if (res == MLOD_OK) {
            FZ_REQUIRE(a->bytes == c->mem.live - k.live && a->bytes == mlod_atlas_bound(views, count, desc),
                       "%s: the atlas reports %zu bytes, holds %zu, mlod_atlas_bound %zu", what, a->bytes,
                       c->mem.live - k.live, mlod_atlas_bound(views, count, desc));
            return a;
        }
        fz_where = what;
        check_error(res, &e);
        FZ_REQUIRE(a == NULL, "%s: mlod_atlas_create failed but left *out set", what);
        fz_holds_as_before(&c->mem, &k, what);
        FZ_REQUIRE(res == MLOD_ERROR_OUT_OF_MEMORY && fz_refused(&c->mem, &k), "%s: mlod_atlas_create refused valid views: %s",
                   what, e.message);
        FZ_NOTE("fuzz: %s: %s\n", what, e.message);
        if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) return NULL;
    }
}

/* ---------------------------------------------------------- reference */

/* The per-view render with delta = 0: each view's basic cut of its
   MegaViews view; without directions mlod_splat, with them its drawn nodes
   that the view's field of view does not cull, drawn in order as
   mlod_splat draws them (tests/mv_reference.h).  The
   drawn nodes counted into *drawn. */
static int reference_render(mlod_atlas *ref, const mlod_tree *scene, const mlod_view *vs, const fz_views *v,
                            float epsilon, uint64_t *drawn)
{
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_error e;
    uint32_t i;
    memset(&cp, 0, sizeof cp);
    cp.epsilon = epsilon;
    cp.mode = MLOD_CUT_BASIC;
    FZ_REQUIRE(mlod_cut_create(v->count, NULL, &cut, &e) == MLOD_OK && mlod_cut_update(cut, scene, vs, &cp, &e) == MLOD_OK,
               "the per-view reference's cut failed: %s", e.message);
    *drawn = 0;
    for (i = 0; i < v->count; i++) {
        mlod_cut_view cv = mlod_cut_get(cut, i);
        *drawn += cv.drawn + cv.oversize;
    }
    if (!v->set.directions) {
        FZ_REQUIRE(mlod_splat(ref, scene, cut, vs, NULL, &e) == MLOD_OK, "the per-view reference's splat failed: %s",
                   e.message);
        mlod_cut_destroy(cut);
        return 1;
    }
    *drawn = 0;
    for (i = 0; i < v->count; i++) {
        FZ_REQUIRE(mlod_view_check(&vs[i], &e) == MLOD_OK, "the reference's view %u: %s", i, e.message);
        *drawn += mvref_draw_view(ref, scene, &vs[i], i, mlod_cut_get(cut, i), v->eye[i], v->direction[i], v->fov[i]);
    }
    mlod_cut_destroy(cut);
    return 1;
}

/* Tiles of a and b equal bit for bit; the first pixel that differs.  A
   pixel of equal depth bits whose channels differ is an exact depth tie
   (the manual's one exception to delta 0's equality: both atlases' nodes
   lie at that depth, as check_drawn checks of each), counted in *ties. */
static int same_tiles(const mlod_atlas *a, const mlod_atlas *b, uint32_t *view, uint32_t *x, uint32_t *y,
                      uint64_t *ties)
{
    uint32_t i, row, col;
    for (i = 0; i < a->view_count; i++) {
        const uint32_t *ta = a->tiles + 4 * (size_t)i, *tb = b->tiles + 4 * (size_t)i;
        for (row = 0; row < ta[3]; row++)
            for (col = 0; col < ta[2]; col++) {
                size_t pa = ((size_t)ta[1] + row) * a->width + ta[0] + col, pb = ((size_t)tb[1] + row) * b->width + tb[0] + col;
                int same_depth = memcmp(a->depth + pa, b->depth + pb, 4) == 0;
                if (same_depth && ((a->normal && memcmp(a->normal + 3 * pa, b->normal + 3 * pb, 12)) ||
                                   (a->color && memcmp(a->color + 3 * pa, b->color + 3 * pb, 12)))) {
                    (*ties)++;
                    continue;
                }
                if (!same_depth) {
                    *view = i;
                    *x = col;
                    *y = row;
                    return 0;
                }
            }
    }
    return 1;
}

static size_t pixel_of(const mlod_atlas *a, uint32_t view, uint32_t x, uint32_t y)
{
    const uint32_t *t = a->tiles + 4 * (size_t)view;
    return ((size_t)t[1] + y) * a->width + t[0] + x;
}

/* ------------------------------------------------------- hole filling */

/* mlod_atlas_fill_holes, checked: a failure changes nothing and holds
   nothing (an injected one is tried again); drawn pixels keep their bits;
   every other tile pixel is the pull-push of a double reference, within
   1e-5 of the tile's largest value; pixels outside tiles keep theirs; a
   second call changes nothing. */
static void fill_holes(fz_ctx *c, mlod_atlas *a, const char *when)
{
    fz_image before, after;
    uint32_t values = 1 + (a->normal ? 3u : 0u) + (a->color ? 3u : 0u), stride = values + 1, v;
    mlod_error e;
    mlod_result res;
    int tries;
    image_save(&before, a);
    for (tries = 0;; tries++) {
        fz_mark k = fz_mark_now(&c->mem);
        res = mlod_atlas_fill_holes(a, c->parallel, &e);
        if (res == MLOD_OK) break;
        fz_where = "mlod_atlas_fill_holes";
        check_error(res, &e);
        FZ_REQUIRE(res == MLOD_ERROR_OUT_OF_MEMORY && fz_refused(&c->mem, &k), "%s: mlod_atlas_fill_holes: %s", when,
                   e.message);
        FZ_REQUIRE(image_same(&before, a), "%s: mlod_atlas_fill_holes failed but changed the atlas", when);
        fz_holds_as_before(&c->mem, &k, "mlod_atlas_fill_holes");
        if (!fz_injected(&c->mem, &k) || tries > 1) {
            image_free(&before);
            return;
        }
    }
    check_outside_tiles(a, &before, when);
    for (v = 0; v < a->view_count; v++) {
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        uint32_t w = t[2], h = t[3], lw[40], lh[40], levels = 0, l, x, y, q;
        double *level[40], largest[7] = {0, 0, 0, 0, 0, 0, 0};
        level[0] = (double *)calloc((size_t)w * h * stride, sizeof(double));
        FZ_REQUIRE(level[0] != NULL, "out of memory (harness)");
        lw[0] = w;
        lh[0] = h;
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++) {
                size_t at = pixel_of(a, v, x, y);
                double *p = level[0] + ((size_t)y * w + x) * stride;
                if (!isfinite(before.depth[at])) continue;
                p[0] = 1.0;
                p[1] = before.depth[at];
                for (q = 0; q < 3 && a->normal; q++) p[2 + q] = before.normal[3 * at + q];
                for (q = 0; q < 3 && a->color; q++) p[2 + (a->normal ? 3 : 0) + q] = before.color[3 * at + q];
                for (q = 0; q < values; q++)
                    if (fabs(p[1 + q]) > largest[q]) largest[q] = fabs(p[1 + q]);
            }
        while (lw[levels] > 1 || lh[levels] > 1) { /* pull: means of the non-empty children */
            uint32_t cw = (lw[levels] + 1) / 2, ch = (lh[levels] + 1) / 2, dx, dy;
            double *up = (double *)calloc((size_t)cw * ch * stride, sizeof(double));
            FZ_REQUIRE(up != NULL, "out of memory (harness)");
            for (y = 0; y < ch; y++)
                for (x = 0; x < cw; x++) {
                    double *p = up + ((size_t)y * cw + x) * stride;
                    for (dy = 0; dy < 2; dy++)
                        for (dx = 0; dx < 2; dx++) {
                            const double *s;
                            if (2 * x + dx >= lw[levels] || 2 * y + dy >= lh[levels]) continue;
                            s = level[levels] + ((size_t)(2 * y + dy) * lw[levels] + 2 * x + dx) * stride;
                            if (s[0] == 0.0) continue;
                            p[0] += 1.0;
                            for (q = 1; q < stride; q++) p[q] += s[q];
                        }
                    if (p[0] > 0.0) {
                        for (q = 1; q < stride; q++) p[q] /= p[0];
                        p[0] = 1.0;
                    }
                }
            levels++;
            level[levels] = up;
            lw[levels] = cw;
            lh[levels] = ch;
        }
        for (l = levels; l-- > 0;) /* push: empty pixels take their parent's value */
            for (y = 0; y < lh[l]; y++)
                for (x = 0; x < lw[l]; x++) {
                    double *p = level[l] + ((size_t)y * lw[l] + x) * stride;
                    const double *parent = level[l + 1] + ((size_t)(y / 2) * lw[l + 1] + x / 2) * stride;
                    if (p[0] == 0.0 && parent[0] != 0.0) memcpy(p + 1, parent + 1, values * sizeof(double)), p[0] = -1.0;
                }
        for (y = 0; y < h; y++)
            for (x = 0; x < w; x++) {
                size_t at = pixel_of(a, v, x, y);
                const double *p = level[0] + ((size_t)y * w + x) * stride;
                float got[7];
                got[0] = a->depth[at];
                for (q = 0; q < 3 && a->normal; q++) got[1 + q] = a->normal[3 * at + q];
                for (q = 0; q < 3 && a->color; q++) got[1 + (a->normal ? 3 : 0) + q] = a->color[3 * at + q];
                if (p[0] > 0.0) { /* drawn: its bits */
                    FZ_REQUIRE(!memcmp(&a->depth[at], &before.depth[at], 4) &&
                                   (!a->normal || !memcmp(a->normal + 3 * at, before.normal + 3 * at, 12)) &&
                                   (!a->color || !memcmp(a->color + 3 * at, before.color + 3 * at, 12)),
                               "%s: hole filling changed drawn pixel (%u, %u) of view %u", when, x, y, v);
                } else if (p[0] == 0.0) { /* a tile with nothing drawn */
                    FZ_REQUIRE(got[0] == INFINITY, "%s: hole filling drew %g into pixel (%u, %u) of empty view %u", when,
                               (double)got[0], x, y, v);
                } else {
                    for (q = 0; q < values; q++)
                        FZ_REQUIRE(fabs(got[q] - p[1 + q]) <= 1e-5 * largest[q] + 1e-30,
                                   "%s: hole filling gave value %u of pixel (%u, %u) of view %u (%u x %u) %.9g, the "
                                   "pull-push reference %.9g",
                                   when, q, x, y, v, w, h, (double)got[q], p[1 + q]);
                }
            }
        for (l = 0; l <= levels; l++) free(level[l]);
    }
    image_save(&after, a);
    res = mlod_atlas_fill_holes(a, c->parallel, &e);
    FZ_REQUIRE(res != MLOD_OK || image_same(&after, a), "%s: a second mlod_atlas_fill_holes changed the atlas", when);
    image_free(&after);
    image_free(&before);
}

/* Atlases of 1 .. 8 perspective views of 1 .. 40 pixels a side (any
   channels, columns, a reversed order), pixels drawn at random with
   values of any sign up to 1e30: hole filling, checked. */
static void fill_other(fz_ctx *c)
{
    fz_reader *r = &c->r;
    mlod_view views[FZ_FILL_VIEWS];
    uint32_t order[FZ_FILL_VIEWS], n = 1 + rd_u8(r) % FZ_FILL_VIEWS, i, x, y;
    mlod_atlas_desc desc;
    mlod_atlas *a;
    uint8_t density = rd_u8(r), form = rd_u8(r);
    memset(&desc, 0, sizeof desc);
    desc.channels = form & 3u;
    desc.columns = (form >> 2) % 4;
    for (i = 0; i < n; i++) {
        memset(&views[i], 0, sizeof views[i]);
        views[i].kind = MLOD_VIEW_PERSPECTIVE;
        views[i].forward[2] = 1.0f;
        views[i].up[1] = 1.0f;
        views[i].width = 1 + rd_u8(r) % FZ_FILL_SIDE;
        views[i].height = 1 + rd_u8(r) % FZ_FILL_SIDE;
        views[i].fov_y = 1.0f;
        views[i].near_plane = 0.1f;
        views[i].far_plane = INFINITY;
        order[i] = n - 1 - i;
    }
    if (form & 0x10) desc.order = order;
    a = create_atlas(c, views, n, &desc, "mlod_atlas_create (hole filling)");
    if (!a) return;
    for (i = 0; i < n; i++)
        for (y = 0; y < views[i].height; y++)
            for (x = 0; x < views[i].width; x++) {
                size_t at = pixel_of(a, i, x, y);
                int k, scale = (int)(rd_u8(r) % 100) - 40;
                if (rd_u8(r) >= density) continue;
                a->depth[at] = (float)ldexp(rd_signed(r), scale);
                for (k = 0; k < 3 && a->normal; k++) a->normal[3 * at + k] = (float)rd_signed(r);
                for (k = 0; k < 3 && a->color; k++) a->color[3 * at + k] = (float)ldexp(rd_unit(r), scale);
            }
    fill_holes(c, a, "hole filling of random tiles");
    FZ_NOTE("fuzz: hole filling of %u random tiles checked\n", n);
    mlod_atlas_destroy(a);
}

/* ------------------------------------------------------------ frames */

/* The fused render's statistics add up. */
static void check_stats(const mlod_megaviews_stats *st, const mlod_tree *scene, uint32_t views, const char *what)
{
    FZ_REQUIRE(st->pairs >= st->leaf_draws + st->shared_draws + st->culled && st->shared_leaves <= st->shared_draws &&
                   st->shared_views >= 2 * st->shared_draws && st->node_pairs <= st->pairs &&
                   st->node_pairs <= scene->node_count && st->levels == mlod__depth_of(2 * (uint64_t)views - 2) + 1,
               "%s: statistics do not add up: pairs %llu, culled %llu, shared draws %llu (views %llu, leaves %llu), "
               "leaf draws %llu, node pairs %llu (scene nodes %u), levels %u for %u views",
               what, (unsigned long long)st->pairs, (unsigned long long)st->culled, (unsigned long long)st->shared_draws,
               (unsigned long long)st->shared_views, (unsigned long long)st->shared_leaves,
               (unsigned long long)st->leaf_draws, (unsigned long long)st->node_pairs, scene->node_count, st->levels,
               views);
}

/* Every drawn pixel of the tiles (views: the atlas's): a node with its
   cone axis as normal, at its distance from the view's eye (sphere discs),
   or (tangent discs) at the depth measured along the pixel's ray
   (mlod__remeasure: where the fusion of an ancestor's pixel and the view's
   own draw agree), within the sphere's range of distances; empty ones
   have channels 0. */
static void check_drawn(const mlod_atlas *a, const mlod_view *views, const mlod_tree *scene, const mlod_view_tree *vt,
                        const char *what)
{
    uint32_t v, x, y, leaf_of[FZ_MAX_VIEWS];
    int tangent = mlod__splat_tangent(a->splat, scene);
    for (v = 0; v < vt->view_count; v++) leaf_of[vt->eyes->leaf_sources[v]] = v;
    for (v = 0; v < a->view_count; v++) {
        const uint32_t *t = a->tiles + 4 * (size_t)v;
        const float *eye = vt->eyes->spheres + 4 * (size_t)(vt->eyes->leaf_count - 1 + leaf_of[v]);
        mlod__pview pv;
        FZ_REQUIRE(mlod__view_prepare(&views[v], &pv, NULL) == MLOD_OK, "%s: view %u does not prepare", what, v);
        for (y = 0; y < t[3]; y++)
            for (x = 0; x < t[2]; x++) {
                size_t at = pixel_of(a, v, x, y);
                float d = a->depth[at];
                FZ_REQUIRE(!isnan(d) && d >= 0.0f, "%s: view %u pixel (%u, %u) has depth %g", what, v, x, y, (double)d);
                if (d == INFINITY) {
                    FZ_REQUIRE((!a->normal || (a->normal[3 * at] == 0.0f && a->normal[3 * at + 1] == 0.0f &&
                                               a->normal[3 * at + 2] == 0.0f)) &&
                                   (!a->color || (a->color[3 * at] == 0.0f && a->color[3 * at + 1] == 0.0f &&
                                                  a->color[3 * at + 2] == 0.0f)),
                               "%s: view %u pixel (%u, %u) is empty with channels not 0", what, v, x, y);
                    continue;
                }
                if (a->color) {
                    float id = a->color[3 * at];
                    uint32_t node = (uint32_t)id, k;
                    double dist2 = 0.0, dist;
                    const float *s;
                    FZ_REQUIRE(id >= 0.0f && id < (float)scene->node_count && (float)node == id,
                               "%s: view %u pixel (%u, %u) holds colour %g, no node of %u", what, v, x, y, (double)id,
                               scene->node_count);
                    s = scene->spheres + 4 * (size_t)node;
                    for (k = 0; k < 3; k++) dist2 += ((double)s[k] - eye[k]) * ((double)s[k] - eye[k]);
                    dist = sqrt(dist2);
                    if (tangent) {
                        float m = mlod__remeasure(&pv, scene, node, x, y, 1);
                        double r = s[3];
                        FZ_REQUIRE(d == m && d >= (dist - r) * (1.0 - 1e-6) - 1e-37 && d <= (dist + r) * (1.0 + 1e-6) + 1e-37,
                                   "%s: view %u pixel (%u, %u) holds node %u at depth %.9g: measured along its ray "
                                   "%.9g, the sphere's distances %.9g to %.9g",
                                   what, v, x, y, node, (double)d, (double)m, dist - r, dist + r);
                    } else
                        FZ_REQUIRE(fabs(d - dist) <= 1e-6 * dist + 1e-37,
                                   "%s: view %u pixel (%u, %u) holds node %u at depth %.9g, its distance from the eye %.9g",
                                   what, v, x, y, node, (double)d, dist);
                    if (a->normal)
                        FZ_REQUIRE(!memcmp(a->normal + 3 * at, scene->cones + 4 * (size_t)node, 12),
                                   "%s: view %u pixel (%u, %u): the normal is not node %u's cone axis", what, v, x, y,
                                   node);
                }
            }
    }
}

/* A render's outcome: refused (parameters first, then a mismatched atlas:
   untouched), over size_t (untouched), out of memory (only where the
   allocator refused: tiles empty), holding nothing more either way. */
static void check_failed_render(fz_ctx *c, const fz_params *fp, uint32_t view_nodes, mlod_result res,
                                const mlod_error *e, const fz_mark *k, const mlod_atlas *a, const fz_image *before,
                                int mismatch, const char *what)
{
    fz_where = what;
    check_error(res, e);
    fz_holds_as_before(&c->mem, k, what);
    if (fp->bad) {
        mlod_error e2;
        FZ_REQUIRE(res == mlod_megaviews_check(&fp->p, &e2), "%s: %s, mlod_megaviews_check %s", what,
                   mlod_result_name(res), mlod_result_name(e2.code));
    } else if (res == MLOD_ERROR_MISMATCH) {
        FZ_REQUIRE(mismatch, "%s: MLOD_ERROR_MISMATCH for a matching atlas: %s", what, e->message);
    } else if (res == MLOD_ERROR_OVERFLOW) {
        FZ_REQUIRE(!maps_fit(fp->p.resolution, view_nodes), "%s: MLOD_ERROR_OVERFLOW at resolution %u: %s", what,
                   fp->p.resolution, e->message);
    } else {
        FZ_REQUIRE(res == MLOD_ERROR_OUT_OF_MEMORY && fz_refused(&c->mem, k), "%s failed: %s (%s)", what,
                   mlod_result_name(res), e->message);
    }
    if (!a) return;
    if (res != MLOD_ERROR_OUT_OF_MEMORY) {
        FZ_REQUIRE(image_same(before, a), "%s refused the call (%s) but changed the atlas", what, mlod_result_name(res));
    } else {
        uint32_t v, x, y;
        check_outside_tiles(a, before, what);
        for (v = 0; v < a->view_count; v++)
            for (y = 0; y < a->tiles[4 * (size_t)v + 3]; y++)
                for (x = 0; x < a->tiles[4 * (size_t)v + 2]; x++) {
                    size_t at = pixel_of(a, v, x, y);
                    FZ_REQUIRE(a->depth[at] == INFINITY && (!a->normal || !a->normal[3 * at]) && (!a->color || !a->color[3 * at]),
                               "%s ran out of memory but view %u pixel (%u, %u) is not empty", what, v, x, y);
                }
    }
}

/* The render's own variants (private, as tests/test_megaviews.c calls
   them): walks of the view subtrees from any level (past the last: level
   by level), a first list room from 1, descents of any room, the exact
   path instead of the float filter: the same atlas and statistics, the
   peak within mlod__mv_bound for that walk level and room. */
static void walk_variant(fz_ctx *c, const fz_params *fp, const mlod_view_tree *vt, mlod_atlas *a,
                         const mlod_megaviews_stats *st)
{
    fz_reader *r = &c->r;
    uint32_t level = rd_u8(r) % (st->levels + 2), descend = rd_u8(r) % 40;
    if (descend < 4) descend = 0; /* 0: the default; else 4 .. 39 (4 at least) */
    size_t room = rd_u8(r) < 128 ? 1 + rd_u8(r) % 64 : MLOD__MV_WALK_ROOM, peak;
    int exact = rd_u8(r) & 1, tries;
    fz_image with;
    mlod_megaviews_stats st3;
    mlod_error e;
    mlod_result res;
    fz_mark k;
    image_save(&with, a);
    for (tries = 0;; tries++) {
        k = fz_mark_now(&c->mem);
        res = mlod__megaviews_run(a, NULL, c->scene, vt, &fp->p, level, room, descend, exact, &st3, &e);
        if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) break;
    }
    FZ_REQUIRE(res == MLOD_OK, "render walking from level %u (room %zu, descent room %u, exact %d): %s", level, room,
               descend, exact, e.message);
    peak = fp->uncounted ? st3.peak_bytes : fz_peak(&c->mem, &k);
    FZ_REQUIRE(image_same(&with, a) && st3.pairs == st->pairs && st3.culled == st->culled &&
                   st3.shared_draws == st->shared_draws && st3.shared_views == st->shared_views &&
                   st3.shared_leaves == st->shared_leaves && st3.leaf_draws == st->leaf_draws &&
                   st3.node_pairs == st->node_pairs && st3.levels == st->levels,
               "the render walking from level %u (room %zu, descent room %u, exact %d) differs from the public one "
               "(pairs %llu / %llu, shared draws %llu / %llu)",
               level, room, descend, exact, (unsigned long long)st3.pairs, (unsigned long long)st->pairs,
               (unsigned long long)st3.shared_draws, (unsigned long long)st->shared_draws);
    FZ_REQUIRE(st3.peak_bytes == peak && peak <= mlod__mv_bound(vt->eyes, fp->p.resolution, st3.node_pairs, level, room),
               "the render walking from level %u (room %zu): peak %zu bytes (reported %zu), mlod__mv_bound %.0f", level,
               room, peak, st3.peak_bytes, mlod__mv_bound(vt->eyes, fp->p.resolution, st3.node_pairs, level, room));
    image_free(&with);
}

/* Render the maps and query them: against the fused atlas `a` (rendered
   with the same parameters, stats `fused`; NULL: none to compare). */
static void run_maps(fz_ctx *c, const fz_params *fp, const fz_views *v, const mlod_view_tree *vt,
                     const mlod_view_tree *other, const mlod_atlas *a, const mlod_megaviews_stats *fused)
{
    fz_reader *r = &c->r;
    mlod_megaviews_params p = fp->p;
    mlod_megaviews_maps *maps;
    mlod_megaviews_stats st;
    mlod_error e;
    mlod_result res;
    uint32_t R = p.resolution, tries, q, queries;
    uint64_t pixels;
    fz_mark k;
    p.allocator = &c->alloc;
    for (tries = 0;; tries++) {
        k = fz_mark_now(&c->mem);
        maps = (mlod_megaviews_maps *)&k;
        res = mlod_megaviews_render_maps(c->scene, vt, &p, &maps, &st, &e);
        if (res == MLOD_OK) break;
        FZ_REQUIRE(maps == NULL, "mlod_megaviews_render_maps failed but left *out set");
        check_failed_render(c, fp, vt->eyes->node_count, res, &e, &k, NULL, NULL, 0, "mlod_megaviews_render_maps");
        FZ_REQUIRE(!maps_overflow(R, vt->eyes->node_count) || res == MLOD_ERROR_OVERFLOW || fp->bad,
                   "mlod_megaviews_render_maps: %s, not MLOD_ERROR_OVERFLOW, for maps beyond size_t (resolution %u)",
                   mlod_result_name(res), R);
        FZ_NOTE("fuzz: render_maps: %s\n", e.message);
        if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) return;
    }
    FZ_REQUIRE(!fp->bad, "mlod_megaviews_render_maps accepted parameters mlod_megaviews_check refuses");
    FZ_REQUIRE(maps && maps != (mlod_megaviews_maps *)&k && mlod_megaviews_maps_bytes(maps) == c->mem.live - k.live,
               "render_maps: the maps report %zu bytes, the allocator holds %zu for them", mlod_megaviews_maps_bytes(maps),
               c->mem.live - k.live);
    FZ_REQUIRE(st.peak_bytes == fz_peak(&c->mem, &k), "render_maps: stats.peak_bytes %zu, the allocator's peak %zu",
               st.peak_bytes, fz_peak(&c->mem, &k));
    check_stats(&st, c->scene, v->count, "render_maps");
    if (fused)
        FZ_REQUIRE(st.pairs == fused->pairs && st.culled == fused->culled && st.shared_draws == fused->shared_draws &&
                       st.leaf_draws == fused->leaf_draws && st.shared_views == fused->shared_views &&
                       st.shared_leaves == fused->shared_leaves && st.levels == fused->levels,
                   "render_maps: another traversal than the fused render's (pairs %llu / %llu, shared draws %llu / %llu, "
                   "leaf draws %llu / %llu)",
                   (unsigned long long)st.pairs, (unsigned long long)fused->pairs, (unsigned long long)st.shared_draws,
                   (unsigned long long)fused->shared_draws, (unsigned long long)st.leaf_draws,
                   (unsigned long long)fused->leaf_draws);
    /* queries: every pixel, or FZ_QUERIES spread over them */
    pixels = (uint64_t)v->count * 2 * R * R;
    queries = pixels < FZ_QUERIES ? (uint32_t)pixels : FZ_QUERIES;
    for (q = 0; q < queries; q++) {
        uint64_t i = pixels <= FZ_QUERIES ? q : ((uint64_t)rd_u32(r) << 16 ^ rd_u16(r)) % pixels;
        uint32_t view = (uint32_t)(i / (2 * (uint64_t)R * R)), x = (uint32_t)(i % (2 * R)), y = (uint32_t)(i / (2 * R) % R),
                 node = UINT32_MAX;
        float depth = -1.0f;
        int hit = mlod_megaviews_query(maps, c->scene, vt, view, x, y, &depth, &node);
        FZ_REQUIRE(hit == 0 || hit == 1, "mlod_megaviews_query returned %d", hit);
        FZ_REQUIRE(hit == mlod_megaviews_query(maps, c->scene, vt, view, x, y, NULL, NULL),
                   "mlod_megaviews_query differs without its outputs");
        if (hit) FZ_REQUIRE(node < c->scene->node_count && depth >= 0.0f && depth < INFINITY,
                            "mlod_megaviews_query: node %u of %u at depth %g", node, c->scene->node_count, (double)depth);
        if (!a) continue;
        {
            size_t at = pixel_of(a, view, x, y);
            FZ_REQUIRE(hit == (a->depth[at] < INFINITY),
                       "mlod_megaviews_query of view %u pixel (%u, %u): %s, the fused atlas: %g", view, x, y,
                       hit ? "drawn" : "empty", (double)a->depth[at]);
            if (hit)
                FZ_REQUIRE(!memcmp(&depth, &a->depth[at], 4) && (!a->color || (float)node == a->color[3 * at]),
                           "mlod_megaviews_query of view %u pixel (%u, %u): node %u at %.9g, the fused atlas: %g at %.9g",
                           view, x, y, node, (double)depth, a->color ? (double)a->color[3 * at] : -1.0, (double)a->depth[at]);
        }
    }
    FZ_REQUIRE(!mlod_megaviews_query(maps, c->scene, vt, v->count, 0, 0, NULL, NULL) &&
                   !mlod_megaviews_query(maps, c->scene, vt, 0, 2 * R, 0, NULL, NULL) &&
                   !mlod_megaviews_query(maps, c->scene, vt, 0, 0, R, NULL, NULL) &&
                   !mlod_megaviews_query(maps, c->scene, vt, UINT32_MAX, UINT32_MAX, UINT32_MAX, NULL, NULL) &&
                   !mlod_megaviews_query(NULL, c->scene, vt, 0, 0, 0, NULL, NULL) &&
                   !mlod_megaviews_query(maps, NULL, vt, 0, 0, 0, NULL, NULL) &&
                   !mlod_megaviews_query(maps, c->scene, NULL, 0, 0, 0, NULL, NULL),
               "mlod_megaviews_query: out of range or NULL is not 0");
    if (c->scene->node_count != 3) { /* a scene of another node count (3): 0 */
        static const float two[6] = {0, 0, 0, 1, 0, 0};
        mlod_points points;
        mlod_build_desc desc;
        mlod_tree *tiny = NULL;
        memset(&points, 0, sizeof points);
        memset(&desc, 0, sizeof desc);
        points.positions = two;
        points.count = 2;
        FZ_REQUIRE(mlod_build_points(&points, &desc, &tiny, &e) == MLOD_OK, "a scene of two points: %s", e.message);
        for (q = 0; q < 16; q++) {
            uint32_t view = rd_u8(r) % v->count, x = rd_u8(r) % (2 * R), y = rd_u8(r) % R;
            FZ_REQUIRE(!mlod_megaviews_query(maps, tiny, vt, view, x, y, NULL, NULL),
                       "mlod_megaviews_query answered for a scene of 3 nodes, the render's has %u", c->scene->node_count);
        }
        mlod_tree_destroy(tiny);
    }
    if (other) { /* a view tree of another count: 0, and nothing read out of bounds */
        for (q = 0; q < 16; q++) {
            uint32_t view = rd_u8(r) % (other->view_count + 1), x = rd_u8(r) % (2 * R), y = rd_u8(r) % R;
            FZ_REQUIRE(!mlod_megaviews_query(maps, c->scene, other, view, x, y, NULL, NULL),
                       "mlod_megaviews_query answered for a view tree of %u views, the render's has %u",
                       other->view_count, vt->view_count);
        }
    }
    FZ_NOTE("fuzz: render_maps: %zu bytes, %u queries checked%s\n", mlod_megaviews_maps_bytes(maps), queries,
            a ? " against the fused atlas" : "");
    mlod_megaviews_maps_destroy(maps);
    FZ_REQUIRE(c->mem.live == k.live && c->mem.blocks == k.blocks, "mlod_megaviews_maps_destroy left %zu bytes",
               c->mem.live - k.live);
}

/* One frame: parameters, an atlas, the fused render and its checks, the
   maps and their queries, hole filling. */
static void run_frame(fz_ctx *c, const fz_views *v, const mlod_view_tree *vt, const mlod_view_tree *other,
                      const char *when)
{
    fz_reader *r = &c->r;
    fz_params fp;
    mlod_view *views;
    mlod_atlas_desc desc;
    mlod_atlas *a = NULL;
    mlod_megaviews_stats st;
    mlod_error e;
    mlod_result res = MLOD_ERROR_INVALID_ARGUMENT;
    uint32_t order[FZ_MAX_VIEWS + 1], count, R, tile_R, i;
    uint8_t ab = rd_u8(r), cb = rd_u8(r);
    int mismatch, tries, compared = 0, oriented;
    const float *forward, *up; /* the maps' orientation for the views (NULL: the default; a refused one too) */
    fz_image before;
    parse_params(c, v->count, &fp);
    check_params(&fp);
    R = fp.p.resolution;
    FZ_NOTE("fuzz: %s: epsilon %g delta %g resolution %u flags 0x%x group_radius %g forward (%g %g %g) up (%g %g %g), "
            "%u views\n", when, (double)fp.p.epsilon, (double)fp.p.delta, R, fp.p.flags, (double)fp.p.group_radius,
            (double)fp.p.forward[0], (double)fp.p.forward[1], (double)fp.p.forward[2], (double)fp.p.up[0],
            (double)fp.p.up[1], (double)fp.p.up[2], v->count);
    /* pure helpers */
    {
        mlod_view mv = mlod_megaviews_view(v->eye[0], R, fp.p.flags);
        mlod_view mo = mlod_megaviews_view_oriented(v->eye[0], R, fp.p.flags, fp.p.forward, fp.p.up);
        int none = 1;
        FZ_REQUIRE(mv.kind == MLOD_VIEW_DUAL_PARABOLOID && mv.height == R && mv.width == (R > 0x7fffffffu ? 0u : 2 * R) &&
                       mv.flags == fp.p.flags && !memcmp(mv.position, v->eye[0], 12) && mv.forward[2] == 1.0f &&
                       mv.up[1] == 1.0f && mv.forward[0] == 0.0f && mv.forward[1] == 0.0f && mv.up[0] == 0.0f &&
                       mv.up[2] == 0.0f,
                   "mlod_megaviews_view(resolution %u): %u x %u", R, mv.width, mv.height);
        for (i = 0; i < 3; i++) none &= fp.p.forward[i] == 0.0f && fp.p.up[i] == 0.0f;
        FZ_REQUIRE(mo.kind == mv.kind && mo.width == mv.width && mo.height == mv.height && mo.flags == mv.flags &&
                       !memcmp(mo.position, mv.position, 12) &&
                       (none ? !memcmp(mo.forward, mv.forward, 12) && !memcmp(mo.up, mv.up, 12)
                             : !memcmp(mo.forward, fp.p.forward, 12) && !memcmp(mo.up, fp.p.up, 12)),
                   "mlod_megaviews_view_oriented: not mlod_megaviews_view's map with %s", none ? "no orientation"
                                                                                               : "the params' axes");
        mo = mlod_megaviews_view_oriented(NULL, 1, 0, fp.p.forward, fp.p.up); /* the axes alone */
        oriented = !none && mlod_view_check(&mo, NULL) == MLOD_OK;
        forward = oriented ? fp.p.forward : NULL;
        up = oriented ? fp.p.up : NULL;
        FZ_REQUIRE(mlod_megaviews_bound(NULL, R, 1) == 0 && mlod_megaviews_bound(vt, 0, 1) == 0 &&
                       mlod_megaviews_bound(vt, R, UINT64_MAX) == (R == 0 || R > 0x7fffffffu ? 0 : (size_t)-1),
                   "mlod_megaviews_bound(resolution %u): 0 for no views or a resolution the render refuses, "
                   "(size_t)-1 for unbounded pairs", R);
    }
    /* the atlas: the views' MegaViews views (sometimes one view more or
       less, another resolution, channels the scene lacks: mismatches) */
    count = v->count;
    if (ab < 8) count = count > 1 ? count - 1 : count + 1;
    else if (ab < 16) count++;
    tile_R = R == 0 || R > 64 ? 1 + (ab >> 4) % 8 : R;
    if ((ab & 0xf0) == 0xf0) tile_R++;
    views = (mlod_view *)malloc(sizeof(mlod_view) * (count + 1));
    FZ_REQUIRE(views != NULL, "out of memory (harness)");
    for (i = 0; i < count; i++)
        views[i] = mlod_megaviews_view_oriented(v->eye[i < v->count ? i : 0], tile_R, fp.p.flags & 1u, forward, up);
    memset(&desc, 0, sizeof desc);
    desc.channels = cb & 3u;
    if (ab >= 32) /* the channels the scene has, mostly */
        desc.channels &= (c->scene->cones ? (uint32_t)MLOD_ATLAS_NORMAL : 0u) | (c->scene->colors ? (uint32_t)MLOD_ATLAS_COLOR : 0u);
    desc.disc_scale = (cb >> 2) % 4 == 3 ? (float)((cb >> 4) % 7 + 1) / 8.0f : 0.0f;
    desc.columns = (cb >> 6) ? (cb >> 6) + 1 : 0;
    desc.splat = (ab >> 1) % 4 == 3 ? (uint32_t)MLOD_SPLAT_SPHERES : (ab >> 1) % 8 == 2 ? (uint32_t)MLOD_SPLAT_TANGENT : 0u;
    if (count == v->count && rd_u8(r) < 128) { /* the view tree's leaf order, or reversed */
        for (i = 0; i < count; i++) order[i] = (cb & 0x20) ? vt->eyes->leaf_sources[i] : count - 1 - i;
        desc.order = order;
    }
    mismatch = count != v->count || tile_R != R || ((desc.channels & MLOD_ATLAS_NORMAL) && !c->scene->cones) ||
               ((desc.channels & MLOD_ATLAS_COLOR) && !c->scene->colors) ||
               (desc.splat == MLOD_SPLAT_TANGENT && !c->scene->cones);
    a = create_atlas(c, views, count, &desc, "mlod_atlas_create (MegaViews)");
    if (a) {
        paint(a, c->hash);
        image_save(&before, a);
        if (ab % 8 == 5) { /* NULLs: refused, the atlas untouched */
            mlod_megaviews_maps *none = (mlod_megaviews_maps *)&e;
            FZ_REQUIRE(mlod_megaviews_render(NULL, c->scene, vt, &fp.p, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           mlod_megaviews_render(a, NULL, vt, &fp.p, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           mlod_megaviews_render(a, c->scene, NULL, &fp.p, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           mlod_megaviews_render(a, c->scene, vt, NULL, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           mlod_megaviews_render_maps(c->scene, vt, &fp.p, NULL, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           mlod_megaviews_render_maps(NULL, vt, &fp.p, &none, &st, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
                           none == NULL && image_same(&before, a),
                       "MegaViews calls with NULLs: not MLOD_ERROR_INVALID_ARGUMENT, or the atlas changed");
        }
        for (tries = 0;; tries++) {
            fz_mark k = fz_mark_now(&c->mem);
            res = mlod_megaviews_render(a, c->scene, vt, &fp.p, &st, &e);
            if (res == MLOD_OK) {
                size_t peak = fz_peak(&c->mem, &k), bound = mlod_megaviews_bound(vt, R, st.node_pairs);
                FZ_REQUIRE(!fp.bad && !mismatch, "mlod_megaviews_render accepted %s",
                           fp.bad ? "parameters mlod_megaviews_check refuses" : "a mismatched atlas");
                FZ_REQUIRE(e.code == MLOD_OK, "mlod_megaviews_render: success with error.code %d", (int)e.code);
                FZ_REQUIRE(c->mem.live == k.live && c->mem.blocks == k.blocks, "mlod_megaviews_render holds %zu bytes after",
                           c->mem.live - k.live);
                if (fp.uncounted) peak = st.peak_bytes;
                FZ_REQUIRE(st.peak_bytes == peak, "mlod_megaviews_render: stats.peak_bytes %zu, the allocator's peak %zu",
                           st.peak_bytes, peak);
                FZ_REQUIRE(peak <= bound && bound <= mlod_megaviews_bound(vt, R, c->scene->node_count),
                           "mlod_megaviews_render held %zu bytes, mlod_megaviews_bound %zu for %llu pairs per view node "
                           "(%zu for the scene's %u nodes)",
                           peak, bound, (unsigned long long)st.node_pairs, mlod_megaviews_bound(vt, R, c->scene->node_count),
                           c->scene->node_count);
                break;
            }
            check_failed_render(c, &fp, vt->eyes->node_count, res, &e, &k, a, &before, mismatch, "mlod_megaviews_render");
            FZ_NOTE("fuzz: render: %s\n", e.message);
            if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) break;
        }
        if (res == MLOD_OK) {
            check_stats(&st, c->scene, v->count, "mlod_megaviews_render");
            check_outside_tiles(a, &before, "mlod_megaviews_render");
            check_drawn(a, views, c->scene, vt, "mlod_megaviews_render");
            FZ_NOTE("fuzz: render: %llu pairs, %llu shared draws, %llu leaf draws, peak %zu bytes\n",
                    (unsigned long long)st.pairs, (unsigned long long)st.shared_draws,
                    (unsigned long long)st.leaf_draws, st.peak_bytes);
            if (fp.p.delta == 0.0f && fp.p.group_radius == 0.0f) { /* the per-view cut and splat */
                mlod_atlas *ref = NULL;
                uint64_t drawn = 0;
                uint32_t dv = 0, dx = 0, dy = 0, j;
                uint64_t ties = 0;
                int distinct = 1;
                for (i = 0; i < count; i++) views[i] = mlod_megaviews_view_oriented(v->eye[i], R, fp.p.flags, forward, up);
                FZ_REQUIRE(mlod_atlas_create(views, count, &desc, NULL, &ref, &e) == MLOD_OK, "the reference atlas: %s",
                           e.message);
                reference_render(ref, c->scene, views, v, fp.p.epsilon, &drawn);
                check_drawn(ref, views, c->scene, vt, "the per-view cut and splat");
                if (!same_tiles(a, ref, &dv, &dx, &dy, &ties)) {
                    size_t pa = pixel_of(a, dv, dx, dy), pr = pixel_of(ref, dv, dx, dy);
                    FZ_REQUIRE(0,
                               "delta 0: view %u pixel (%u, %u) differs from the per-view cut and splat: depth %.9g, "
                               "normal (%g %g %g), colour %g; per view depth %.9g, normal (%g %g %g), colour %g",
                               dv, dx, dy, (double)a->depth[pa], a->normal ? (double)a->normal[3 * pa] : 0.0,
                               a->normal ? (double)a->normal[3 * pa + 1] : 0.0, a->normal ? (double)a->normal[3 * pa + 2] : 0.0,
                               a->color ? (double)a->color[3 * pa] : -1.0, (double)ref->depth[pr],
                               ref->normal ? (double)ref->normal[3 * pr] : 0.0, ref->normal ? (double)ref->normal[3 * pr + 1] : 0.0,
                               ref->normal ? (double)ref->normal[3 * pr + 2] : 0.0, ref->color ? (double)ref->color[3 * pr] : -1.0);
                }
                for (i = 0; i < count && distinct; i++)
                    for (j = 0; j < i && distinct; j++) distinct = memcmp(v->eye[i], v->eye[j], 12) != 0;
                if (distinct)
                    FZ_REQUIRE(st.shared_draws == 0 && st.leaf_draws == drawn,
                               "delta 0, distinct eyes: %llu shared draws, %llu leaf draws, the per-view cuts draw %llu",
                               (unsigned long long)st.shared_draws, (unsigned long long)st.leaf_draws,
                               (unsigned long long)drawn);
                mlod_atlas_destroy(ref);
                compared = 1;
                FZ_NOTE("fuzz: delta 0: the per-view cut and splat, %llu drawn nodes, equal (%llu pixels of exact depth "
                        "ties)\n", (unsigned long long)drawn, (unsigned long long)ties);
            }
            { /* again: without the hook (the same atlas and statistics), or without statistics */
                fz_image with;
                mlod_megaviews_params p = fp.p;
                mlod_megaviews_stats st2;
                fz_mark k;
                image_save(&with, a);
                p.parallel = NULL;
                k = fz_mark_now(&c->mem);
                res = mlod_megaviews_render(a, c->scene, vt, &p, c->parallel ? &st2 : NULL, &e);
                if (res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) /* the failing allocation: again */
                    res = mlod_megaviews_render(a, c->scene, vt, &p, c->parallel ? &st2 : NULL, &e);
                FZ_REQUIRE(res == MLOD_OK, "render again: %s", e.message);
                FZ_REQUIRE(image_same(&with, a), "mlod_megaviews_render differs %s",
                           c->parallel ? "with and without the hook" : "with stats and without");
                st2.peak_bytes = st.peak_bytes; /* the allocator's: the same, or the injected failure's */
                FZ_REQUIRE(!c->parallel || !memcmp(&st, &st2, sizeof st),
                           "mlod_megaviews_render's statistics differ with and without the hook");
                image_free(&with);
            }
            if (rd_u8(r) < 128) walk_variant(c, &fp, vt, a, &st);
        }
        image_free(&before);
    }
    run_maps(c, &fp, v, vt, other, a && res == MLOD_OK && a->disc_scale == 1.0f && a->splat != MLOD_SPLAT_SPHERES ? a : NULL,
             a && res == MLOD_OK ? &st : NULL);
    if (a && res == MLOD_OK) fill_holes(c, a, "hole filling of a MegaViews atlas");
    FZ_NOTE("fuzz: %s done%s\n", when, compared ? " (compared with the per-view path)" : "");
    mlod_atlas_destroy(a);
    free(views);
}

/* ----------------------------------------------------------- refit */

/* Moved views: refit allocates nothing, succeeds for valid sets of the
   same count and kind, else leaves the tree as it was. */
static int refit(fz_ctx *c, mlod_view_tree *vt, const fz_views *moved)
{
    const mlod_tree *eyes = vt->eyes;
    size_t nodes = eyes->node_count;
    float *spheres = copy_floats(eyes->spheres, 4 * nodes), *cones = copy_floats(eyes->cones, 4 * nodes),
          *fovs = copy_floats(vt->half_fovs, 2 * nodes), *floors = copy_floats(vt->floors, 2 * nodes);
    fz_mark k = fz_mark_now(&c->mem);
    mlod_error e;
    mlod_result res = mlod_view_tree_refit(vt, &moved->set, c->parallel, &e);
    int ok = moved->valid && moved->count == vt->view_count && !moved->set.directions == !vt->half_fovs;
    FZ_REQUIRE(c->mem.calls == k.calls, "mlod_view_tree_refit allocated");
    FZ_NOTE("fuzz: refit to moved views: %s\n", res == MLOD_OK ? "done" : e.message);
    if (res == MLOD_OK) {
        FZ_REQUIRE(ok, "mlod_view_tree_refit accepted an invalid or mismatched view set");
        check_view_tree(vt, moved, "after refit");
    } else {
        fz_where = "mlod_view_tree_refit";
        check_error(res, &e);
        FZ_REQUIRE(!ok, "mlod_view_tree_refit refused a valid view set: %s", e.message);
        FZ_REQUIRE(!memcmp(spheres, eyes->spheres, 16 * nodes) && (!cones || !memcmp(cones, eyes->cones, 16 * nodes)) &&
                       (!fovs || !memcmp(fovs, vt->half_fovs, 8 * nodes)) && (!floors || !memcmp(floors, vt->floors, 8 * nodes)),
                   "mlod_view_tree_refit failed (%s) but changed the tree", mlod_result_name(res));
    }
    free(spheres);
    free(cones);
    free(fovs);
    free(floors);
    return res == MLOD_OK;
}

/* ----------------------------------------------------------- sampling */

/* mlod_sample on hostile arguments: refused exactly as documented, with
   the outputs untouched; otherwise samples in the domain with finite
   weights >= 0, 0 where the importance is (everywhere where it all is),
   the inverse transform's F / f exactly; the same with the reversed hook;
   the allocator's peak is mlod_sample_bound. */
static void check_sample(fz_ctx *c)
{
    static float importance[FZ_SAMPLE_DOMAIN];
    static uint32_t samples[FZ_SAMPLE_COUNT], again[FZ_SAMPLE_COUNT];
    static float weights[FZ_SAMPLE_COUNT], again_weights[FZ_SAMPLE_COUNT];
    fz_reader *r = &c->r;
    uint8_t form = rd_u8(r), zeros = rd_u8(r), nulls = rd_u8(r);
    uint32_t d = 1 + rd_u16(r) % FZ_SAMPLE_DOMAIN, n = 1 + rd_u16(r) % FZ_SAMPLE_COUNT, j;
    mlod_sample_params p;
    mlod_parallel reverse = {fz_run_reverse, NULL};
    mlod_result res, expected = MLOD_OK;
    mlod_error e;
    double total = 0.0, largest = 0.0, smallest = INFINITY, ratio;
    int known, faults = 0, tries;
    fz_mark k;
    memset(&p, 0, sizeof p);
    p.method = (mlod_sampler)(form & 1);
    p.chain_length = (form & 2) ? rd_u8(r) % 65 : 0;
    p.seed = rd_u32(r);
    p.allocator = &c->alloc;
    p.parallel = c->parallel;
    if (rd_hostile(r)) p.method = (mlod_sampler)(rd_u8(r) < 128 ? 2 + rd_u8(r) % 3 : (int)rd_u32(r));
    if (rd_hostile(r)) d = 0;
    if (rd_hostile(r)) n = 0;
    known = p.method == MLOD_SAMPLER_INVERSE_TRANSFORM || p.method == MLOD_SAMPLER_METROPOLIS;
    for (j = 0; j < d; j++) {
        /* a range of 2^40, or (rarely) denormals to FLT_MAX: the weights' range */
        int scale = (form & 4) ? -(int)(rd_u8(r) % ((form & 0x30) == 0x30 ? 150 : 40)) : 0;
        importance[j] = rd_u8(r) < zeros / 2 ? 0.0f : (float)ldexp(rd_unit(r), scale);
        if ((form & 0xc8) == 0xc8 && rd_u8(r) < 4) importance[j] = FLT_MAX;
        if (rd_hostile(r)) importance[j] = rd_raw_float(r);
    }
    /* what the documentation refuses, and its code when one thing is
       wrong: NULLs, an unknown method (INVALID_ARGUMENT), D or N 0 (EMPTY),
       a non-finite importance (NON_FINITE), a negative one
       (INVALID_ARGUMENT), weights beyond float range (RANGE) */
    if (nulls < 4) faults++, expected = MLOD_ERROR_INVALID_ARGUMENT;
    if (!known) faults++, expected = MLOD_ERROR_INVALID_ARGUMENT;
    if (d == 0 || n == 0) faults++, expected = MLOD_ERROR_EMPTY;
    {
        int nonfinite = 0, negative = 0;
        for (j = 0; j < d; j++) {
            double f = importance[j];
            if (!isfinite(f)) nonfinite = 1;
            else if (f < 0.0) negative = 1;
        }
        if (nonfinite) faults++, expected = MLOD_ERROR_NON_FINITE;
        if (negative) faults++, expected = MLOD_ERROR_INVALID_ARGUMENT;
    }
    for (j = 0; j < d && !faults; j++) {
        double f = importance[j];
        total += f;
        if (f > largest) largest = f;
        if (f > 0.0 && f < smallest) smallest = f;
    }
    ratio = total > 0.0 ? (p.method == MLOD_SAMPLER_INVERSE_TRANSFORM ? total : (double)d * largest) / smallest : 0.0;
    if (!faults && ratio > 0.5 * FLT_MAX * (1.0 + 1e-9)) faults++, expected = MLOD_ERROR_RANGE;
    if ((form & 0xc0) == 0x40) c->mem.fail_at = c->mem.calls + 1; /* its table's allocation fails (once) */
    for (tries = 0;; tries++) {
        memset(samples, 0xab, sizeof samples);
        memset(weights, 0xab, sizeof weights);
        k = fz_mark_now(&c->mem);
        fz_where = "mlod_sample";
        res = mlod_sample(nulls == 0 ? NULL : importance, d, n, nulls == 1 ? NULL : &p, nulls == 2 ? NULL : samples,
                          nulls == 3 ? NULL : weights, &e);
        if (res == MLOD_OK) break;
        check_error(res, &e);
        FZ_NOTE("fuzz: mlod_sample (method %d, D %u, N %u): %s\n", (int)p.method, d, n, e.message);
        fz_holds_as_before(&c->mem, &k, "mlod_sample");
        memset(&e, 0xff, sizeof e); /* a stale error: success clears it */
        for (j = 0; j < FZ_SAMPLE_COUNT; j++)
            FZ_REQUIRE(samples[j] == 0xababababu && !memcmp(&weights[j], &samples[j], 4),
                       "mlod_sample failed (%s) and wrote sample or weight %u", mlod_result_name(res), j);
        FZ_REQUIRE(faults || ratio > 0.5 * FLT_MAX * (1.0 - 1e-9) || (res == MLOD_ERROR_OUT_OF_MEMORY && fz_refused(&c->mem, &k)),
                   "mlod_sample refused valid input (method %d, D %u, N %u): %s", (int)p.method, d, n, e.message);
        FZ_REQUIRE(faults != 1 || res == expected, "mlod_sample: %s, expected %s (%s)", mlod_result_name(res),
                   mlod_result_name(expected), e.message);
        if (!(res == MLOD_ERROR_OUT_OF_MEMORY && fz_injected(&c->mem, &k)) || tries > 1) return;
    }
    FZ_REQUIRE(!faults && e.code == MLOD_OK, "mlod_sample accepted invalid input (expected %s), error.code %d",
               mlod_result_name(expected), (int)e.code);
    FZ_REQUIRE(fz_peak(&c->mem, &k) == mlod_sample_bound(d, p.method) && c->mem.live == k.live &&
                   (p.method == MLOD_SAMPLER_INVERSE_TRANSFORM || c->mem.calls == k.calls),
               "mlod_sample held %zu bytes at most, mlod_sample_bound %zu", fz_peak(&c->mem, &k),
               mlod_sample_bound(d, p.method));
    for (j = 0; j < n; j++) {
        uint32_t s = samples[j];
        FZ_REQUIRE(s < d && isfinite(weights[j]) && weights[j] >= 0.0f, "mlod_sample: sample %u is %u of %u, weight %g", j,
                   s, d, (double)weights[j]);
        if (importance[s] == 0.0f || total == 0.0)
            FZ_REQUIRE(weights[j] == 0.0f, "mlod_sample: sample %u (importance %g, total %g) has weight %g", j,
                       (double)importance[s], total, (double)weights[j]);
        if (p.method == MLOD_SAMPLER_INVERSE_TRANSFORM && total > 0.0)
            FZ_REQUIRE(importance[s] > 0.0f && weights[j] == (float)(total / importance[s]),
                       "mlod_sample (inverse transform): sample %u of importance %g has weight %.9g, F / f = %.9g", j,
                       (double)importance[s], (double)weights[j], total / importance[s]);
    }
    p.parallel = &reverse;
    p.allocator = NULL;
    FZ_REQUIRE(mlod_sample(importance, d, n, &p, again, again_weights, &e) == MLOD_OK &&
                   !memcmp(samples, again, n * sizeof *again) && !memcmp(weights, again_weights, n * sizeof *again_weights),
               "mlod_sample differs with the reversed hook and the default allocator");
    FZ_REQUIRE(mlod_sample_bound(d, MLOD_SAMPLER_METROPOLIS) == 0 &&
                   mlod_sample_bound(d, MLOD_SAMPLER_INVERSE_TRANSFORM) == ((size_t)d + 1) * sizeof(double) &&
                   mlod_sample_bound(d, (mlod_sampler)2) == (size_t)-1,
               "mlod_sample_bound(%u): 0 for Metropolis, (D + 1) doubles, (size_t)-1 for an unknown method", d);
    FZ_NOTE("fuzz: mlod_sample (method %d, D %u, N %u) checked\n", (int)p.method, d, n);
}

/* ------------------------------------------------------------ driver */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_views views, moved;
    fz_ctx c;
    mlod_view_tree *vt = NULL, *other = NULL;
    uint64_t h = 1469598103934665603ull;
    size_t i;
    for (i = 0; i < size; i++) h = (h ^ data[i]) * 1099511628211ull;
    memset(&c, 0, sizeof c);
    c.r.data = data;
    c.r.size = size;
    c.r.state = h;
    c.hash = h;
    c.mem.cap = FZ_CAP;
    c.alloc.alloc = fz_alloc;
    c.alloc.free = fz_free;
    c.alloc.user = &c.mem;
    c.hook.run = fz_run_reverse;
    c.flags = rd_u8(&c.r);
    c.parallel = (c.flags & FZ_HOOK) ? &c.hook : NULL;
    if (c.flags & FZ_FAIL) c.mem.fail_at = 1 + rd_u8(&c.r);
    if (c.flags & FZ_HOSTILE) c.r.chaos = rd_u8(&c.r);
    c.scene = build_scene(&c);
    if (c.scene) {
        parse_views(&c, &views, NULL);
        vt = build_view_tree(&c, &views);
        if (vt) {
            /* a view tree of another count, for the queries: half the
               views, or two */
            mlod_view_set half;
            float two[6];
            memset(&half, 0, sizeof half);
            memcpy(two, views.eye[0], 12);
            memcpy(two + 3, views.eye[0], 12);
            half.eyes = views.count > 1 ? views.eyes : two;
            half.eye_stride = views.count > 1 ? views.set.eye_stride : 0;
            half.count = views.count > 1 ? views.count / 2 : 2;
            FZ_REQUIRE(mlod_view_tree_build(&half, NULL, NULL, &other, NULL) == MLOD_OK, "a view tree of half the views");
            run_frame(&c, &views, vt, other, "frame 1");
            if (rd_u8(&c.r) < 192) {
                parse_views(&c, &moved, &views);
                if (refit(&c, vt, &moved)) run_frame(&c, &moved, vt, other, "frame 2 (refitted)");
            }
            mlod_view_tree_destroy(other);
            mlod_view_tree_destroy(vt);
        }
        mlod_tree_destroy(c.scene);
    }
    fill_other(&c);
    check_sample(&c);
    FZ_REQUIRE(c.mem.live == 0 && c.mem.blocks == 0, "%lu blocks (%zu bytes) not given back", c.mem.blocks, c.mem.live);
    return 0;
}
