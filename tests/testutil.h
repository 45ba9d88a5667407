/* tests/testutil.h - helpers shared by the test programs: scene -> mesh,
   the in-order layout of a tree, views, a brute-force reference cut, a
   counting allocator and serial parallel-for hooks that run tasks out of
   order.  Include after manylods.h. */
#ifndef MANYLODS_TEST_UTIL_H
#define MANYLODS_TEST_UTIL_H

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "exact.h"
#include "../examples/scenes.h"

#define TU_PI 3.14159265358979323846

#ifdef MANYLODS_IMPLEMENTATION
/* One sphere's image in sub-projection s: mlod__image_discs with one lane
   (the splat's arithmetic); 0 when unbounded. */
static inline int tu_image_disc(const mlod__pview *pv, int s, const double *centre, double r, mlod__disc *out)
{
    int bounded;
    return mlod__image_discs(pv, s, (const double (*)[3])centre, &r, out, &bounded, 1);
}
#endif

static inline mlod_mesh tu_mesh(const scene_mesh *s)
{
    mlod_mesh m;
    memset(&m, 0, sizeof m);
    m.positions = s->positions;
    m.vertex_count = s->vertex_count;
    m.indices = s->indices;
    m.index_count = s->index_count;
    m.normals = s->normals;
    m.colors = s->colors;
    return m;
}

static inline mlod_build_desc tu_desc(uint32_t samples, uint64_t seed, uint32_t attributes)
{
    mlod_build_desc d;
    memset(&d, 0, sizeof d);
    d.sample_count = samples;
    d.seed = seed;
    d.attributes = attributes;
    return d;
}

static inline mlod_tree *tu_build(const scene_mesh *s, uint32_t samples, uint64_t seed, uint32_t attributes)
{
    mlod_mesh m = tu_mesh(s);
    mlod_build_desc d = tu_desc(samples, seed, attributes);
    mlod_tree *t = NULL;
    mlod_error e;
    if (mlod_build_mesh(&m, &d, &t, &e) != MLOD_OK) {
        fprintf(stderr, "build failed: %s\n", e.message);
        return NULL;
    }
    return t;
}

/* ------------------------------------------------------------ layout */

/* The leaves in left-to-right (in-order) order: node n covers leaf
   positions first[n] .. first[n] + count[n] - 1. */
typedef struct tu_layout {
    uint32_t leaves, nodes, max_depth;
    uint32_t *first, *count;
} tu_layout;

/* Leaves below `node` of the implicit tree of n leaves, level by level:
   the nodes below it at each depth form a range, and the leaves are the
   nodes n - 1 .. 2n - 2 (a reference for mlod__leaves_below). */
static inline uint32_t tu_leaves_below(uint64_t node, uint64_t n)
{
    uint64_t lo = node, hi = node, last = 2 * n - 2, count = 0;
    while (lo <= last) {
        uint64_t b = hi < last ? hi : last, a = lo > n - 1 ? lo : n - 1;
        if (b >= a) count += b - a + 1;
        lo = 2 * lo + 1;
        hi = 2 * hi + 2;
    }
    return (uint32_t)count;
}

static inline uint32_t tu_depth(uint32_t node)
{
    uint32_t d = 0;
    node++;
    while (node > 1) {
        node >>= 1;
        d++;
    }
    return d;
}

static inline void tu_layout_assign(tu_layout *L, uint32_t n, uint32_t *next)
{
    if (n >= L->leaves - 1) {
        L->first[n] = (*next)++;
        L->count[n] = 1;
        return;
    }
    tu_layout_assign(L, 2 * n + 1, next);
    tu_layout_assign(L, 2 * n + 2, next);
    L->first[n] = L->first[2 * n + 1];
    L->count[n] = L->count[2 * n + 1] + L->count[2 * n + 2];
}

static inline int tu_layout_init(tu_layout *L, uint32_t leaves)
{
    uint32_t next = 0;
    L->leaves = leaves;
    L->nodes = 2 * leaves - 1;
    L->max_depth = tu_depth(L->nodes - 1);
    L->first = (uint32_t *)malloc(sizeof(uint32_t) * L->nodes);
    L->count = (uint32_t *)malloc(sizeof(uint32_t) * L->nodes);
    if (!L->first || !L->count) return 0;
    tu_layout_assign(L, 0, &next);
    return 1;
}

static inline void tu_layout_free(tu_layout *L)
{
    free(L->first);
    free(L->count);
    L->first = L->count = NULL;
}

static inline int tu_is_leaf(const tu_layout *L, uint32_t n) { return n >= L->leaves - 1; }

/* Is a an ancestor of b (or b itself)? */
static inline int tu_is_ancestor(uint32_t a, uint32_t b)
{
    while (b > a) b = (b - 1) / 2;
    return a == b;
}

/* Leaves covered zero or several times by the subtrees of nodes[0..count),
   or nodes out of range; hits is scratch of L->leaves entries. */
static inline uint32_t tu_partition_errors(const tu_layout *L, const uint32_t *nodes, uint32_t count, uint32_t *hits)
{
    uint32_t i, j, bad = 0;
    memset(hits, 0, sizeof(uint32_t) * L->leaves);
    for (i = 0; i < count; i++) {
        if (nodes[i] >= L->nodes) {
            bad++;
            continue;
        }
        for (j = 0; j < L->count[nodes[i]]; j++) hits[L->first[nodes[i]] + j]++;
    }
    for (j = 0; j < L->leaves; j++) bad += hits[j] != 1;
    return bad;
}

/* ------------------------------------------------------------- views */

static inline void tu_sub3(double *r, const float *a, const float *b)
{
    r[0] = (double)a[0] - b[0];
    r[1] = (double)a[1] - b[1];
    r[2] = (double)a[2] - b[2];
}

static inline double tu_dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static inline void tu_cross3(double *r, const double *a, const double *b)
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    r[0] = x;
    r[1] = y;
    r[2] = z;
}

static inline double tu_norm3(const double *a) { return sqrt(tu_dot3(a, a)); }

static inline void tu_normalize3(double *a)
{
    double n = tu_norm3(a);
    if (n > 0) {
        a[0] /= n;
        a[1] /= n;
        a[2] /= n;
    }
}

static inline void tu_random_unit(uint64_t *rng, double *d)
{
    do {
        d[0] = 2.0 * scene_rng_double(rng) - 1.0;
        d[1] = 2.0 * scene_rng_double(rng) - 1.0;
        d[2] = 2.0 * scene_rng_double(rng) - 1.0;
    } while (tu_dot3(d, d) > 1.0 || tu_dot3(d, d) < 1e-4);
    tu_normalize3(d);
}

/* (float)x, and f[i] = (float)d[i], in functions of their own.  GCC 12.2
   at -O2 (its SLP vectoriser) may otherwise take such floats, where they
   are used as doubles in the same function, as the unrounded doubles they
   came from (seen in test_megaviews' cone tests: a struct's double field
   set to (float)y held y, and (double)cone[1] was taken as the axis[1]
   cone[1] had been rounded from, even through volatile stores). */
#if defined(__GNUC__)
__attribute__((noinline, unused))
#endif
static float tu_float(double x)
{
    return (float)x;
}

static inline void tu_to_floats(const double *d, float *f, int n)
{
    int i;
    for (i = 0; i < n; i++) f[i] = tu_float(d[i]);
}

/* A unit vector perpendicular to unit a. */
static inline void tu_random_perp(uint64_t *rng, const double *a, double *p)
{
    double r[3];
    do {
        tu_random_unit(rng, r);
        tu_cross3(p, a, r);
    } while (tu_norm3(p) < 0.1);
    tu_normalize3(p);
}

/* A view with sensible defaults for every field (a cube map's tile is
   3s x 2s: six 32 x 32 faces). */
static inline mlod_view tu_view(mlod_view_kind kind)
{
    mlod_view v;
    memset(&v, 0, sizeof v);
    v.kind = kind;
    v.forward[2] = -1.0f;
    v.up[1] = 1.0f;
    v.width = kind == MLOD_VIEW_CUBE ? 96 : 64;
    v.height = 64;
    v.fov_y = 1.0f;
    v.near_plane = kind == MLOD_VIEW_ORTHOGRAPHIC ? 0.0f : 0.01f;
    v.far_plane = 1000.0f;
    v.half_width = 2.0f;
    v.half_height = 2.0f;
    return v;
}

static inline void tu_set3f(float *r, const double *a)
{
    r[0] = (float)a[0];
    r[1] = (float)a[1];
    r[2] = (float)a[2];
}

/* Eye at eye, looking at target, with a random up not parallel to it. */
static inline void tu_look(uint64_t *rng, mlod_view *v, const double *eye, const double *target)
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, up[3];
    if (tu_norm3(f) < 1e-30) tu_random_unit(rng, f);
    tu_normalize3(f);
    tu_random_perp(rng, f, up);
    tu_set3f(v->position, eye);
    tu_set3f(v->forward, f);
    tu_set3f(v->up, up);
}

/* A random view of kind around a scene of centre c and radius R: eye at
   0.2 .. 8 R from c, mostly looking at the scene, random tile and planes,
   back-face culling on half of them.  Every kind draws the same random
   numbers (a cube map makes its 3s x 2s tile, s = 1 .. 64, from the width
   drawn), so adding a kind changes no other view's stream. */
static inline mlod_view tu_random_view(uint64_t *rng, mlod_view_kind kind, const double *c, double R)
{
    mlod_view v = tu_view(kind);
    double dir[3], eye[3], target[3], dist = R * 0.2 * pow(40.0, scene_rng_double(rng));
    int k;
    tu_random_unit(rng, dir);
    for (k = 0; k < 3; k++) eye[k] = c[k] + dist * dir[k];
    tu_random_unit(rng, dir);
    for (k = 0; k < 3; k++) target[k] = c[k] + 0.5 * R * dir[k] * scene_rng_double(rng);
    if (scene_rng_double(rng) < 0.2)
        for (k = 0; k < 3; k++) target[k] = eye[k] + dir[k];
    tu_look(rng, &v, eye, target);
    v.width = 1 + (uint32_t)(scene_rng_double(rng) * 128);
    v.height = 1 + (uint32_t)(scene_rng_double(rng) * 128);
    v.fov_y = (float)(0.3 + 2.5 * scene_rng_double(rng));
    if (kind == MLOD_VIEW_CUBE) {
        uint32_t side = 1 + (v.width - 1) / 2;
        v.width = 3 * side;
        v.height = 2 * side;
    }
    if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
        v.near_plane = (float)(-R * scene_rng_double(rng));
        v.far_plane = (float)(v.near_plane + R * (0.5 + 4 * scene_rng_double(rng)));
        v.half_width = (float)(R * (0.2 + 1.8 * scene_rng_double(rng)));
        v.half_height = (float)(R * (0.2 + 1.8 * scene_rng_double(rng)));
    } else {
        v.near_plane = (float)(R * (1e-3 + 0.3 * scene_rng_double(rng)));
        v.far_plane = scene_rng_double(rng) < 0.3 ? INFINITY : (float)(v.near_plane + R * (1 + 20 * scene_rng_double(rng)));
    }
    if (scene_rng_double(rng) < 0.5) v.flags = MLOD_VIEW_CULL_BACKFACES;
    return v;
}

/* Centre and radius (of the box around the vertices) of a scene. */
static inline void tu_bounds(const scene_mesh *s, double *c, double *R)
{
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300}, d[3];
    uint32_t i, k;
    for (i = 0; i < s->vertex_count; i++)
        for (k = 0; k < 3; k++) {
            if (s->positions[3 * i + k] < lo[k]) lo[k] = s->positions[3 * i + k];
            if (s->positions[3 * i + k] > hi[k]) hi[k] = s->positions[3 * i + k];
        }
    for (k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        d[k] = hi[k] - lo[k];
    }
    *R = 0.5 * tu_norm3(d);
}

/* Area of triangle t of a scene, in double. */
static inline double tu_triangle_area(const scene_mesh *s, uint32_t t)
{
    const float *a = s->positions + 3 * s->indices[3 * t], *b = s->positions + 3 * s->indices[3 * t + 1],
                *c = s->positions + 3 * s->indices[3 * t + 2];
    double e1[3], e2[3], cr[3];
    tu_sub3(e1, b, a);
    tu_sub3(e2, c, a);
    tu_cross3(cr, e1, e2);
    return 0.5 * tu_norm3(cr);
}

/* V0 + s (V1 - V0) + t (V2 - V0) of a per-vertex float[3] attribute, in double. */
static inline void tu_eval_on_triangle(const float *attr, const uint32_t *tri, double s, double t, double *out)
{
    int k;
    for (k = 0; k < 3; k++) {
        double a = attr[3 * tri[0] + k], b = attr[3 * tri[1] + k], c = attr[3 * tri[2] + k];
        out[k] = a + s * (b - a) + t * (c - a);
    }
}

/* Largest |coordinate| of a triangle's vertices: the scale of its float rounding. */
static inline double tu_max_abs_coordinate(const scene_mesh *s, const uint32_t *tri)
{
    double m = 0;
    int i, k;
    for (i = 0; i < 3; i++)
        for (k = 0; k < 3; k++) {
            double v = fabs(s->positions[3 * tri[i] + k]);
            if (v > m) m = v;
        }
    return m;
}

/* ------------------------------------------------------- reference cut */

static inline int tu_cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The status the definition gives a cut node of criterion c. */
static inline uint8_t tu_status(double c, float eps, int leaf)
{
    if (c == 0.0) return MLOD_STATUS_CULLED;
    if (c <= eps) return MLOD_STATUS_DRAWN;
    return leaf ? MLOD_STATUS_OVERSIZE : MLOD_STATUS_COARSE;
}

/* The cut straight from the definition: n is in it iff (valid(n) or n is a
   leaf) and (n is the root or its parent is not valid), valid(n) <=>
   mlod_criterion(n) <= eps.  Nodes listed left to right (by first leaf,
   ancestors first), with their statuses.  crit: node_count doubles
   (filled), keys: node_count uint64 scratch.  Returns the count. */
static inline uint32_t tu_reference_cut(const mlod_tree *t, const tu_layout *L, const mlod_view *v, float eps,
                                        double *crit, uint64_t *keys, uint32_t *nodes, uint8_t *status)
{
    uint32_t n, count = 0, i;
    for (n = 0; n < t->node_count; n++) crit[n] = mlod_criterion(t, n, v);
    for (n = 0; n < t->node_count; n++) {
        int valid = crit[n] <= eps;
        int parent_valid = n > 0 && crit[(n - 1) / 2] <= eps;
        if ((valid || tu_is_leaf(L, n)) && !parent_valid) keys[count++] = ((uint64_t)L->first[n] << 32) | n;
    }
    qsort(keys, count, sizeof(uint64_t), tu_cmp_u64);
    for (i = 0; i < count; i++) {
        nodes[i] = (uint32_t)keys[i];
        status[i] = tu_status(crit[nodes[i]], eps, tu_is_leaf(L, nodes[i]));
    }
    return count;
}

/* Compare a library cut with a reference: as sets (sorted node indices),
   statuses node by node, and the library's order (strictly increasing first
   leaf).  Returns 0 when all agree, else writes a description into why. */
static inline int tu_cut_differs(const mlod_cut_view *cv, const uint32_t *ref, const uint8_t *ref_status, uint32_t ref_count,
                                 const tu_layout *L, uint64_t *scratch, char *why, size_t why_size)
{
    uint32_t i;
    if (cv->count != ref_count) {
        snprintf(why, why_size, "count %u, reference %u", cv->count, ref_count);
        return 1;
    }
    for (i = 0; i < ref_count; i++) {
        if (cv->nodes[i] >= L->nodes) {
            snprintf(why, why_size, "node %u out of range", cv->nodes[i]);
            return 1;
        }
        scratch[i] = ((uint64_t)cv->nodes[i] << 8) | cv->status[i];
    }
    qsort(scratch, ref_count, sizeof(uint64_t), tu_cmp_u64);
    for (i = 0; i < ref_count; i++) scratch[ref_count + i] = ((uint64_t)ref[i] << 8) | ref_status[i];
    qsort(scratch + ref_count, ref_count, sizeof(uint64_t), tu_cmp_u64);
    for (i = 0; i < ref_count; i++) {
        if ((scratch[i] >> 8) != (scratch[ref_count + i] >> 8)) {
            snprintf(why, why_size, "sets differ: sorted entry %u is node %u, reference node %u", i,
                     (unsigned)(scratch[i] >> 8), (unsigned)(scratch[ref_count + i] >> 8));
            return 1;
        }
        if (scratch[i] != scratch[ref_count + i]) {
            snprintf(why, why_size, "node %u has status %u, reference %u", (unsigned)(scratch[i] >> 8),
                     (unsigned)(scratch[i] & 0xff), (unsigned)(scratch[ref_count + i] & 0xff));
            return 1;
        }
    }
    for (i = 1; i < ref_count; i++)
        if (L->first[cv->nodes[i]] <= L->first[cv->nodes[i - 1]]) {
            snprintf(why, why_size, "not left to right at %u: node %u (first leaf %u) after node %u (first leaf %u)", i,
                     cv->nodes[i], L->first[cv->nodes[i]], cv->nodes[i - 1], L->first[cv->nodes[i - 1]]);
            return 1;
        }
    return 0;
}

/* Counts by status agree with the list. */
static inline int tu_counts_ok(const mlod_cut_view *cv)
{
    uint32_t i, n[5] = {0, 0, 0, 0, 0};
    for (i = 0; i < cv->count; i++) {
        if (cv->status[i] < 1 || cv->status[i] > 4) return 0;
        n[cv->status[i]]++;
    }
    return n[MLOD_STATUS_DRAWN] == cv->drawn && n[MLOD_STATUS_CULLED] == cv->culled &&
           n[MLOD_STATUS_OVERSIZE] == cv->oversize && n[MLOD_STATUS_COARSE] == cv->coarse &&
           cv->drawn + cv->culled + cv->oversize + cv->coarse == cv->count;
}

/* The manual's bound on a lazy update of one view (THE CUT, "A budget"):
   3 n (2^q - 1) node-views for n entries and q = lazy_steps, saturating
   at UINT64_MAX; written from the manual, not from the library. */
static inline uint64_t tu_lazy_bound(uint32_t n, uint32_t q)
{
    uint64_t rounds = q >= 40 ? UINT64_MAX : ((uint64_t)1 << q) - 1;
    uint64_t per = 3 * (uint64_t)n;
    return per && rounds > UINT64_MAX / per ? UINT64_MAX : rounds * per;
}

/* Two cut views have identical lists, statuses and counts. */
static inline int tu_same_cut(const mlod_cut_view *a, const mlod_cut_view *b)
{
    if (a->count != b->count || a->drawn != b->drawn || a->culled != b->culled || a->oversize != b->oversize ||
        a->coarse != b->coarse)
        return 0;
    if (a->count == 0) return 1;
    return memcmp(a->nodes, b->nodes, sizeof(uint32_t) * a->count) == 0 &&
           memcmp(a->status, b->status, a->count) == 0;
}

/* 2^-20 rad, less what long double cannot promise about atan2. */
#define TU_CONE_SLACK (9.5367431640625e-7L - 1e-15L)

/* Containment (plain and with the documented slack) of every child in its
   parent, spheres and cones; one CHECK per property. */
static inline void tu_check_containment(const mlod_tree *t, const char *what)
{
    uint32_t n, bad = 0, bad_slack = 0, bad_cone = 0, bad_cone_slack = 0, bad_axis = 0, first = 0, first_s = 0,
                first_c = 0, first_cs = 0;
    for (n = 1; n < t->node_count; n++) {
        const float *p = t->spheres + 4 * ((n - 1) / 2), *c = t->spheres + 4 * n;
        if (!exact_sphere_contains(p, c) && !bad++) first = n;
        if (!exact_sphere_contains_slack(p, c) && !bad_slack++) first_s = n;
        if (t->cones) {
            const float *pc = t->cones + 4 * ((n - 1) / 2), *cc = t->cones + 4 * n;
            if (!exact_cone_contains(pc, cc, 0.0L) && !bad_cone++) first_c = n;
            if (!exact_cone_contains(pc, cc, TU_CONE_SLACK) && !bad_cone_slack++) first_cs = n;
        }
    }
    if (first == 0) first = first_s ? first_s : 1; /* only for the messages */
    if (first_c == 0) first_c = first_cs ? first_cs : 1;
    if (t->node_count == 1) first = first_c = 0;
    CHECK(bad == 0, "%s: %u children not inside their parent sphere, first node %u (%.9g %.9g %.9g r %.9g) in (%.9g %.9g %.9g r %.9g)",
          what, bad, first, t->spheres[4 * first], t->spheres[4 * first + 1], t->spheres[4 * first + 2],
          t->spheres[4 * first + 3], t->spheres[4 * (first ? (first - 1) / 2 : 0)], t->spheres[4 * (first ? (first - 1) / 2 : 0) + 1],
          t->spheres[4 * (first ? (first - 1) / 2 : 0) + 2], t->spheres[4 * (first ? (first - 1) / 2 : 0) + 3]);
    CHECK(bad_slack == 0, "%s: %u children violate r_parent >= (d + r_child)(1 + 2^-20), first node %u", what,
          bad_slack, first_s);
    if (t->cones) {
        for (n = 0; n < t->node_count; n++) {
            const float *c = t->cones + 4 * n;
            double len = sqrt((double)c[0] * c[0] + (double)c[1] * c[1] + (double)c[2] * c[2]);
            if (!(c[3] >= 0) || (c[3] < TU_PI && fabs(len - 1.0) > 1e-5)) bad_axis++;
        }
        CHECK(bad_cone == 0, "%s: %u child cones outside their parent cone, first node %u (alpha %.9g in %.9g)", what,
              bad_cone, first_c, t->cones[4 * first_c + 3], t->cones[4 * (first_c ? (first_c - 1) / 2 : 0) + 3]);
        CHECK(bad_cone_slack == 0, "%s: %u child cones within 2^-20 rad of their parent cone's border, first node %u",
              what, bad_cone_slack, first_cs);
        CHECK(bad_axis == 0, "%s: %u cones with a non-unit axis or negative half-angle", what, bad_axis);
    }
}

/* ----------------------------------------------------------- allocator */

/* Counts live blocks and bytes and their high-water mark; can fail the
   fail_at-th call (1-based), or every call from it on (fail_after), any
   block above max_bytes, or any block that would take the live bytes past
   budget_bytes (0: none). */
typedef struct tu_counter {
    unsigned long calls, live_blocks, frees_of_unknown;
    size_t live_bytes, peak_bytes, max_bytes, budget_bytes;
    unsigned long fail_at;
    int fail_after;
} tu_counter;

static inline void *tu_counter_alloc(void *user, size_t bytes)
{
    tu_counter *c = (tu_counter *)user;
    unsigned char *p;
    c->calls++;
    if (c->fail_at && (c->calls == c->fail_at || (c->fail_after && c->calls > c->fail_at))) return NULL;
    if (c->max_bytes && bytes > c->max_bytes) return NULL;
    if (c->budget_bytes && (c->live_bytes >= c->budget_bytes || bytes > c->budget_bytes - c->live_bytes)) return NULL;
    p = (unsigned char *)malloc(bytes + 16);
    if (!p) return NULL;
    memcpy(p, &bytes, sizeof bytes);
    memcpy(p + 8, "mlodTEST", 8);
    c->live_blocks++;
    c->live_bytes += bytes;
    if (c->live_bytes > c->peak_bytes) c->peak_bytes = c->live_bytes;
    return p + 16;
}

static inline void tu_counter_free(void *user, void *pointer)
{
    tu_counter *c = (tu_counter *)user;
    unsigned char *p = (unsigned char *)pointer;
    size_t bytes;
    if (!p) return;
    p -= 16;
    if (memcmp(p + 8, "mlodTEST", 8) != 0) {
        c->frees_of_unknown++;
        return;
    }
    memcpy(&bytes, p, sizeof bytes);
    memset(p + 8, 0, 8);
    c->live_blocks--;
    c->live_bytes -= bytes;
    free(p);
}

static inline mlod_allocator tu_allocator(tu_counter *c)
{
    mlod_allocator a;
    a.alloc = tu_counter_alloc;
    a.free = tu_counter_free;
    a.user = c;
    return a;
}

/* 64-bit FNV-1a of bytes, continuing from hash (start: TU_HASH_START). */
#define TU_HASH_START 0xcbf29ce484222325ull
static inline uint64_t tu_hash(uint64_t hash, const void *data, size_t bytes)
{
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    for (i = 0; i < bytes; i++) hash = (hash ^ p[i]) * 0x100000001b3ull;
    return hash;
}

/* ------------------------------------------------------- serial hooks */

/* Runs the tasks on the calling thread in reverse order. */
static inline void tu_run_reverse(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    (void)user;
    for (i = count; i-- > 0;) task(context, i);
}

/* Runs the odd tasks, then the even ones. */
static inline void tu_run_odd_even(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t i;
    (void)user;
    for (i = 1; i < count; i += 2) task(context, i);
    for (i = 0; i < count; i += 2) task(context, i);
}

#ifdef MANYLODS_PTHREADS
/* The hooks results must not depend on: pools of 1, 2 and 3 threads
   (pools[0..2], NULL when one could not start), tasks backwards, odd
   tasks first.  mlod_pool_destroy the pools after. */
static inline void tu_hooks(mlod_pool *pools[3], mlod_parallel hooks[5])
{
    uint32_t h;
    for (h = 0; h < 3; h++) {
        pools[h] = mlod_pool_create(h + 1);
        hooks[h] = mlod_pool_parallel(pools[h]);
    }
    hooks[3].run = tu_run_reverse;
    hooks[3].user = NULL;
    hooks[4].run = tu_run_odd_even;
    hooks[4].user = NULL;
}
#endif

#endif /* MANYLODS_TEST_UTIL_H */
