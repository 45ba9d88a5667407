/* tests/test_megaviews.c - the view tree and the MegaViews render, against
   independent references.

   - the view tree: its spheres and cones contain their children exactly
     (with the scene tree's slack), each leaf holds its view's eye exactly
     (radius 0) and its direction, the leaves hold every view once, each
     node's half field of view is the largest below it (brute force), and
     all of it again after a refit to moved views;
   - with delta = 0 the render equals, bit for bit in depth, normal and
     colour, the per-view cut and splat of the same maps (mlod_cut_update
     and mlod_splat on mlod_megaviews_view), for omnidirectional views,
     with back-face culling, with duplicate eyes, eyes outside the scene,
     several resolutions and epsilons; with fields of view it equals the
     per-view cut's nodes that the view's field of view does not cull,
     drawn as mlod_splat draws;
   - grouping: a group radius holding every eye gives every view the map
     of one view at the root's centre (its cut and splat), node for node,
     at each view's own distances; smaller groups keep depths exact and
     the atlas the same for any hook, with fewer pairs;
   - culling is conservative, by brute force in long double: no view below
     a culled pair sees any point of the scene node's sphere in its field
     of view (or, back-face culled, with any normal of its cone), and every
     view below would cull it itself;
   - the bounds the traversal shares by hold for eyes sampled in the view
     node's ball: the diameter lies within [cmin, cmax], and the image disc
     (centre and radius) moves by at most the motion bound;
   - the same atlas for every thread count and task order, delta > 0;
   - the same atlas and statistics walking each view subtree depth first
     from any level of the view tree, however little room its lists get
     first, as level by level;
   - the unfused maps queried down the view tree equal the fused atlas,
     in maps of another orientation too;
   - the maps' orientation (params.forward, up): with delta 0 the render
     equals the per-view cut and splat of each view's oriented map, bit
     for bit; frames equal to the default's give the default's atlas; in
     an oblique frame the pair filter, the walks and the bounds hold as in
     the default's;
   - statistics: with delta = 0 and distinct eyes nothing is shared and
     the leaf draws are the per-view cuts' drawn nodes;
   - errors: NULLs, bad epsilon, delta, resolution, orientation,
     mismatched atlases and channels, bad view sets, failing allocators
     (the atlas then empty). */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"
#include "mv_reference.h"

/* ============================================================ helpers */

typedef struct views {
    uint32_t count;
    float *eyes, *directions, *fovs;
} views;

/* count eyes in the box [lo, hi] (some duplicated when dup), random unit
   directions and half fields of view in [0.3, pi]. */
static views make_views(uint64_t seed, uint32_t count, const float *lo, const float *hi, int dup)
{
    views v;
    uint64_t rng = seed;
    uint32_t i;
    int k;
    v.count = count;
    v.eyes = (float *)malloc(12 * (size_t)count);
    v.directions = (float *)malloc(12 * (size_t)count);
    v.fovs = (float *)malloc(4 * (size_t)count);
    for (i = 0; i < count; i++) {
        double d[3];
        for (k = 0; k < 3; k++) v.eyes[3 * i + k] = scene_rng_range(&rng, lo[k], hi[k]);
        if (dup && i % 7 == 3) memcpy(v.eyes + 3 * i, v.eyes + 3 * (i - 1), 12);
        tu_random_unit(&rng, d);
        for (k = 0; k < 3; k++) v.directions[3 * i + k] = (float)(d[k] * (1.0 + i % 3));
        v.fovs[i] = (float)(0.3 + (TU_PI - 0.3) * scene_rng_double(&rng));
    }
    return v;
}

static void free_views(views *v)
{
    free(v->eyes);
    free(v->directions);
    free(v->fovs);
}

/* a[0 .. n) in a random order (Fisher-Yates). */
static void shuffle(uint32_t *a, uint32_t n, uint64_t *rng)
{
    uint32_t i;
    for (i = n; i > 1; i--) {
        uint32_t j = (uint32_t)(scene_rng_double(rng) * i), x = a[i - 1];
        if (j >= i) j = i - 1;
        a[i - 1] = a[j];
        a[j] = x;
    }
}

static mlod_view_set view_set(const views *v, int directions, int per_view_fov)
{
    mlod_view_set s;
    memset(&s, 0, sizeof s);
    s.eyes = v->eyes;
    s.count = v->count;
    if (directions) s.directions = v->directions;
    if (per_view_fov) s.half_fovs = v->fovs;
    return s;
}

static mlod_view_tree *build_views(const mlod_view_set *s, const mlod_parallel *parallel)
{
    mlod_view_tree *t = NULL;
    mlod_error e;
    if (mlod_view_tree_build(s, NULL, parallel, &t, &e) != MLOD_OK) fprintf(stderr, "view tree: %s\n", e.message);
    return t;
}

/* A render's job as the pair test (mlod__pair_action) reads it: the scene,
   the views, maps of 2 x resolution^2 pixels, epsilon 1, flags. */
static mlod__mv_job pair_job(const mlod_tree *scene, const mlod_view_tree *t, uint32_t resolution, uint32_t flags)
{
    mlod__mv_job job;
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.views = t;
    job.epsilon = 1.0;
    job.resolution = resolution;
    job.S = 0.5 * resolution;
    job.flags = flags;
    return job;
}

/* The depth the fusion leaves at pixel (col, row) of the view whose
   prepared map view is pv, holding the node (x: its centre minus the eye):
   the node's distance from the eye (spheres), or, with the tangent discs
   of a scene with cones, as measured along the pixel's ray
   (mlod__remeasure: the fusion of an ancestor's pixel and the view's own
   draw must agree on it), which must lie in the sphere's range of
   distances. */
static float fused_depth(const mlod__pview *pv, const mlod_tree *scene, uint32_t node, uint32_t col, uint32_t row,
                         const double *x)
{
    double d = mlod__length3(x), r = scene->spheres[4 * (size_t)node + 3];
    float v;
    if (!scene->cones) return (float)d;
    v = mlod__remeasure(pv, scene, node, col, row, 1);
    return v >= (float)(d - r) * (1.0f - 1e-6f) && v <= (float)(d + r) * (1.0f + 1e-6f) ? v : -1.0f;
}

/* fused_depth at view i's pixel (col, row). */
static float fused_depth_at(const views *v, uint32_t i, uint32_t resolution, const mlod_tree *scene, uint32_t node,
                            uint32_t col, uint32_t row)
{
    mlod_view view = mlod_megaviews_view(v->eyes + 3 * i, resolution, 0);
    mlod__pview pv;
    double x[3];
    int k;
    mlod__view_prepare(&view, &pv, NULL);
    for (k = 0; k < 3; k++) x[k] = (double)scene->spheres[4 * (size_t)node + k] - v->eyes[3 * i + k];
    return fused_depth(&pv, scene, node, col, row, x);
}

/* An atlas of the views' MegaViews maps in the orientation (forward, up)
   (NULL: the default), cells in `order` (NULL: view order). */
static mlod_atlas *make_atlas_axes(const views *v, uint32_t resolution, uint32_t channels, mlod_view **out_views,
                                   uint32_t flags, const uint32_t *order, const float *forward, const float *up)
{
    mlod_view *vs = (mlod_view *)malloc(sizeof(mlod_view) * v->count);
    mlod_atlas_desc desc;
    mlod_atlas *a = NULL;
    mlod_error e;
    uint32_t i;
    for (i = 0; i < v->count; i++)
        vs[i] = mlod_megaviews_view_oriented(v->eyes + 3 * i, resolution, flags, forward, up);
    memset(&desc, 0, sizeof desc);
    desc.channels = channels;
    desc.order = order;
    if (mlod_atlas_create(vs, v->count, &desc, NULL, &a, &e) != MLOD_OK) fprintf(stderr, "atlas: %s\n", e.message);
    if (out_views)
        *out_views = vs;
    else
        free(vs);
    return a;
}

static mlod_atlas *make_atlas_ordered(const views *v, uint32_t resolution, uint32_t channels, mlod_view **out_views,
                                      uint32_t flags, const uint32_t *order)
{
    return make_atlas_axes(v, resolution, channels, out_views, flags, order, NULL, NULL);
}

static mlod_atlas *make_atlas(const views *v, uint32_t resolution, uint32_t channels, mlod_view **out_views,
                              uint32_t flags)
{
    return make_atlas_ordered(v, resolution, channels, out_views, flags, NULL);
}

static int same_atlas(const mlod_atlas *a, const mlod_atlas *b, size_t *first)
{
    size_t n = (size_t)a->width * a->height, i;
    for (i = 0; i < n; i++)
        if (memcmp(&a->depth[i], &b->depth[i], 4) || (a->normal && memcmp(a->normal + 3 * i, b->normal + 3 * i, 12)) ||
            (a->color && memcmp(a->color + 3 * i, b->color + 3 * i, 12))) {
            *first = i;
            return 0;
        }
    return 1;
}

/* The per-view reference: each view's basic cut of its map view, and of
   its drawn nodes those its own field of view does not cull (all of them
   without directions), drawn in order as mlod_splat draws them. */
static void reference_render(mlod_atlas *ref, const mlod_tree *scene, const mlod_view *vs, const views *v,
                             int directions, float epsilon, uint64_t *drawn_total)
{
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_error e;
    uint32_t i;
    memset(&cp, 0, sizeof cp);
    cp.epsilon = epsilon;
    if (mlod_cut_create(v->count, NULL, &cut, &e) != MLOD_OK || mlod_cut_update(cut, scene, vs, &cp, &e) != MLOD_OK) {
        CHECK(0, "reference cut: %s", e.message);
        mlod_cut_destroy(cut);
        return;
    }
    *drawn_total = 0;
    for (i = 0; i < v->count; i++)
        *drawn_total += mvref_draw_view(ref, scene, &vs[i], i, mlod_cut_get(cut, i), v->eyes + 3 * i,
                                        directions ? v->directions + 3 * i : NULL, v->fovs[i]);
    mlod_cut_destroy(cut);
}

/* ========================================================== view tree */

/* Every view under leaf j's subtree, brute force: the largest half fov. */
static void check_view_tree(const mlod_view_tree *t, const views *v, int directions, int per_view, const char *what)
{
    const mlod_tree *eyes = t->eyes;
    uint32_t n = eyes->leaf_count, i, bad_eye = 0, bad_dir = 0, bad_fov = 0, bad_perm = 0, bad_floor = 0, floors = 0;
    char *seen = (char *)calloc(v->count, 1);
    tu_check_containment(eyes, what);
    CHECK(t->view_count == v->count && n == v->count, "%s: %u leaves for %u views", what, n, v->count);
    for (i = 0; i < n; i++) {
        uint32_t view = eyes->leaf_sources[i];
        const float *s = eyes->spheres + 4 * (size_t)(n - 1 + i);
        if (view >= v->count || seen[view]++) {
            bad_perm++;
            continue;
        }
        if (memcmp(s, v->eyes + 3 * view, 12) || s[3] != 0.0f) bad_eye++;
        if (directions) {
            const float *c = eyes->cones + 4 * (size_t)(n - 1 + i), *d = v->directions + 3 * view;
            long double dot = (long double)c[0] * d[0] + (long double)c[1] * d[1] + (long double)c[2] * d[2];
            long double len = sqrtl((long double)d[0] * d[0] + (long double)d[1] * d[1] + (long double)d[2] * d[2]) *
                              sqrtl((long double)c[0] * c[0] + (long double)c[1] * c[1] + (long double)c[2] * c[2]);
            if (!(dot / len > 1.0L - 1e-12L) || c[3] != 0.0f) bad_dir++;
        }
    }
    if (directions) {
        for (i = 0; i < eyes->node_count; i++) {
            /* the largest and smallest fov of the leaves below node i, by walking up from each leaf */
            float most = 0.0f, least = 4.0f;
            uint32_t j;
            for (j = 0; j < n; j++) {
                uint32_t node = n - 1 + j;
                while (node > i) node = (node - 1) / 2;
                if (node == i) {
                    float f = per_view ? v->fovs[eyes->leaf_sources[j]] : (float)(0.5 * TU_PI);
                    if (f > most) most = f;
                    if (f < least) least = f;
                }
            }
            if (t->half_fovs[2 * i + 1] != most || t->half_fovs[2 * i] != least) bad_fov++;
            /* the floor: every eye below at least that high along the unit axis, in long double; the spread at
               least 2 sin(alpha / 2) + sin(most - pi/2) where most > pi/2 */
            {
                const float *c = eyes->cones + 4 * (size_t)i, *sphere = eyes->spheres + 4 * (size_t)i;
                long double len = sqrtl((long double)c[0] * c[0] + (long double)c[1] * c[1] + (long double)c[2] * c[2]);
                long double spread = c[3] < TU_PI ? 2.0L * sinl(0.5L * c[3]) : 2.0L;
                if (most > 0.5L * TU_PI && most < TU_PI) spread += sinl(most - 0.5L * TU_PI);
                if (!(t->floors[2 * i + 1] >= spread)) bad_floor++;
                if (t->floors[2 * i] > -INFINITY) {
                    floors++;
                    for (j = 0; j < n; j++) {
                        uint32_t node = n - 1 + j;
                        const float *e = v->eyes + 3 * (size_t)eyes->leaf_sources[j];
                        long double up = 0.0L;
                        int k;
                        while (node > i) node = (node - 1) / 2;
                        if (node != i) continue;
                        for (k = 0; k < 3; k++) up += ((long double)e[k] - sphere[k]) * c[k];
                        if (!(up / len >= t->floors[2 * i])) bad_floor++;
                    }
                } else if (c[3] < TU_PI && most < TU_PI && len > 0) {
                    bad_floor++; /* a floor where the cone and the fields of view leave room for one */
                }
            }
            if (eyes->node_count > 300) i += 37; /* a sample of nodes beyond small trees */
        }
        CHECK(bad_floor == 0, "%s: %u nodes' floors or spreads do not bound their eyes and cones (%u floors)", what,
              bad_floor, floors);
    } else {
        CHECK(t->half_fovs == NULL && t->floors == NULL && eyes->cones == NULL, "%s: no directions, yet fovs or cones",
              what);
    }
    CHECK(bad_perm == 0, "%s: %u leaves do not hold a distinct view", what, bad_perm);
    CHECK(bad_eye == 0, "%s: %u leaves are not their view's eye with radius 0", what, bad_eye);
    CHECK(bad_dir == 0, "%s: %u leaf cones are not their view's direction", what, bad_dir);
    CHECK(bad_fov == 0, "%s: %u nodes' half_fovs are not the smallest and largest below", what, bad_fov);
    free(seen);
}

static void test_view_tree(void)
{
    static const float lo[3] = {-3, -1, -2}, hi[3] = {3, 1, 2};
    uint32_t counts[] = {1, 2, 3, 17, 500}, c;
    for (c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        views v = make_views(11 + c, counts[c], lo, hi, 1);
        int mode;
        for (mode = 0; mode < 3; mode++) {
            mlod_view_set s = view_set(&v, mode > 0, mode > 1);
            mlod_view_tree *t = build_views(&s, NULL);
            char what[64];
            mlod_error e;
            uint32_t i;
            snprintf(what, sizeof what, "view tree of %u views, mode %d", counts[c], mode);
            CHECK(t != NULL, "%s: built", what);
            if (!t) continue;
            check_view_tree(t, &v, mode > 0, mode > 1, what);
            CHECK(t->bytes >= t->eyes->bytes + sizeof *t, "%s: bytes %zu count the tree", what, t->bytes);
            /* the views move: refit keeps the leaves' views and contains them again */
            for (i = 0; i < 3 * v.count; i++) v.eyes[i] = v.eyes[i] * 1.5f + 0.25f;
            for (i = 0; i < v.count; i++) v.fovs[i] = v.fovs[i] * 0.5f;
            {
                uint64_t rng = 99 + c;
                for (i = 0; i < 3 * v.count; i++) v.directions[i] += scene_rng_range(&rng, -0.5f, 0.5f);
                for (i = 0; i < v.count; i++)
                    if (v.directions[3 * i] == 0 && v.directions[3 * i + 1] == 0 && v.directions[3 * i + 2] == 0)
                        v.directions[3 * i] = 1;
            }
            CHECK(mlod_view_tree_refit(t, &s, NULL, &e) == MLOD_OK, "%s: refit", what);
            snprintf(what, sizeof what, "refit view tree of %u views, mode %d", counts[c], mode);
            check_view_tree(t, &v, mode > 0, mode > 1, what);
            mlod_view_tree_destroy(t);
        }
        free_views(&v);
    }
}

/* The view tree's leaf order with directions (MLOD__VIEW_TURN): a
   reference by the rule's words, each node's candidates sorted whole by
   qsort (the library selects in place), on views around a room's corner:
   a floor, two walls and the corner's edge, each view along its surface's
   normal (some turned a little), some eyes shared by views looking
   different ways.  Fewer views than MLOD__VIEW_SAMPLE, so every node is
   decided on all its views; the reference must choose a direction at some
   nodes, or the test could not tell the rule from the position-only
   order.  Without directions the order is mlod_build_points's. */
static const float *order_keys; /* 6 per view: eye, unit direction */
static int order_dim;
static int order_cmp(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    float kx = order_keys[6 * (size_t)x + order_dim], ky = order_keys[6 * (size_t)y + order_dim];
    return kx < ky ? -1 : kx > ky ? 1 : x < y ? -1 : x > y;
}

static double order_cost(const uint32_t *items, uint32_t n, double turn)
{
    double lo[6], hi[6], p = 0, q = 0, d;
    uint32_t i;
    int k;
    for (k = 0; k < 6; k++) lo[k] = hi[k] = order_keys[6 * (size_t)items[0] + k];
    for (i = 1; i < n; i++)
        for (k = 0; k < 6; k++) {
            double x = order_keys[6 * (size_t)items[i] + k];
            lo[k] = x < lo[k] ? x : lo[k];
            hi[k] = x > hi[k] ? x : hi[k];
        }
    for (k = 0; k < 3; k++) {
        p += (hi[k] - lo[k]) * (hi[k] - lo[k]);
        q += (hi[k + 3] - lo[k + 3]) * (hi[k + 3] - lo[k + 3]);
    }
    d = sqrt(p) + turn * sqrt(q);
    return d * d * d;
}

static void order_reference(uint32_t *items, uint32_t node, uint32_t n, double turn, uint32_t *order,
                            uint32_t *by_direction)
{
    uint32_t count = mlod__leaves_below(node, n), nl, i;
    double extent[6], widest = 0, best = 0;
    int k, axis = 0, first = 1;
    if (count == 1) {
        order[node - (n - 1)] = items[0];
        return;
    }
    nl = mlod__leaves_below(2 * node + 1, n);
    for (k = 0; k < 6; k++) {
        double lo = order_keys[6 * (size_t)items[0] + k], hi = lo;
        for (i = 1; i < count; i++) {
            double x = order_keys[6 * (size_t)items[i] + k];
            lo = x < lo ? x : lo;
            hi = x > hi ? x : hi;
        }
        extent[k] = (hi - lo) * (k < 3 ? 1.0 : turn);
        widest = extent[k] > widest ? extent[k] : widest;
    }
    for (k = 0; k < 6; k++) {
        double cost;
        if (!(extent[k] > 1e-3 * widest)) continue;
        order_dim = k;
        qsort(items, count, sizeof *items, order_cmp);
        cost = order_cost(items, nl, turn) + order_cost(items + nl, count - nl, turn);
        if (first || cost < best) {
            best = cost;
            axis = k;
        }
        first = 0;
    }
    *by_direction += axis >= 3;
    order_dim = axis;
    qsort(items, count, sizeof *items, order_cmp);
    order_reference(items, 2 * node + 1, n, turn, order, by_direction);
    order_reference(items + nl, 2 * node + 2, n, turn, order, by_direction);
}

static void test_view_order(void)
{
    enum { N = 400 };
    static float eyes[3 * N], dirs[3 * N], keys[6 * N];
    static const float normals[4][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {0.70710678f, 0, 0.70710678f}};
    uint32_t items[N], order[N], i, by_direction = 0, differ = 0;
    uint64_t rng = 4711;
    double lo[3], hi[3], diagonal = 0;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel two = mlod_pool_parallel(pool);
    int k, threads;
    for (i = 0; i < N; i++) {
        int surface = (int)(i % 4);
        float a = scene_rng_range(&rng, 0.0f, 2.0f), b = scene_rng_range(&rng, 0.0f, 2.0f);
        float *e = eyes + 3 * i, *d = dirs + 3 * i;
        if (surface == 0) { e[0] = a; e[1] = 0.01f; e[2] = b; }              /* the floor */
        else if (surface == 1) { e[0] = 0.01f; e[1] = a; e[2] = b; }         /* a wall */
        else if (surface == 2) { e[0] = a; e[1] = b; e[2] = 0.01f; }         /* the other wall */
        else { e[0] = 0.01f; e[1] = a; e[2] = 0.01f; }                        /* their edge */
        for (k = 0; k < 3; k++) d[k] = normals[surface][k];
        if (i % 7 == 3) d[surface == 0 ? 0 : 1] += scene_rng_range(&rng, -0.2f, 0.2f); /* turned a little */
        if (i % 11 == 5 && i > 0) { /* an eye shared with the view before, looking another way */
            memcpy(e, eyes + 3 * (i - 1), sizeof(float) * 3);
        }
    }
    for (i = 0; i < N; i++) {
        double length = sqrt((double)dirs[3 * i] * dirs[3 * i] + (double)dirs[3 * i + 1] * dirs[3 * i + 1] +
                             (double)dirs[3 * i + 2] * dirs[3 * i + 2]);
        for (k = 0; k < 3; k++) {
            keys[6 * i + k] = eyes[3 * i + k];
            keys[6 * i + 3 + k] = (float)(dirs[3 * i + k] / length);
            lo[k] = i == 0 || eyes[3 * i + k] < lo[k] ? eyes[3 * i + k] : lo[k];
            hi[k] = i == 0 || eyes[3 * i + k] > hi[k] ? eyes[3 * i + k] : hi[k];
        }
        items[i] = i;
    }
    for (k = 0; k < 3; k++) diagonal += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    order_keys = keys;
    order_reference(items, 0, N, MLOD__VIEW_TURN * sqrt(diagonal), order, &by_direction);
    CHECK(by_direction > 10, "view order: the reference splits %u nodes by direction (the set-up should make it "
                             "choose directions)", by_direction);
    for (threads = 0; threads < 2; threads++) {
        mlod_view_set s;
        mlod_view_tree *t;
        memset(&s, 0, sizeof s);
        s.eyes = eyes;
        s.directions = dirs;
        s.count = N;
        t = build_views(&s, threads ? &two : NULL);
        CHECK(t != NULL, "view order: built");
        if (!t) continue;
        for (i = 0, differ = 0; i < N; i++) differ += t->eyes->leaf_sources[i] != order[i];
        CHECK(differ == 0, "view order (%s): %u of %u leaves hold another view than the rule's", threads ? "two threads" : "one thread", differ, N);
        mlod_view_tree_destroy(t);
    }
    { /* without directions: the scene tree's order of the eyes */
        mlod_view_set s;
        mlod_view_tree *t;
        mlod_points pts;
        mlod_build_desc d;
        mlod_tree *plain = NULL;
        memset(&s, 0, sizeof s);
        s.eyes = eyes;
        s.count = N;
        memset(&pts, 0, sizeof pts);
        pts.positions = eyes;
        pts.count = N;
        memset(&d, 0, sizeof d);
        d.attributes = MLOD_ATTR_REFIT;
        t = build_views(&s, NULL);
        CHECK(t && mlod_build_points(&pts, &d, &plain, NULL) == MLOD_OK, "view order: built without directions");
        if (t && plain)
            CHECK(memcmp(t->eyes->leaf_sources, plain->leaf_sources, N * sizeof(uint32_t)) == 0,
                  "view order: without directions the leaves are in the order of mlod_build_points");
        mlod_view_tree_destroy(t);
        mlod_tree_destroy(plain);
    }
    mlod_pool_destroy(pool);
}

/* ================================================= delta 0: per view */

static void test_equals_per_view(const mlod_tree *scene, const char *scene_name)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const float far_lo[3] = {-9, -9, -9}, far_hi[3] = {9, 9, 9};
    struct {
        uint32_t views, resolution;
        float epsilon;
        int directions, per_view, backfaces, far, dup;
    } cases[] = {{300, 8, 1.0f, 0, 0, 0, 0, 0}, {200, 5, 2.5f, 0, 0, 1, 0, 1}, {150, 16, 1.0f, 0, 0, 0, 1, 0},
                 {300, 8, 1.0f, 1, 1, 0, 0, 0}, {200, 8, 1.5f, 1, 0, 1, 0, 1}, {1, 7, 1.0f, 1, 1, 0, 0, 0},
                 {64, 4, 0.25f, 0, 0, 0, 0, 0}};
    uint32_t c;
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        views v = make_views(100 + c, cases[c].views, cases[c].far ? far_lo : lo, cases[c].far ? far_hi : hi,
                             cases[c].dup);
        mlod_view_set s = view_set(&v, cases[c].directions, cases[c].per_view);
        mlod_view_tree *t = build_views(&s, NULL);
        uint32_t flags = cases[c].backfaces ? MLOD_VIEW_CULL_BACKFACES : 0u, i;
        uint32_t channels = (scene->cones ? MLOD_ATLAS_NORMAL : 0u) | (scene->colors ? MLOD_ATLAS_COLOR : 0u);
        mlod_view *vs = NULL, *vs2 = NULL;
        mlod_atlas *a = make_atlas(&v, cases[c].resolution, channels, &vs, flags);
        mlod_atlas *ref = make_atlas(&v, cases[c].resolution, channels, &vs2, flags);
        mlod_megaviews_params p;
        mlod_megaviews_stats st;
        mlod_error e;
        uint64_t drawn = 0;
        size_t first = 0;
        memset(&p, 0, sizeof p);
        p.epsilon = cases[c].epsilon;
        p.resolution = cases[c].resolution;
        p.flags = flags;
        if (!cases[c].per_view && cases[c].directions)
            for (i = 0; i < v.count; i++) v.fovs[i] = (float)(0.5 * TU_PI); /* the reference's fov */
        if (t && a && ref) {
            mlod_result r = mlod_megaviews_render(a, scene, t, &p, &st, &e);
            CHECK(r == MLOD_OK, "%s case %u: render: %s", scene_name, c, e.message);
            reference_render(ref, scene, vs, &v, cases[c].directions, p.epsilon, &drawn);
            int same = same_atlas(a, ref, &first);
            CHECK(same, "%s case %u: delta 0 differs from the per-view cut and splat at "
                  "pixel %zu (%g against %g)", scene_name, c, first, a->depth[first], ref->depth[first]);
            if (cases[c].dup) { /* coincident eyes share, near scene leaves too: the equality above covers them */
                CHECK(st.shared_draws > 0 && st.shared_leaves > 0, "%s case %u: coincident eyes share (%llu draws, "
                      "%llu of them near leaves)", scene_name, c, (unsigned long long)st.shared_draws,
                      (unsigned long long)st.shared_leaves);
            } else {
                CHECK(st.shared_draws == 0, "%s case %u: %llu shared draws with delta 0 and distinct eyes",
                      scene_name, c, (unsigned long long)st.shared_draws);
                CHECK(st.leaf_draws == drawn, "%s case %u: %llu leaf draws, the per-view cuts draw %llu", scene_name,
                      c, (unsigned long long)st.leaf_draws, (unsigned long long)drawn);
            }
            CHECK(st.pairs >= st.leaf_draws + st.shared_draws + st.culled && st.shared_leaves <= st.shared_draws &&
                  st.levels == mlod__depth_of(2 * v.count - 2) + 1,
                  "%s case %u: statistics add up", scene_name, c);
        } else {
            CHECK(0, "%s case %u: set up", scene_name, c);
        }
        mlod_atlas_destroy(a);
        mlod_atlas_destroy(ref);
        mlod_view_tree_destroy(t);
        free(vs);
        free(vs2);
        free_views(&v);
    }
}

/* ========================================================= conservative */

/* Does an eye e with direction dir and half fov see any point of the
   sphere?  (long double) */
static int sees_sphere(const float *e, const float *dir, float fov, const float *sphere)
{
    long double x[3], d = 0, dl = 0, dot = 0, ang;
    int k;
    for (k = 0; k < 3; k++) {
        x[k] = (long double)sphere[k] - e[k];
        d += x[k] * x[k];
        dl += (long double)dir[k] * dir[k];
        dot += x[k] * dir[k];
    }
    d = sqrtl(d);
    if (d <= sphere[3]) return 1;
    ang = acosl(fmaxl(-1.0L, fminl(1.0L, dot / (d * sqrtl(dl)))));
    return ang <= (long double)fov + asinl((long double)sphere[3] / d);
}

/* Can some normal of the cone at some point of the sphere face the eye? */
static int faces_eye(const float *e, const float *sphere, const float *cone)
{
    long double x[3], d = 0, dot = 0, ang;
    int k;
    if (cone[3] >= TU_PI / 2) return 1;
    for (k = 0; k < 3; k++) {
        x[k] = (long double)e[k] - sphere[k];
        d += x[k] * x[k];
        dot += x[k] * cone[k];
    }
    d = sqrtl(d);
    if (d <= sphere[3]) return 1;
    ang = acosl(fmaxl(-1.0L, fminl(1.0L, dot / d)));
    return ang <= TU_PI / 2 + (long double)cone[3] + asinl((long double)sphere[3] / d);
}

/* Culled pairs of views v (per-view fields of view, or half_fov for all)
   sampled against brute force; floor: how many were culled by the eyes'
   floor (mlod__below_floor) alone, at least. */
static void check_culling(const mlod_tree *scene, views *v, int per_view_fov, float half_fov, const char *name,
                          uint32_t floor_least)
{
    mlod_view_set s = view_set(v, 1, per_view_fov);
    mlod_view_tree *t;
    mlod__mv_job job;
    uint64_t rng = 5;
    uint32_t trial, culled = 0, wrong = 0, not_implied = 0, back = 0, back_wrong = 0, by_floor_only = 0;
    s.half_fov = half_fov;
    t = build_views(&s, NULL);
    if (!t) return;
    job = pair_job(scene, t, 8, MLOD_VIEW_CULL_BACKFACES);
    for (trial = 0; trial < 20000; trial++) {
        uint32_t vn_index = (uint32_t)(scene_rng_double(&rng) * (t->eyes->leaf_count - 1));
        uint32_t s_index = (uint32_t)(scene_rng_double(&rng) * scene->node_count);
        const float *sphere = scene->spheres + 4 * (size_t)s_index;
        mlod__vnode vn;
        double x[3], d;
        int k, by_fov;
        mlod__vnode_set(&job, vn_index, &vn);
        for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - vn.centre[k];
        d = mlod__length3(x);
        if (mlod__pair_action(&job, &vn, s_index) != MLOD__PAIR_CULL) continue;
        culled++;
        by_fov = mlod__outside_cone(x, d, sphere[3] + vn.radius, vn.cone, vn.most_fov, 1.0 / 1073741824.0);
        if (!by_fov && vn.slab && mlod__below_floor(x, d, sphere[3], &vn)) { /* the eyes' floor: as the field of view */
            by_fov = 1;
            by_floor_only++;
        }
        if (!by_fov) back++;
        {
            uint32_t n = t->eyes->leaf_count, j;
            for (j = 0; j < n; j++) { /* every view below vn_index */
                uint32_t node = n - 1 + j, view = t->eyes->leaf_sources[j], leaves = 0;
                const float *e = v->eyes + 3 * view;
                const float *cone = t->eyes->cones + 4 * (size_t)(n - 1 + j);
                double y[3];
                while (node > vn_index) node = (node - 1) / 2;
                if (node != vn_index) continue;
                for (k = 0; k < 3; k++) y[k] = (double)sphere[k] - e[k];
                if (by_fov) {
                    float fov = per_view_fov ? v->fovs[view] : half_fov;
                    if (!mlod__outside_cone(y, mlod__length3(y), sphere[3], cone, fov, 0.0)) not_implied++;
                    if (sees_sphere(e, v->directions + 3 * view, fov, sphere)) wrong++;
                } else {
                    /* back-face culled: no leaf below the scene node (up to 64) faces the eye */
                    uint32_t stack[64], top = 0;
                    stack[top++] = s_index;
                    while (top && leaves < 64) {
                        uint32_t node2 = stack[--top];
                        if (node2 >= scene->leaf_count - 1) {
                            leaves++;
                            if (faces_eye(e, scene->spheres + 4 * (size_t)node2, scene->cones + 4 * (size_t)node2))
                                back_wrong++;
                            continue;
                        }
                        stack[top++] = 2 * node2 + 2;
                        stack[top++] = 2 * node2 + 1;
                    }
                    {
                        mlod_view mv = mlod_megaviews_view(e, 8, MLOD_VIEW_CULL_BACKFACES);
                        int culled_there = 0;
                        mlod__pview pv;
                        mlod__view_prepare(&mv, &pv, NULL);
                        mlod__evaluate(&pv, sphere, scene->cones + 4 * (size_t)s_index, &culled_there);
                        if (!culled_there) not_implied++;
                    }
                }
            }
        }
    }
    CHECK(culled > 200 && back > 20 && by_floor_only >= floor_least,
          "culling, %s: %u culled pairs sampled (%u back-facing, %u by the eyes' floor alone): enough to test", name,
          culled, back, by_floor_only);
    CHECK(wrong == 0, "culling, %s: %u culled (view, scene node) pairs where the view sees the sphere", name, wrong);
    CHECK(back_wrong == 0, "culling, %s: %u back-face culled pairs where a leaf below faces the eye", name, back_wrong);
    CHECK(not_implied == 0, "culling, %s: %u culled pairs a view below would not cull itself", name, not_implied);
    mlod_view_tree_destroy(t);
}

/* count virtual point lights just above the room's floor, facing up (a
   quarter tilted by up to 0.3 rad): the eyes' floor (mlod__below_floor)
   culls the floor's own nodes for them, with hemispheres (half_fov 0: pi/2
   rounded to float, a hair above). */
static views make_floor_lights(uint64_t seed, uint32_t count)
{
    static const float lo[3] = {-1.9f, 0.05f, -1.9f}, hi[3] = {1.9f, 0.15f, 1.9f};
    views v = make_views(seed, count, lo, hi, 0);
    uint64_t rng = seed + 1;
    uint32_t i;
    for (i = 0; i < v.count; i++) {
        float *n = v.directions + 3 * i;
        double tilt = i % 4 == 0 ? 0.3 * scene_rng_double(&rng) : 0.0, turn = 2.0 * TU_PI * scene_rng_double(&rng);
        n[0] = (float)(sin(tilt) * cos(turn));
        n[1] = (float)cos(tilt);
        n[2] = (float)(sin(tilt) * sin(turn));
    }
    return v;
}

static void test_culling(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    views v = make_views(7, 400, lo, hi, 0), lights = make_floor_lights(8, 400);
    check_culling(scene, &v, 1, 0.0f, "random views", 0);
    check_culling(scene, &lights, 0, 0.0f, "lights above the floor", 50);
    free_views(&v);
    free_views(&lights);
}

/* ============================================ the bounds sharing rests on */

static void test_bounds(void)
{
    uint64_t rng = 3;
    uint32_t trial, tested = 0, moved = 0, bad_max = 0, bad_min = 0, bad_motion = 0, oriented = 0;
    double worst = 0.0;
    for (trial = 0; trial < 4000; trial++) {
        double c[3], x[3], xm[3], d, rho = 0.5 * scene_rng_double(&rng), r = 0.3 * scene_rng_double(&rng), cmax, cmin;
        double S = 8.0, dir[3], motion, fd[3], ud[3];
        float sphere[4], cf[3], forward[3] = {0, 0, 0}, up[3] = {0, 0, 0};
        const double *in_map;
        mlod__mv_job job;
        mlod_view mv;
        mlod__pview pc;
        mlod__disc dc[2];
        int k, bc[2], sample;
        tu_random_unit(&rng, dir);
        /* odd trials: maps of a random orientation, the bounds reading x in their frame */
        tu_random_unit(&rng, fd);
        tu_random_unit(&rng, ud);
        for (k = 0; trial % 2 && k < 3; k++) {
            forward[k] = (float)(fd[k] * 2.5);
            up[k] = (float)ud[k];
        }
        memset(&job, 0, sizeof job);
        if (!mlod__mv_orient(&job, forward, up)) continue; /* (nearly) parallel: not a frame */
        d = 0.05 + 3.0 * scene_rng_double(&rng);
        for (k = 0; k < 3; k++) {
            c[k] = scene_rng_range(&rng, -1, 1);
            cf[k] = (float)c[k];
            sphere[k] = (float)(c[k] + d * dir[k]);
        }
        sphere[3] = (float)r;
        for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - (double)cf[k];
        d = mlod__length3(x);
        in_map = mlod__map_coords(x, job.axes[0], job.oriented, xm);
        mlod__ball_diameters(S, in_map, d, r, rho, &cmax, &cmin);
        motion = mlod__ball_motion(S, in_map, d, r, rho);
        oriented += job.oriented;
        mv = mlod_megaviews_view_oriented(cf, 16, 0, forward, up);
        mlod__view_prepare(&mv, &pc, NULL);
        for (k = 0; k < 2; k++) {
            double centre[3] = {sphere[0], sphere[1], sphere[2]};
            bc[k] = tu_image_disc(&pc, k, centre, r, &dc[k]) && mlod__reached(&pc, sphere) >> k & 1u;
        }
        for (sample = 0; sample < 16; sample++) {
            double y[3], len = rho * pow(scene_rng_double(&rng), 1.0 / 3.0);
            float e[3];
            mlod__pview pe;
            int culled;
            double ce;
            tu_random_unit(&rng, y);
            for (k = 0; k < 3; k++) e[k] = (float)(c[k] + len * y[k]);
            {
                double off[3] = {(double)e[0] - cf[0], (double)e[1] - cf[1], (double)e[2] - cf[2]};
                if (mlod__length3(off) > rho) continue; /* rounding left the ball */
            }
            mv = mlod_megaviews_view_oriented(e, 16, 0, forward, up);
            mlod__view_prepare(&mv, &pe, NULL);
            ce = mlod__evaluate(&pe, sphere, NULL, &culled);
            tested++;
            if (ce > cmax) bad_max++;
            if (ce < cmin) bad_min++;
            if (motion < INFINITY) {
                for (k = 0; k < 2; k++) {
                    mlod__disc de;
                    double centre[3] = {sphere[0], sphere[1], sphere[2]}, shift;
                    if (!bc[k] || !(mlod__reached(&pe, sphere) >> k & 1u)) continue;
                    if (!tu_image_disc(&pe, k, centre, r, &de)) {
                        bad_motion++;
                        continue;
                    }
                    /* every point of one disc within `motion` of the other: centres and radii */
                    shift = sqrt((de.x - dc[k].x) * (de.x - dc[k].x) + (de.y - dc[k].y) * (de.y - dc[k].y)) +
                            fabs(de.radius - dc[k].radius);
                    moved++;
                    if (shift > motion * (1 + 1e-9)) bad_motion++;
                    if (motion > 0 && shift / motion > worst) worst = shift / motion;
                }
            }
        }
    }
    CHECK(tested > 30000 && moved > 10000 && oriented > 1900, "bounds: %u eyes sampled, %u motions, %u of 4000 "
          "spheres in maps of a random orientation", tested, moved, oriented);
    CHECK(bad_max == 0, "bounds: %u eyes see a diameter above cmax", bad_max);
    CHECK(bad_min == 0, "bounds: %u eyes see a diameter below cmin", bad_min);
    CHECK(bad_motion == 0, "bounds: %u images moved beyond the motion bound", bad_motion);
    CHECK(worst > 0.3, "bounds: the motion bound is not vacuous (largest shift / bound %.3f)", worst);
}

/* ================================================= delta > 0: fusion */

/* With delta > 0, each pixel of each view holds a node (read from the
   colour channel, set to the node's index) whose depth is exactly its
   distance from the view's own eye (the fusion's correction), whose
   normal is its cone's axis, whose image from that eye lies within
   delta of the pixel (the disc's radius plus delta, plus the pixel
   holding a disc's centre), which the view itself would not cull facing
   away, and which, where the view's field of view culls it (shared from
   above: with delta > 0 fields of view act only in culling), lies at a
   pixel outside that field of view, but for the angle delta plus the
   pixel holding a disc's centre span there; and the views share. */
/* The scene's colours set to its node indices (red), so that an atlas says
   which node each pixel holds. */
static void colours_are_node_indices(mlod_tree *scene)
{
    uint32_t i;
    for (i = 0; i < scene->node_count; i++) {
        scene->colors[3 * (size_t)i] = (float)i;
        scene->colors[3 * (size_t)i + 1] = scene->colors[3 * (size_t)i + 2] = 0.0f;
    }
}

static void test_fusion(mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const float deltas[3] = {MLOD_MEGAVIEWS_DELTA, 2.0f, MLOD_MEGAVIEWS_DELTA};
    static const uint32_t resolutions[3] = {8, 8, 24};
    views v = make_views(41, 900, lo, hi, 0);
    uint32_t i, d;
    colours_are_node_indices(scene);
    for (d = 0; d < 3; d++) {
        mlod_view_set s = view_set(&v, d > 0, d > 0);
        mlod_view_tree *t = build_views(&s, NULL);
        mlod_view *vs = NULL;
        uint32_t flags = d == 1 ? MLOD_VIEW_CULL_BACKFACES : 0u;
        mlod_atlas *a = make_atlas(&v, resolutions[d], MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, &vs, flags);
        mlod_megaviews_params p;
        mlod_megaviews_stats st;
        mlod_error e;
        uint64_t filled = 0, bad_depth = 0, bad_normal = 0, far_off = 0, culled = 0, outside = 0, inside = 0;
        uint64_t other_half = 0, off_plane = 0; /* drawn into a half the node does not reach from the eye */
        /* the angle delta + the centre pixel's 0.7072 px span at most: 2 / R map units a pixel, the
           paraboloid's map r = tan(phi / 2) turning at most 2 rad per unit */
        double worst = 0.0, deepest = -TU_PI, reach = 2.0 * (deltas[d] + 0.7072) * 2.0 / resolutions[d];
        memset(&p, 0, sizeof p);
        p.epsilon = 1.0f;
        p.delta = deltas[d];
        p.resolution = resolutions[d];
        p.flags = flags;
        if (!t || !a || mlod_megaviews_render(a, scene, t, &p, &st, &e) != MLOD_OK) {
            CHECK(0, "fusion: render");
            continue;
        }
        for (i = 0; i < v.count; i++) {
            const uint32_t *tile = a->tiles + 4 * (size_t)i;
            uint32_t row, col;
            mlod__pview pv;
            mlod__view_prepare(&vs[i], &pv, NULL);
            for (row = 0; row < tile[3]; row++)
                for (col = 0; col < tile[2]; col++) {
                    size_t at = (size_t)(tile[1] + row) * a->width + tile[0] + col;
                    uint32_t node = (uint32_t)a->color[3 * at];
                    const float *sph = scene->spheres + 4 * (size_t)node;
                    double x[3], centre[3], dist;
                    mlod__disc disc;
                    int k;
                    if (!(a->depth[at] < INFINITY)) continue;
                    filled++;
                    for (k = 0; k < 3; k++) {
                        centre[k] = sph[k];
                        x[k] = (double)sph[k] - v.eyes[3 * i + k];
                    }
                    if (a->depth[at] != fused_depth(&pv, scene, node, col, row, x)) bad_depth++;
                    if (memcmp(a->normal + 3 * at, scene->cones + 4 * (size_t)node, 12)) bad_normal++;
                    if (d > 0) {
                        const float *dir = v.directions + 3 * i;
                        double len = sqrt((double)dir[0] * dir[0] + (double)dir[1] * dir[1] + (double)dir[2] * dir[2]);
                        float cone[4] = {(float)(dir[0] / len), (float)(dir[1] / len), (float)(dir[2] / len), 0.0f};
                        float origin[3], ray[3];
                        int away = 0;
                        mlod__evaluate(&pv, sph, scene->cones + 4 * (size_t)node, &away);
                        if (away) culled++;
                        if (mlod__outside_cone(x, mlod__length3(x), sph[3], cone, v.fovs[i], 0.0)) {
                            /* how far inside the field of view its pixel's ray lies */
                            double ray_d[3], axis[3], in;
                            outside++;
                            if (!mlod_view_pixel_ray(&vs[i], col + 0.5f, row + 0.5f, origin, ray)) continue;
                            for (k = 0; k < 3; k++) ray_d[k] = ray[k], axis[k] = cone[k];
                            in = v.fovs[i] - mlod__angle(ray_d, axis);
                            if (in > deepest) deepest = in;
                            if (in > reach) inside++;
                        }
                    }
                    if ((col < p.resolution ? x[2] : -x[2]) + sph[3] < 0.0) { /* the half's culling plane */
                        other_half++;
                        off_plane += fabs(x[2]) - sph[3] > t->eyes->spheres[3]; /* within the root's rho, any ball's */
                    }
                    if (!tu_image_disc(&pv, col < p.resolution ? 0 : 1, centre, sph[3], &disc)) {
                        far_off++;
                        continue;
                    }
                    dist = sqrt((col + 0.5 - disc.x) * (col + 0.5 - disc.x) + (row + 0.5 - disc.y) * (row + 0.5 - disc.y));
                    if (dist > disc.radius + p.delta + 0.7072) far_off++;
                    if (dist - disc.radius > worst) worst = dist - disc.radius;
                }
        }
        CHECK(st.shared_draws > 1000 && st.shared_views > 2 * st.shared_draws,
              "fusion, delta %g: %llu shared draws for %llu views", p.delta, (unsigned long long)st.shared_draws,
              (unsigned long long)st.shared_views);
        /* scene leaves larger than epsilon shared too (MegaViews 3.2.4): the checks above hold for them */
        CHECK(st.shared_leaves > 0 && st.shared_leaves < st.shared_draws,
              "fusion, delta %g: %llu oversize scene leaves shared (of %llu shared draws)", p.delta,
              (unsigned long long)st.shared_leaves, (unsigned long long)st.shared_draws);
        CHECK(filled > v.count * 64, "fusion, delta %g: %llu pixels filled", p.delta, (unsigned long long)filled);
        CHECK(bad_depth == 0, "fusion, delta %g: %llu pixels whose depth is not the distance from the view's eye",
              p.delta, (unsigned long long)bad_depth);
        CHECK(bad_normal == 0, "fusion, delta %g: %llu pixels whose normal is not their node's", p.delta,
              (unsigned long long)bad_normal);
        CHECK(culled == 0, "fusion, delta %g: %llu pixels hold a node their view culls facing away", p.delta,
              (unsigned long long)culled);
        CHECK(inside == 0, "fusion, delta %g, R %u: %llu pixels within the field of view (by more than %.3f rad, "
              "up to %.3f) hold a node it culls", p.delta, p.resolution, (unsigned long long)inside, reach, deepest);
        CHECK(d == 0 || outside > 0, "fusion, delta %g, R %u: nodes shared outside some field of view (%llu pixels)",
              p.delta, p.resolution, (unsigned long long)outside);
        CHECK(off_plane == 0,
              "fusion, delta %g: %llu pixels in a half their node does not reach from the eye (%llu farther than rho "
              "from the plane between the halves)", p.delta, (unsigned long long)other_half, (unsigned long long)off_plane);
        CHECK(far_off == 0, "fusion, delta %g: %llu pixels farther than delta from their node's image (worst %.3f px)",
              p.delta, (unsigned long long)far_off, worst);
        CHECK(worst > 0.25, "fusion, delta %g: shared images do move (worst %.3f px beyond the disc)", p.delta,
              worst);
        mlod_atlas_destroy(a);
        mlod_view_tree_destroy(t);
        free(vs);
    }
    free_views(&v);
}

/* ============================================================= groups */

/* The scene's colours set to node indices.  With a group radius
   that holds every eye, the root is one group: every view's tile holds, per
   pixel, the node that one view at the root's centre draws there (its cut
   and splat), at the distance from the view's own eye.  With a smaller
   radius, depths stay exact per eye and the atlas is the same for any
   thread count. */
static void test_groups(mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    views v = make_views(51, 300, lo, hi, 1);
    mlod_view_set s = view_set(&v, 0, 0);
    mlod_view_tree *t = build_views(&s, NULL);
    mlod_view *vs = NULL, centre_view;
    mlod_atlas *a = make_atlas(&v, 8, MLOD_ATLAS_COLOR, &vs, 0), *one = NULL;
    mlod_atlas_desc desc;
    mlod_cut *cut = NULL;
    mlod_cut_params cp;
    mlod_megaviews_params p;
    mlod_megaviews_stats st;
    mlod_error e;
    uint64_t wrong_node = 0, wrong_depth = 0, filled = 0;
    uint32_t i, row, col, g;
    colours_are_node_indices(scene);
    if (!t || !a) {
        CHECK(0, "groups: set-up");
        return;
    }
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.resolution = 8;
    p.group_radius = 1e6f;
    centre_view = mlod_megaviews_view(t->eyes->spheres, 8, 0);
    memset(&desc, 0, sizeof desc);
    desc.channels = MLOD_ATLAS_COLOR;
    memset(&cp, 0, sizeof cp);
    cp.epsilon = 1.0f;
    CHECK(mlod_megaviews_render(a, scene, t, &p, &st, &e) == MLOD_OK, "groups: render with one group");
    CHECK(mlod_atlas_create(&centre_view, 1, &desc, NULL, &one, &e) == MLOD_OK && mlod_cut_create(1, NULL, &cut, &e) == MLOD_OK &&
          mlod_cut_update(cut, scene, &centre_view, &cp, &e) == MLOD_OK &&
          mlod_splat(one, scene, cut, &centre_view, NULL, &e) == MLOD_OK, "groups: the centre's view");
    CHECK(st.leaf_draws == 0 && st.shared_draws == (uint64_t)mlod_cut_get(cut, 0).drawn + mlod_cut_get(cut, 0).oversize,
          "groups: one group draws the centre's cut once (%llu shared draws)", (unsigned long long)st.shared_draws);
    for (i = 0; i < v.count && one; i++) {
        const uint32_t *tile = a->tiles + 4 * (size_t)i;
        for (row = 0; row < tile[3]; row++)
            for (col = 0; col < tile[2]; col++) {
                size_t at = (size_t)(tile[1] + row) * a->width + tile[0] + col, ref = (size_t)row * one->width + col;
                uint32_t node;
                if ((a->depth[at] < INFINITY) != (one->depth[ref] < INFINITY) ||
                    (a->depth[at] < INFINITY && a->color[3 * at] != one->color[3 * ref])) {
                    wrong_node++;
                    continue;
                }
                if (!(a->depth[at] < INFINITY)) continue;
                filled++;
                node = (uint32_t)a->color[3 * at];
                if (a->depth[at] != fused_depth_at(&v, i, p.resolution, scene, node, col, row)) wrong_depth++;
            }
    }
    CHECK(filled > v.count * 100, "groups: %llu pixels filled", (unsigned long long)filled);
    CHECK(wrong_node == 0, "groups: %llu pixels hold another node than the centre's view", (unsigned long long)wrong_node);
    CHECK(wrong_depth == 0, "groups: %llu pixels not at their node's distance from the view's eye",
          (unsigned long long)wrong_depth);
    /* a radius that makes many small groups: same atlas for any hook, fewer pairs than without */
    for (g = 0; g < 2; g++) {
        mlod_pool *pool = mlod_pool_create(3);
        mlod_parallel hook = mlod_pool_parallel(pool), reverse;
        mlod_view *vs2 = NULL, *vs3 = NULL;
        mlod_atlas *b1 = make_atlas(&v, 8, MLOD_ATLAS_COLOR, &vs2, 0), *b2 = make_atlas(&v, 8, MLOD_ATLAS_COLOR, &vs3, 0);
        mlod_megaviews_stats s1, s2, s0;
        size_t first = 0;
        int same;
        reverse.run = tu_run_reverse;
        reverse.user = NULL;
        p.delta = g ? MLOD_MEGAVIEWS_DELTA : 0.0f;
        p.group_radius = 0.0f;
        p.parallel = NULL;
        CHECK(mlod_megaviews_render(b1, scene, t, &p, &s0, &e) == MLOD_OK, "groups: render without");
        p.group_radius = 0.3f;
        p.parallel = &hook;
        CHECK(mlod_megaviews_render(b1, scene, t, &p, &s1, &e) == MLOD_OK, "groups: render, pool");
        p.parallel = &reverse;
        CHECK(mlod_megaviews_render(b2, scene, t, &p, &s2, &e) == MLOD_OK, "groups: render, reversed");
        same = same_atlas(b1, b2, &first);
        CHECK(same && s1.pairs == s2.pairs, "groups, delta %g: another atlas for another hook (pixel %zu)", p.delta,
              first);
        CHECK(s1.pairs < s0.pairs, "groups, delta %g: %llu pairs with groups, %llu without", p.delta,
              (unsigned long long)s1.pairs, (unsigned long long)s0.pairs);
        for (i = 0, wrong_depth = 0; i < v.count; i++) {
            const uint32_t *tile = b1->tiles + 4 * (size_t)i;
            for (row = 0; row < tile[3]; row++)
                for (col = 0; col < tile[2]; col++) {
                    size_t at = (size_t)(tile[1] + row) * b1->width + tile[0] + col;
                    if (!(b1->depth[at] < INFINITY)) continue;
                    if (b1->depth[at] != fused_depth_at(&v, i, p.resolution, scene,
                                                        (uint32_t)b1->color[3 * at], col, row))
                        wrong_depth++;
                }
        }
        CHECK(wrong_depth == 0, "groups, delta %g: %llu pixels not at their node's distance from the eye", p.delta,
              (unsigned long long)wrong_depth);
        mlod_atlas_destroy(b1);
        mlod_atlas_destroy(b2);
        free(vs2);
        free(vs3);
        mlod_pool_destroy(pool);
    }
    mlod_cut_destroy(cut);
    mlod_atlas_destroy(one);
    mlod_atlas_destroy(a);
    mlod_view_tree_destroy(t);
    free(vs);
    free_views(&v);
}

/* ============================================================== query */

/* The unfused maps, queried pixel by pixel down the view tree, equal the
   fused atlas (depth, and the node through the colour channel holding
   node indices), with sharing, fields of view, back faces and groups. */
/* The maps of a render queried with a view tree or a scene that cannot be
   the render's: 0, nothing read past the maps' tables (AddressSanitizer
   watches). */
static void query_other_trees(const mlod_megaviews_maps *maps, const mlod_tree *scene, const mlod_view_tree *t,
                              const views *v)
{
    static const float lo[3] = {-1, 0.5f, -1}, hi[3] = {1, 2, 1};
    views few = make_views(62, 2, lo, hi, 0), more = make_views(63, 4 * v->count, lo, hi, 0);
    mlod_view_set s_few = view_set(&few, 0, 0), s_more = view_set(&more, 0, 0);
    mlod_view_tree *t_few = build_views(&s_few, NULL), *t_more = build_views(&s_more, NULL);
    mlod_megaviews_maps *small = NULL;
    mlod_megaviews_params p;
    mlod_error e;
    scene_mesh room;
    int have_room = scene_room(&room);
    mlod_tree *other = have_room ? tu_build(&room, 500, 3, 0) : NULL;
    uint32_t i, hits = 0, own = 0;
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.resolution = 8;
    CHECK(t_few && t_more && other && mlod_megaviews_render_maps(scene, t_few, &p, &small, NULL, &e) == MLOD_OK,
          "query: renders of other trees");
    if (small && t_more && other) {
        for (i = 0; i < v->count; i++) { /* the maps of 2 views, a tree of 4 x as many: every view in its range */
            hits += mlod_megaviews_query(small, scene, t_more, 4 * i + 3, 15, 7, NULL, NULL);
            hits += mlod_megaviews_query(small, scene, t, i, 15, 7, NULL, NULL);
            hits += mlod_megaviews_query(maps, other, t, i, 8, 4, NULL, NULL); /* another scene */
            own += mlod_megaviews_query(maps, scene, t, i, 8, 4, NULL, NULL);
        }
        CHECK(hits == 0 && own > 0, "query: maps of another view tree or scene give 0 (%u hits; %u of %u own views hit)",
              hits, own, v->count);
    }
    mlod_megaviews_maps_destroy(small);
    mlod_tree_destroy(other);
    if (have_room) scene_free(&room);
    mlod_view_tree_destroy(t_few);
    mlod_view_tree_destroy(t_more);
    free_views(&few);
    free_views(&more);
}

static void test_query(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const float forward[3] = {0.2f, -3.0f, 0.5f}, up[3] = {0.0f, 0.1f, 1.0f};
    views v = make_views(61, 500, lo, hi, 1);
    uint32_t c, i, row, col;
    for (c = 0; c < 4; c++) { /* 3: maps of another orientation, which the maps keep for the query */
        mlod_view_set s = view_set(&v, c > 0, c > 0);
        mlod_view_tree *t = build_views(&s, NULL);
        mlod_view *vs = NULL;
        uint32_t flags = c == 2 ? MLOD_VIEW_CULL_BACKFACES : 0u;
        mlod_atlas *a = make_atlas(&v, 8, MLOD_ATLAS_COLOR, &vs, flags);
        mlod_megaviews_maps *maps = NULL;
        mlod_megaviews_params p;
        mlod_megaviews_stats st_a, st_m;
        mlod_error e;
        uint64_t compared = 0, differ = 0, filled = 0;
        memset(&p, 0, sizeof p);
        p.epsilon = 1.0f;
        p.delta = MLOD_MEGAVIEWS_DELTA;
        p.resolution = 8;
        p.flags = flags;
        p.group_radius = c == 1 ? 0.2f : 0.0f;
        if (c == 3) {
            memcpy(p.forward, forward, sizeof forward);
            memcpy(p.up, up, sizeof up);
        }
        if (!t || !a || mlod_megaviews_render(a, scene, t, &p, &st_a, &e) != MLOD_OK ||
            mlod_megaviews_render_maps(scene, t, &p, &maps, &st_m, &e) != MLOD_OK) {
            CHECK(0, "query case %u: renders", c);
        } else {
            for (i = 0; i < v.count; i++) {
                const uint32_t *tile = a->tiles + 4 * (size_t)i;
                for (row = 0; row < tile[3]; row++)
                    for (col = 0; col < tile[2]; col++) {
                        size_t at = (size_t)(tile[1] + row) * a->width + tile[0] + col;
                        float depth = -1.0f;
                        uint32_t node = 0;
                        int hit = mlod_megaviews_query(maps, scene, t, i, col, row, &depth, &node);
                        compared++;
                        filled += hit;
                        if (hit != (a->depth[at] < INFINITY) ||
                            (hit && (memcmp(&depth, &a->depth[at], 4) || (float)node != a->color[3 * at])))
                            differ++;
                    }
            }
            CHECK(filled > compared / 2 && st_a.shared_draws > 1000, "query case %u: %llu of %llu pixels filled, %llu shared draws",
                  c, (unsigned long long)filled, (unsigned long long)compared, (unsigned long long)st_a.shared_draws);
            CHECK(differ == 0, "query case %u: %llu pixels differ from the fused atlas", c, (unsigned long long)differ);
            CHECK(st_m.pairs == st_a.pairs && st_m.shared_draws == st_a.shared_draws && st_m.leaf_draws == st_a.leaf_draws &&
                  st_m.shared_leaves == st_a.shared_leaves,
                  "query case %u: the same traversal (pairs %llu / %llu)", c, (unsigned long long)st_m.pairs,
                  (unsigned long long)st_a.pairs);
            CHECK(mlod_megaviews_maps_bytes(maps) > (size_t)v.count * 8 * 16,
                  "query case %u: the maps report their bytes (%zu)", c, mlod_megaviews_maps_bytes(maps));
            CHECK(!mlod_megaviews_query(maps, scene, t, v.count, 0, 0, NULL, NULL) &&
                  !mlod_megaviews_query(maps, scene, t, 0, 16, 0, NULL, NULL) &&
                  !mlod_megaviews_query(maps, scene, t, 0, 0, 8, NULL, NULL) && !mlod_megaviews_query(NULL, scene, t, 0, 0, 0, NULL, NULL),
                  "query: out of range is 0");
            if (c == 0) query_other_trees(maps, scene, t, &v);
        }
        mlod_megaviews_maps_destroy(maps);
        mlod_atlas_destroy(a);
        mlod_view_tree_destroy(t);
        free(vs);
    }
    free_views(&v);
}

/* ======================================================== orientation */

static int same_view(const mlod_view *a, const mlod_view *b)
{
    return a->kind == b->kind && !memcmp(a->position, b->position, 12) && !memcmp(a->forward, b->forward, 12) &&
           !memcmp(a->up, b->up, 12) && a->width == b->width && a->height == b->height && a->flags == b->flags;
}

/* The maps' orientation (params.forward, up).  mlod_megaviews_view_oriented
   gives mlod_megaviews_view's map for none (NULL or 0) and copies any
   other; a light's straight down lands in the middle of the front half
   with forward -y, on the rim of both halves by default.  With delta 0
   and no groups the render equals, bit for bit, each view's basic cut and
   mlod_splat of its oriented map (down: forward -y, up +z; an oblique
   frame of random axes, not unit), with and without directions and
   fields of view, back-face culling, duplicate eyes, both scenes, and
   differs from the default's.  Frames equal to the default's, (0, 0, 1)
   and (0, 1, 0) at any length, render the default's atlas and
   statistics bit for bit, with sharing and groups.  In an oblique frame,
   with sharing and groups, the float pair filter and the exact path, and
   the subtree walks from any level, give the same atlas and
   statistics. */
static void test_orientation(const mlod_tree *scene, const mlod_tree *bare)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const float down[3] = {0, -1, 0}, north[3] = {0, 0, 1}, zero[3] = {0, 0, 0};
    float oblique[2][3];
    const float *frames[2][2];
    uint64_t rng = 4242;
    double fd[3], ud[3];
    uint32_t c, i;
    int k;
    tu_random_unit(&rng, fd);
    tu_random_unit(&rng, ud);
    for (k = 0; k < 3; k++) {
        oblique[0][k] = (float)(1.7 * fd[k]);
        oblique[1][k] = (float)(0.6 * ud[k]);
    }
    frames[0][0] = down;
    frames[0][1] = north;
    frames[1][0] = oblique[0];
    frames[1][1] = oblique[1];
    { /* the view */
        const float eye[3] = {0.5f, 2.5f, -0.25f}, below[3] = {0.5f, 0.5f, -0.25f}, up[3] = {0, 1, 0};
        mlod_view a = mlod_megaviews_view(eye, 8, MLOD_VIEW_CULL_BACKFACES);
        mlod_view b = mlod_megaviews_view_oriented(eye, 8, MLOD_VIEW_CULL_BACKFACES, NULL, NULL);
        mlod_view z = mlod_megaviews_view_oriented(eye, 8, MLOD_VIEW_CULL_BACKFACES, zero, zero);
        mlod_view d = mlod_megaviews_view_oriented(eye, 8, 0, down, north);
        mlod_view bad = mlod_megaviews_view_oriented(eye, 8, 0, zero, up);
        mlod_error e;
        float pa[2] = {0, 0}, pd[2] = {0, 0}, depth_a = 0.0f, depth_d = 0.0f;
        CHECK(same_view(&a, &b) && same_view(&a, &z) && a.forward[2] == 1.0f && a.up[1] == 1.0f,
              "orientation: none (NULL or 0) gives mlod_megaviews_view's map, forward +z, up +y");
        CHECK(!memcmp(d.forward, down, 12) && !memcmp(d.up, north, 12) && d.width == 16 && d.height == 8 &&
              d.kind == MLOD_VIEW_DUAL_PARABOLOID && mlod_view_check(&d, &e) == MLOD_OK,
              "orientation: forward and up copied into the map's view");
        CHECK(mlod_view_check(&bad, &e) == MLOD_ERROR_BAD_VIEW,
              "orientation: a zero forward with a nonzero up is copied, and mlod_view_check refuses it");
        /* straight down from a ceiling light: the middle of the front half with forward -y; the seam by default */
        CHECK(mlod_view_project(&d, below, pd, &depth_d) && fabsf(pd[0] - 4.0f) < 1e-4f && fabsf(pd[1] - 4.0f) < 1e-4f,
              "orientation: straight down lands in the middle of the front half with forward -y (%g, %g)", pd[0],
              pd[1]);
        CHECK(mlod_view_project(&a, below, pa, &depth_a) &&
                  fabs(hypot(pa[0] - 4.0, pa[1] - 4.0) - 4.0) < 1e-3 && depth_a == depth_d && depth_d == 2.0f,
              "orientation: by default straight down lands on the front half's rim, the seam (%g, %g)", pa[0], pa[1]);
    }
    { /* delta 0: the per-view cut and splat of the oriented maps, bit for bit */
        struct {
            int frame, scene, directions, per_view, backfaces, dup;
            uint32_t views, resolution;
            float epsilon;
        } cases[] = {{0, 0, 0, 0, 0, 0, 200, 8, 1.0f}, {1, 0, 1, 1, 0, 0, 200, 7, 1.5f}, {1, 0, 0, 0, 1, 1, 150, 8, 1.0f},
                     {0, 0, 1, 0, 1, 0, 150, 5, 2.5f}, {1, 1, 0, 0, 0, 0, 150, 8, 1.0f}, {0, 1, 1, 1, 0, 1, 120, 6, 1.0f}};
        for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            const mlod_tree *sc = cases[c].scene ? bare : scene;
            const float *forward = frames[cases[c].frame][0], *up = frames[cases[c].frame][1];
            views v = make_views(700 + c, cases[c].views, lo, hi, cases[c].dup);
            mlod_view_set s = view_set(&v, cases[c].directions, cases[c].per_view);
            mlod_view_tree *t = build_views(&s, NULL);
            uint32_t flags = cases[c].backfaces ? MLOD_VIEW_CULL_BACKFACES : 0u;
            uint32_t channels = (sc->cones ? MLOD_ATLAS_NORMAL : 0u) | (sc->colors ? MLOD_ATLAS_COLOR : 0u);
            mlod_view *vs = NULL;
            mlod_atlas *a = make_atlas(&v, cases[c].resolution, channels, NULL, flags);
            mlod_atlas *ref = make_atlas_axes(&v, cases[c].resolution, channels, &vs, flags, NULL, forward, up);
            mlod_atlas *plain = make_atlas(&v, cases[c].resolution, channels, NULL, flags);
            mlod_megaviews_params p;
            mlod_megaviews_stats st;
            mlod_error e;
            uint64_t drawn = 0;
            size_t first = 0, n, differ = 0;
            memset(&p, 0, sizeof p);
            p.epsilon = cases[c].epsilon;
            p.resolution = cases[c].resolution;
            p.flags = flags;
            memcpy(p.forward, forward, 12);
            memcpy(p.up, up, 12);
            if (!cases[c].per_view && cases[c].directions)
                for (i = 0; i < v.count; i++) v.fovs[i] = (float)(0.5 * TU_PI); /* the reference's fov */
            if (t && a && ref && plain && mlod_megaviews_render(a, sc, t, &p, &st, &e) == MLOD_OK) {
                reference_render(ref, sc, vs, &v, cases[c].directions, p.epsilon, &drawn);
                CHECK(same_atlas(a, ref, &first), "orientation case %u: delta 0 differs from the per-view cut and "
                      "splat of the oriented maps at pixel %zu (%g against %g)", c, first, a->depth[first],
                      ref->depth[first]);
                CHECK(cases[c].dup ? st.shared_draws > 0 : st.leaf_draws == drawn,
                      "orientation case %u: %llu leaf draws, %llu shared; the per-view cuts draw %llu", c,
                      (unsigned long long)st.leaf_draws, (unsigned long long)st.shared_draws,
                      (unsigned long long)drawn);
                memset(p.forward, 0, 12);
                memset(p.up, 0, 12);
                CHECK(mlod_megaviews_render(plain, sc, t, &p, NULL, &e) == MLOD_OK, "orientation case %u: %s", c,
                      e.message);
                for (n = 0; n < (size_t)a->width * a->height; n++) differ += memcmp(&a->depth[n], &plain->depth[n], 4) != 0;
                CHECK(differ > n / 4, "orientation case %u: the oriented maps differ from the default's (%zu of %zu "
                      "pixels)", c, differ, n);
            } else {
                CHECK(0, "orientation case %u: set up and render", c);
            }
            mlod_atlas_destroy(a);
            mlod_atlas_destroy(ref);
            mlod_atlas_destroy(plain);
            mlod_view_tree_destroy(t);
            free(vs);
            free_views(&v);
        }
    }
    { /* sharing and groups: the default's frame at any length is the default; an oblique frame takes the filter and
         the walks as the default does */
        static const float z3[3] = {0, 0, 3}, y2[3] = {0, 2.5f, 0}, z1[3] = {0, 0, 1}, y1[3] = {0, 1, 0};
        views v = make_views(720, 1200, lo, hi, 1);
        mlod_view_set s = view_set(&v, 1, 1);
        mlod_view_tree *t = build_views(&s, NULL);
        uint32_t channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, g;
        for (g = 0; g < 2; g++) {
            mlod_atlas *a = make_atlas(&v, 8, channels, NULL, 0), *b = make_atlas(&v, 8, channels, NULL, 0);
            mlod_megaviews_params p;
            mlod_megaviews_stats sa, sb;
            mlod_error e;
            size_t first = 0;
            int same = 1;
            memset(&p, 0, sizeof p);
            p.epsilon = 1.0f;
            p.delta = MLOD_MEGAVIEWS_DELTA;
            p.resolution = 8;
            p.group_radius = g ? 0.25f : 0.0f;
            if (!t || !a || !b || mlod_megaviews_render(a, scene, t, &p, &sa, &e) != MLOD_OK) {
                CHECK(0, "orientation: sharing, set up");
            } else {
                for (i = 0; i < 2; i++) {
                    mlod_megaviews_params q = p;
                    memcpy(q.forward, i ? z3 : z1, 12);
                    memcpy(q.up, i ? y2 : y1, 12);
                    same &= mlod_megaviews_render(b, scene, t, &q, &sb, &e) == MLOD_OK && same_atlas(a, b, &first) &&
                            sa.pairs == sb.pairs && sa.shared_draws == sb.shared_draws &&
                            sa.leaf_draws == sb.leaf_draws && sa.culled == sb.culled;
                }
                CHECK(same && sa.shared_draws > 1000, "orientation, group %g: forward (0, 0, 1) and up (0, 1, 0), at "
                      "any length, render the default's atlas and statistics (%llu shared draws)",
                      (double)p.group_radius, (unsigned long long)sa.shared_draws);
                memcpy(p.forward, oblique[0], 12);
                memcpy(p.up, oblique[1], 12);
                same = mlod__megaviews_run(a, NULL, scene, t, &p, MLOD__MV_WALK_LEVEL, 64, 0, 0, &sa, &e) == MLOD_OK &&
                       mlod__megaviews_run(b, NULL, scene, t, &p, MLOD__MV_WALK_LEVEL, 64, 0, 1, &sb, &e) == MLOD_OK &&
                       same_atlas(a, b, &first) && sa.pairs == sb.pairs && sa.shared_draws == sb.shared_draws &&
                       sa.leaf_draws == sb.leaf_draws && sa.culled == sb.culled && sa.node_pairs == sb.node_pairs;
                CHECK(same && sa.shared_draws > 1000, "orientation, group %g: an oblique frame's float pair filter "
                      "gives the exact path's atlas and statistics (pixel %zu, pairs %llu / %llu, %llu shared)",
                      (double)p.group_radius, first, (unsigned long long)sa.pairs, (unsigned long long)sb.pairs,
                      (unsigned long long)sa.shared_draws);
                for (i = 0; i < 4; i++) { /* the walks from levels 0, 2, 5 and past the last: level by level */
                    static const uint32_t levels[4] = {0, 2, 5, 64};
                    same = mlod__megaviews_run(b, NULL, scene, t, &p, levels[i], i == 0 ? 1 : 4096, 0, 0, &sb, &e) ==
                               MLOD_OK && same_atlas(a, b, &first) && sa.pairs == sb.pairs &&
                           sa.shared_draws == sb.shared_draws && sa.leaf_draws == sb.leaf_draws;
                    CHECK(same, "orientation, group %g: walks from level %u give the same atlas in an oblique frame "
                          "(pixel %zu)", (double)p.group_radius, levels[i], first);
                }
            }
            mlod_atlas_destroy(a);
            mlod_atlas_destroy(b);
        }
        mlod_view_tree_destroy(t);
        free_views(&v);
    }
}

/* ============================================================== walks */

/* Walking each view subtree depth first from any level, with any first
   room for its lists (1: every walk outgrows it and runs again), gives the
   atlas and statistics of the level-synchronous traversal (walk level
   past the last), bit for bit: with sharing, fields of view, back faces,
   groups, and a tree whose leaves lie on two levels. */
static void test_walks(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const uint32_t counts[3] = {700, 1, 257};
    uint32_t c;
    for (c = 0; c < 3; c++) {
        views v = make_views(71 + c, counts[c], lo, hi, 1);
        mlod_view_set s = view_set(&v, c != 1, c == 2);
        mlod_view_tree *t = build_views(&s, NULL);
        mlod_view *vs = NULL;
        uint32_t flags = c == 2 ? MLOD_VIEW_CULL_BACKFACES : 0u, channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
        mlod_atlas *ref = make_atlas(&v, 8, channels, &vs, flags), *a = make_atlas(&v, 8, channels, NULL, flags);
        uint32_t levels = 0, level, g, differ = 0, runs = 0, over = 0;
        mlod_megaviews_params p;
        tu_counter counter;
        mlod_allocator al = tu_allocator(&counter);
        mlod_megaviews_stats st0, st;
        mlod_error e;
        memset(&p, 0, sizeof p);
        memset(&st0, 0, sizeof st0);
        p.epsilon = 1.0f;
        p.delta = MLOD_MEGAVIEWS_DELTA;
        p.resolution = 8;
        p.flags = flags;
        p.allocator = &al;
        for (g = 0; g < 2 && t && ref && a; g++) {
            p.group_radius = g ? 0.3f : 0.0f;
            memset(&counter, 0, sizeof counter);
            if (mlod__megaviews_run(ref, NULL, scene, t, &p, 64, 0, 0, 0, &st0, &e) != MLOD_OK) {
                CHECK(0, "walks case %u: level-synchronous render: %s", c, e.message);
                break;
            }
            levels = st0.levels;
            over += counter.peak_bytes > mlod__mv_bound(t->eyes, p.resolution, st0.node_pairs, 64, 0);
            for (level = 0; level <= levels; level++) {
                uint32_t variant;
                /* a walk's list room of 1 (every walk outgrows it) with a descent's full room, and a large
                   list room with descents of 4 and 37 pairs (groups and single roots outgrow them) */
                for (variant = 0; variant < 4; variant++) {
                    static const uint32_t descend_rooms[4] = {0, 0, 4, 37};
                    size_t first = 0, room = variant == 0 ? 1 : 4096;
                    int same;
                    runs++;
                    memset(&counter, 0, sizeof counter);
                    if (mlod__megaviews_run(a, NULL, scene, t, &p, level, room, descend_rooms[variant], 0, &st, &e) !=
                        MLOD_OK) {
                        CHECK(0, "walks case %u: walk from level %u: %s", c, level, e.message);
                        continue;
                    }
                    /* the sizing bound holds for the pairs per view node the render reports (the
                       allocator's own count, and the render's) */
                    if (counter.peak_bytes > mlod__mv_bound(t->eyes, p.resolution, st.node_pairs, level, room) ||
                        st.peak_bytes > counter.peak_bytes) {
                        if (over++ < 3)
                            CHECK(0, "walks case %u, group %u, level %u, room %zu: peak %zu bytes (reported %zu) above the bound %.0f",
                                  c, g, level, room, counter.peak_bytes, st.peak_bytes,
                                  mlod__mv_bound(t->eyes, p.resolution, st.node_pairs, level, room));
                    }
                    same = same_atlas(a, ref, &first) && st.pairs == st0.pairs && st.culled == st0.culled &&
                           st.shared_draws == st0.shared_draws && st.shared_views == st0.shared_views &&
                           st.shared_leaves == st0.shared_leaves && st.node_pairs == st0.node_pairs &&
                           st.leaf_draws == st0.leaf_draws && st.levels == st0.levels;
                    if (!same && differ++ < 3)
                        CHECK(0, "walks case %u, group %u: walking from level %u (room %zu, descent variant %u) differs (pixel %zu, pairs %llu / %llu)",
                              c, g, level, room, variant, first, (unsigned long long)st.pairs, (unsigned long long)st0.pairs);
                }
            }
            CHECK(c == 1 || st0.shared_draws > (g ? 100u : 1000u), "walks case %u: shares (%llu shared draws)", c,
                  (unsigned long long)st0.shared_draws);
        }
        CHECK(differ == 0 && runs == 2 * 4 * (levels + 1), "walks case %u: %u walk levels x 4 list and descent rooms x 2 group radii equal the level-synchronous render (%u differ)",
              c, levels + 1, differ);
        CHECK(over == 0 && st0.node_pairs > 0 && st0.node_pairs <= st0.pairs && st0.node_pairs <= scene->node_count,
              "walks case %u: every render's peak within the sizing bound for its pairs per view node (%llu; %u above)",
              c, (unsigned long long)st0.node_pairs, over);
        mlod_atlas_destroy(ref);
        mlod_atlas_destroy(a);
        mlod_view_tree_destroy(t);
        free(vs);
        free_views(&v);
    }
}

/* ========================================================== fast paths */

/* The back-face tests' cosine fast paths decide as the exact tests do
   wherever they decide: mlod__surely_backfacing against mlod__outside_cone
   (the sphere grown by rho faces away from every eye), mlod__surely_facing
   against mlod__within_cone (every eye finds a normal facing it), on random
   spheres, balls of eyes and normal cones, the direction to the sphere put
   10^-10 to 10^-1 rad from the test's threshold, a quarter of them nearly
   tangent (r + rho, or rho and r, within 2^-52 to 2^-40 of d and d + rho,
   relatively); and they decide most of them: 99 % of those 1e-6 rad or
   more from the threshold, not nearly tangent. */
static void test_fast_paths(void)
{
    uint64_t rng = 5;
    uint32_t i, n = 400000, wrong[2] = {0, 0}, decided[2] = {0, 0}, tried[2] = {0, 0}, far[2] = {0, 0}, far_decided[2] = {0, 0},
                            tangent[2] = {0, 0};
    const double margin = 1.0 / 1073741824.0;
    for (i = 0; i < n; i++) {
        double axis[3], p[3], x[3], away[3], len, d, r, rho, theta, gamma, offset;
        float cone[4];
        int k, which = (int)(i & 1), near = (i >> 1) % 4 == 0, fast, exact;
        tu_random_unit(&rng, axis);
        theta = i % 5 == 0 ? 0.0 : scene_rng_double(&rng) * 1.7; /* past pi/2 too */
        d = 0.5 + 10.0 * scene_rng_double(&rng);
        r = d * 0.6 * scene_rng_double(&rng);
        rho = i % 7 == 0 ? 0.0 : d * 0.6 * scene_rng_double(&rng);
        if (near && which == 0) { /* r + rho within 2^-52 to 2^-40 of d */
            rho = d * (1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52)) - r;
        } else if (near) { /* rho as near d, r sometimes as near d + rho */
            rho = d * (1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52));
            if (i % 3 == 0) r = (d + rho) * (1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52));
        }
        tu_to_floats(axis, cone, 3);
        cone[3] = tu_float(theta);
        theta = cone[3];
        len = sqrt((double)cone[0] * cone[0] + (double)cone[1] * cone[1] + (double)cone[2] * cone[2]);
        for (k = 0; k < 3; k++) axis[k] = cone[k] / len;
        if (!(which ? d > rho : d > r + rho) || !(d + rho > r)) continue;
        tu_random_perp(&rng, axis, p);
        gamma = 0.5 * 3.14159265358979323846 + theta +
                (which ? asin(r / (d + rho)) - asin(rho / d) : asin((r + rho) / d));
        offset = pow(10.0, -10.0 + 9.0 * scene_rng_double(&rng)) * (scene_rng_double(&rng) < 0.5 ? -1.0 : 1.0);
        gamma += offset;
        if (!(gamma > 0.0 && gamma < 3.14159265358979323846)) continue;
        for (k = 0; k < 3; k++) {
            away[k] = d * (cos(gamma) * axis[k] + sin(gamma) * p[k]); /* -x, gamma off the axis */
            x[k] = -away[k];
        }
        d = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (which == 0) {
            fast = mlod__surely_backfacing(x, d, r + rho, cone);
            exact = mlod__outside_cone(away, d, r + rho, cone, 0.5 * MLOD__PI, margin);
        } else {
            if (!(cone[3] < 0.5 * MLOD__PI)) continue;
            fast = mlod__surely_facing(x, d, r, rho, cone);
            exact = mlod__within_cone(away, d, r, rho, cone, 0.0, 0.5 * MLOD__PI + cone[3]);
        }
        tried[which]++;
        tangent[which] += near;
        far[which] += !near && fabs(offset) >= 1e-6;
        if (fast < 0) continue;
        decided[which]++;
        far_decided[which] += !near && fabs(offset) >= 1e-6;
        if (fast != exact && wrong[which]++ < 3)
            CHECK(0, "%s fast path: %d, exact test: %d (theta %.9g, d %.9g, r %.9g, rho %.9g, %.3g rad off)",
                  which ? "facing" : "back-facing", fast, exact, theta, d, r, rho, offset);
    }
    CHECK(wrong[0] == 0 && wrong[1] == 0, "the back-face fast paths decide as the exact tests (%u and %u of %u and %u "
                                          "decided, %u and %u nearly tangent, %u and %u wrong)",
          decided[0], decided[1], tried[0], tried[1], tangent[0], tangent[1], wrong[0], wrong[1]);
    CHECK(far_decided[0] >= 0.99 * far[0] && far_decided[1] >= 0.99 * far[1],
          "the fast paths decide 99 %% of the cases 1e-6 rad or more from the threshold (%u of %u, %u of %u)",
          far_decided[0], far[0], far_decided[1], far[1]);
}

/* The view-cone fast paths (mlod__surely_outside, mlod__surely_within)
   against the exact tests they stand for (mlod__outside_cone and
   mlod__within_cone with a view node's constants, mlod__vnode_cone_set):
   scene spheres placed at 1e-10 to 0.1 rad from each threshold, on either
   side, a quarter of them nearly tangent to the eyes' ball (d within 2^-40
   to 2^-52 of g or rho, relatively), where an angle's cosine taken from its
   sine loses half its digits.  Wherever a fast path answers, it answers as
   the exact test; it answers nearly every case 1e-6 rad or more away
   (within: where L = least_fov - alpha >= 0; with L < 0 it answers only
   "not within", which half the L < 0 cases test with the sphere anywhere,
   and it answers a quarter of those at least). */
static void test_cone_fast_paths(void)
{
    uint64_t rng = 11;
    uint32_t i, n = 400000, wrong[2] = {0, 0}, decided[2] = {0, 0}, tried[2] = {0, 0}, far[2] = {0, 0},
                            far_decided[2] = {0, 0}, tangent[2] = {0, 0}, below = 0, below_decided = 0;
    for (i = 0; i < n; i++) {
        double axis[3], p[3], x[3], len, d, r, rho, g, psi, phi, offset, cos_phi;
        float cone[4];
        mlod__vnode vn;
        int k, which = (int)(i & 1), near = (i >> 1) % 4 == 0, fast, exact, far_now;
        memset(&vn, 0, sizeof vn);
        tu_random_unit(&rng, axis);
        tu_to_floats(axis, cone, 3);
        cone[3] = tu_float(i % 5 == 0 ? 0.0 : 1.4 * scene_rng_double(&rng));
        vn.cone = cone;
        vn.leaf = (i >> 2) % 3 == 0;
        vn.most_fov = tu_float(0.1 + 3.1 * scene_rng_double(&rng));
        vn.least_fov = tu_float(vn.most_fov * scene_rng_double(&rng));
        mlod__vnode_cone_set(&vn);
        len = sqrt((double)cone[0] * cone[0] + (double)cone[1] * cone[1] + (double)cone[2] * cone[2]);
        for (k = 0; k < 3; k++) axis[k] = cone[k] / len;
        tu_random_perp(&rng, axis, p);
        d = 0.5 + 10.0 * scene_rng_double(&rng);
        if (which == 0) { /* outside: phi > reach + asin(g / d) */
            g = near ? d * (1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52)) : d * scene_rng_double(&rng);
            r = g * scene_rng_double(&rng);
            rho = vn.leaf ? 0.0 : g - r;
            g = r + rho;
            psi = vn.cone[3] + vn.most_fov + (vn.leaf ? 0.0 : 1.0 / 1073741824.0) + asin(g / d);
        } else { /* within: phi <= least - alpha - 2^-30 - asin(rho / d) + asin(r / (d + rho)) */
            rho = near ? d * (1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52)) : d * scene_rng_double(&rng);
            r = (d + rho) * (near && i % 3 == 0 ? 1.0 - ldexp(pow(4096.0, scene_rng_double(&rng)), -52)
                                                : scene_rng_double(&rng));
            g = r + rho;
            psi = vn.least_fov - vn.cone[3] - 1.0 / 1073741824.0 - asin(rho / d) + asin(r / (d + rho));
        }
        vn.radius = rho;
        offset = pow(10.0, -10.0 + 9.0 * scene_rng_double(&rng)) * (scene_rng_double(&rng) < 0.5 ? -1.0 : 1.0);
        phi = psi + offset;
        if (which == 1 && vn.cos_least < -1.0 && (i >> 3) % 2) /* L < 0: anywhere, mostly far below psi */
            phi = 3.14159265358979323846 * scene_rng_double(&rng);
        if (!(phi > 0.0 && phi < 3.14159265358979323846)) continue;
        for (k = 0; k < 3; k++) x[k] = d * (cos(phi) * axis[k] + sin(phi) * p[k]);
        d = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        /* as mlod__pair_action takes it */
        cos_phi = (x[0] * cone[0] + x[1] * cone[1] + x[2] * cone[2]) / (d * vn.axis_length);
        if (which == 0) {
            fast = mlod__surely_outside(cos_phi, d, g, &vn);
            exact = mlod__outside_cone(x, d, g, cone, vn.most_fov, vn.leaf ? 0.0 : 1.0 / 1073741824.0);
        } else {
            fast = mlod__surely_within(cos_phi, d, r, &vn);
            exact = mlod__within_cone(x, d, r, rho, cone, cone[3], vn.least_fov);
        }
        tried[which]++;
        tangent[which] += near;
        /* within, L < 0 (psi >= 0 only where seen > turn): the exact test's, by design */
        far_now = !near && fabs(offset) >= 1e-6 && (which == 0 || vn.cos_least >= -1.0);
        far[which] += far_now;
        below += which == 1 && vn.cos_least < -1.0;
        if (fast < 0) continue;
        decided[which]++;
        far_decided[which] += far_now;
        below_decided += which == 1 && vn.cos_least < -1.0;
        if (fast != exact && wrong[which]++ < 3)
            CHECK(0, "%s fast path: %d, exact test: %d (alpha %.9g, fovs %.9g %.9g, d %.17g, r %.17g, rho %.17g, "
                     "%.3g rad off)",
                  which ? "within" : "outside", fast, exact, cone[3], vn.least_fov, vn.most_fov, d, r, rho, offset);
    }
    CHECK(wrong[0] == 0 && wrong[1] == 0, "the view-cone fast paths decide as the exact tests (%u and %u of %u and %u "
                                          "decided, %u and %u nearly tangent, %u and %u wrong)",
          decided[0], decided[1], tried[0], tried[1], tangent[0], tangent[1], wrong[0], wrong[1]);
    CHECK(far_decided[0] >= 0.99 * far[0] && far_decided[1] >= 0.99 * far[1],
          "the view-cone fast paths decide 99 %% of the cases 1e-6 rad or more from the threshold (%u of %u, %u of %u)",
          far_decided[0], far[0], far_decided[1], far[1]);
    CHECK(below_decided >= below / 4, "with L < 0 the within fast path answers (%u of %u)", below_decided, below);
}

/* The pair filter (mlod__vpair) against the exact pair test.
   Renders: every setting the filter takes (delta > 0, groups or none,
   cones or none, per-view fields of view) and one it leaves (back faces
   culled) render the same atlas, channels and statistics with the filter
   and without it (mlod__megaviews_run's exact).  Pairs: inner view nodes
   and leaves and scene nodes of every level, with epsilon and delta placed
   on the pair's own cmax, cmin and motion and the views' cone reach on its
   own angle, 2^-1 to 2^-50 to either side: every lane the filter decides
   takes the exact path's action, and it decides most lanes of inner nodes
   (not groups: those take the cut's filter, which test_cut measures) 2^-6
   or more from a finite threshold (else it buys nothing), and a quarter
   of the lanes of leaves or more (their thresholds are placed as close by:
   most lanes of a render's leaves are decided). */
/* The plain recursion the descent (mlod__mv_descend) must equal: the pairs
   in depth-first order, each through the exact path, scene splits
   recursed into. */
typedef struct ref_out {
    uint32_t *draw, *split;
    size_t draws, splits;
    uint64_t pairs, culled, leaves;
} ref_out;

static void ref_descend(const mlod__mv_job *job, const mlod__vnode *vn, uint32_t s, ref_out *o)
{
    int a = mlod__pair_action(job, vn, s);
    o->pairs++;
    if (a == MLOD__PAIR_SPLIT_SCENE) {
        ref_descend(job, vn, 2 * s + 1, o);
        ref_descend(job, vn, 2 * s + 2, o);
        return;
    }
    o->culled += a == MLOD__PAIR_CULL;
    o->leaves += a == MLOD__PAIR_DRAW_LEAF;
    if (a == MLOD__PAIR_DRAW || a == MLOD__PAIR_DRAW_LEAF) o->draw[o->draws++] = s;
    if (a == MLOD__PAIR_SPLIT_VIEW) o->split[o->splits++] = s;
}

/* The descent level by level against that recursion: from the same roots
   (the scene root, or up to 300 distinct nodes of one level in random
   order) and view node (inner, group or leaf; with and without the float
   filter, back faces culled or not), its lists of draws and of view
   splits (with and without the view node beside each) equal the
   recursion's, in order, and so do its counts of pairs, culled pairs and
   leaves, with its full room and with rooms of 4 to 300 pairs, where
   groups of roots are halved and single roots taken one level down. */
static void test_descend(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const uint32_t rooms[5] = {0, 4, 5, 37, 300};
    size_t cap = 2 * (size_t)scene->node_count;
    uint32_t *roots = (uint32_t *)malloc(sizeof(uint32_t) * scene->node_count);
    uint32_t *rd = (uint32_t *)malloc(sizeof(uint32_t) * cap), *rs = (uint32_t *)malloc(sizeof(uint32_t) * cap);
    uint32_t *od = (uint32_t *)malloc(sizeof(uint32_t) * 2 * cap), *os = (uint32_t *)malloc(sizeof(uint32_t) * 2 * cap);
    uint64_t rng = 4141, pairs = 0;
    uint32_t c, trial, runs = 0, wrong = 0, small_roots = 0, overflowed = 0;
    if (!roots || !rd || !rs || !od || !os) {
        CHECK(0, "descent: out of memory");
        return;
    }
    for (c = 0; c < 4; c++) {
        views v = make_views(801 + c, c == 3 ? 2000 : 300, lo, hi, c == 1);
        mlod_view_set set = view_set(&v, c != 2, c == 1);
        mlod_view_tree *t = build_views(&set, NULL);
        mlod__mv_job job = pair_job(scene, t, 8, c == 1 ? MLOD_VIEW_CULL_BACKFACES : 0u);
        job.delta = c == 2 ? 0.0 : 0.5;
        job.group_radius = c == 3 ? 0.3 : 0.0;
        for (trial = 0; t && trial < 60; trial++) {
            uint32_t nodes = t->eyes->node_count, vi = (uint32_t)(scene_rng_double(&rng) * nodes), n, i, k, r;
            uint32_t level = 1 + (uint32_t)(scene_rng_double(&rng) * 11.0), begin = (1u << level) - 1;
            mlod__vnode vn;
            ref_out ref;
            if (vi >= nodes) vi = nodes - 1;
            mlod__vnode_set(&job, vi, &vn);
            if (trial % 3 == 0) {
                roots[0] = 0;
                n = 1;
            } else { /* distinct nodes of one level, shuffled */
                uint32_t width = begin + 1 < scene->node_count - begin ? begin + 1 : scene->node_count - begin;
                for (i = 0; i < width; i++) roots[i] = begin + i;
                shuffle(roots, width, &rng);
                n = width < 300 ? width : 300;
            }
            small_roots += n <= 4;
            memset(&ref, 0, sizeof ref);
            ref.draw = rd;
            ref.split = rs;
            for (i = 0; i < n; i++) ref_descend(&job, &vn, roots[i], &ref);
            pairs += ref.pairs;
            for (r = 0; r < 5; r++) {
                mlod__mv_out out;
                int with_view = (int)((trial + r) % 2), same;
                memset(&out, 0, sizeof out);
                out.draw = od;
                out.split = os;
                out.capacity = cap;
                out.with_view = with_view;
                job.descend_room = rooms[r] ? rooms[r] : MLOD__MV_ROOM;
                runs++;
                overflowed += rooms[r] && ref.pairs > rooms[r];
                same = mlod__mv_descend(&job, &vn, roots, n, &out, NULL) && out.pairs == ref.pairs &&
                       out.culled == ref.culled && out.leaves == ref.leaves && out.draw_count == ref.draws &&
                       out.split_count == ref.splits;
                for (k = 0; same && k < ref.draws; k++) same = od[2 * k] == vi && od[2 * k + 1] == rd[k];
                for (k = 0; same && k < ref.splits; k++)
                    same = (!with_view || os[2 * k] == vi) && os[with_view ? 2 * k + 1 : k] == rs[k];
                if (!same && wrong++ < 3)
                    CHECK(0, "descent: case %u, view node %u, %u roots, room %u: %llu pairs, %zu draws, %zu view splits; "
                             "the recursion %llu, %zu, %zu (or the order differs)",
                          c, vi, n, rooms[r], (unsigned long long)out.pairs, out.draw_count, out.split_count,
                          (unsigned long long)ref.pairs, ref.draws, ref.splits);
            }
        }
        mlod_view_tree_destroy(t);
        free_views(&v);
    }
    CHECK(wrong == 0 && runs == 4 * 60 * 5 && overflowed > 300 && small_roots > 50,
          "descent: %u descents (%llu pairs; %u outgrow a small room) equal the depth-first recursion, lists in order",
          runs, (unsigned long long)pairs, overflowed);
    free(roots);
    free(rd);
    free(rs);
    free(od);
    free(os);
}

static void test_pair_filter(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const float eps[3] = {0.5f, 1.0f, 4.0f}, deltas[3] = {0.1f, 0.5f, 3.0f};
    uint32_t c, same = 0, renders = 0;
    for (c = 0; c < 7; c++) { /* 6: lights above the floor, which their floor culls (mlod__below_floor) */
        views v = c == 6 ? make_floor_lights(507, 1500) : make_views(501 + c, c == 5 ? 3000 : 300 + 100 * c, lo, hi, c == 2);
        mlod_view_set s = view_set(&v, c != 1, c == 3);
        mlod_view_tree *t = build_views(&s, NULL);
        uint32_t flags = c == 4 ? MLOD_VIEW_CULL_BACKFACES : 0u, channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
        uint32_t resolution = c % 2 ? 11 : 8;
        mlod_atlas *a = make_atlas(&v, resolution, channels, NULL, flags), *b = make_atlas(&v, resolution, channels, NULL, flags);
        mlod_megaviews_params p;
        mlod_megaviews_stats sa, sb;
        mlod_error e;
        size_t first = 0;
        int ok;
        memset(&p, 0, sizeof p);
        p.epsilon = eps[c % 3];
        p.delta = deltas[(c / 2) % 3];
        p.resolution = resolution;
        p.flags = flags;
        p.group_radius = c % 3 == 2 ? 0.25f : 0.0f;
        ok = t && a && b && mlod__megaviews_run(a, NULL, scene, t, &p, MLOD__MV_WALK_LEVEL, 64, 0, 0, &sa, &e) == MLOD_OK &&
             mlod__megaviews_run(b, NULL, scene, t, &p, MLOD__MV_WALK_LEVEL, 64, 0, 1, &sb, &e) == MLOD_OK;
        renders++;
        if (ok && same_atlas(a, b, &first) && sa.pairs == sb.pairs && sa.culled == sb.culled &&
            sa.shared_draws == sb.shared_draws && sa.leaf_draws == sb.leaf_draws && sa.shared_leaves == sb.shared_leaves &&
            sa.node_pairs == sb.node_pairs)
            same++;
        else
            CHECK(0, "pair filter: render %u (%u views, epsilon %g, delta %g, group %g, flags %u) differs from the exact "
                     "path (pixel %zu, pairs %llu / %llu)", c, v.count, (double)p.epsilon, (double)p.delta,
                  (double)p.group_radius, flags, first, (unsigned long long)sa.pairs, (unsigned long long)sb.pairs);
        mlod_atlas_destroy(a);
        mlod_atlas_destroy(b);
        mlod_view_tree_destroy(t);
        free_views(&v);
    }
    CHECK(same == renders, "pair filter: %u of %u renders equal the exact path's bit for bit (atlas, channels, "
                           "statistics)", same, renders);
#ifdef MLOD__VLANES
    {
        views v = make_views(601, 2000, lo, hi, 0);
        mlod_view_set s = view_set(&v, 1, 1);
        mlod_view_tree *t = build_views(&s, NULL);
        mlod__mv_job job = pair_job(scene, t, 11, 0);
        uint64_t rng = 77;
        uint32_t trial, wrong = 0, lanes = 0, decided = 0, far = 0, far_decided = 0, kinds[6] = {0, 0, 0, 0, 0, 0};
        uint32_t leaves = 0, leaves_decided = 0, oriented = 0;
        static const float axes[2][2][3] = {{{0, -1, 0}, {0, 0, 1}}, {{0.3f, -2.0f, 0.7f}, {1.0f, 0.2f, 0.1f}}};
        if (!t) return;
        for (trial = 0; trial < 30000 && wrong < 3; trial++) {
            uint32_t inner = t->eyes->leaf_count - 1, level = (uint32_t)(scene_rng_double(&rng) * 14.0);
            uint32_t vi = (uint32_t)(scene_rng_double(&rng) * inner), si, lane[MLOD__VLANES], l, which = trial % 4;
            if (trial % 7 == 3) vi = inner + (uint32_t)(scene_rng_double(&rng) * t->eyes->leaf_count); /* a leaf */
            uint32_t first_s = (1u << (level < 13 ? level : 13)) - 1;
            double x[3], xm[3], d, r, rho, cmax, cmin, motion, T = 0.0, off;
            const double *in_map;
            const float *sphere;
            mlod__vnode vn;
            mlod__vf sp[4];
            uint8_t codes[MLOD__VLANES];
            int k, exact, fast, placed;
            si = first_s + (uint32_t)(scene_rng_double(&rng) * (first_s + 1));
            if (si >= scene->node_count) si = scene->node_count - 1;
            sphere = scene->spheres + 4 * (size_t)si;
            job.epsilon = 1.0;
            job.delta = 0.5;
            job.group_radius = trial % 5 == 0 ? 0.3 : 0.0;
            /* maps of the default orientation, down (-y, up +z) and an oblique one, in turn */
            mlod__mv_orient(&job, trial % 3 ? axes[trial % 3 - 1][0] : NULL, trial % 3 ? axes[trial % 3 - 1][1] : NULL);
            oriented += job.oriented;
            mlod__vnode_set(&job, vi, &vn);
            for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - vn.centre[k];
            d = mlod__length3(x);
            r = sphere[3];
            rho = vn.radius;
            in_map = mlod__map_coords(x, job.axes[0], job.oriented, xm);
            mlod__ball_diameters(job.S, in_map, d, r, rho, &cmax, &cmin);
            motion = mlod__ball_motion(job.S, in_map, d, r, rho);
            off = ldexp(1.0, -1 - (int)(scene_rng_double(&rng) * 50.0)) * (trial & 4 ? -1.0 : 1.0);
            if (which == 0) T = cmax;
            if (which == 1) T = cmin;
            if (which == 2) T = motion;
            if (which == 3 && vn.cone) { /* the cone's reach A on this sphere's angle: phi = A + asin(g / d) */
                double cos_phi = (x[0] * vn.cone[0] + x[1] * vn.cone[1] + x[2] * vn.cone[2]) / (d * vn.axis_length);
                double g = r + rho;
                if (d > g) {
                    vn.most_fov = acos(cos_phi > 1.0 ? 1.0 : cos_phi) - asin(g / d) - 1.0 / 1073741824.0 - vn.cone[3] + off;
                    if (!(vn.most_fov > 0.0 && vn.most_fov < TU_PI)) continue;
                    if (vn.least_fov > vn.most_fov) vn.least_fov = vn.most_fov;
                    mlod__vnode_cone_set(&vn);
                    mlod__vnode_fast_set(&job, &vn);
                }
            } else if (T > 1e-6 && T < 1e6) {
                if (which == 2)
                    job.delta = T * (1.0 + off);
                else
                    job.epsilon = T * (1.0 + off);
                mlod__vnode_set(&job, vi, &vn);
            } else
                off = 1.0;
            if (!vn.fast) continue;
            for (l = 0; l < MLOD__VLANES; l++) lane[l] = si;
            mlod__vload(scene->spheres, lane, &sp[0], &sp[1], &sp[2], &sp[3]);
            mlod__vbytes(mlod__vpair(&vn, sp, mlod__vleaf(lane, scene->leaf_count - 1)), codes);
            exact = mlod__pair_action(&job, &vn, si);
            fast = mlod__vpair_action(scene, &vn, si, codes[0]);
            lanes++;
            placed = !vn.group && !vn.leaf && fabs(off) >= 1.0 / 64.0 && fabs(off) < 1.0;
            leaves += vn.leaf;
            far += placed;
            if (fast < 0) continue;
            decided++;
            leaves_decided += vn.leaf;
            kinds[codes[0] - 1]++;
            far_decided += placed;
            if (fast != exact && wrong++ < 3)
                CHECK(0, "pair filter: view node %u, scene node %u (threshold %u, %.3g off): filter %d, exact %d", vi, si,
                      which, off, fast, exact);
        }
        CHECK(wrong == 0, "pair filter: every decided lane takes the exact action (%u of %u lanes decided; culled %u, "
                          "drawn %u, leaves drawn %u, scene split %u, view split %u, middle %u)",
              decided, lanes, kinds[0], kinds[1], kinds[2], kinds[3], kinds[4], kinds[5]);
        CHECK(far_decided >= 0.9 * far && kinds[0] && kinds[1] && kinds[2] && kinds[3] && kinds[4] && kinds[5],
              "pair filter: decides %u of %u lanes of inner nodes 2^-6 to 2^-1 from a finite threshold, and every "
              "kind of action",
              far_decided, far);
        CHECK(oriented > lanes / 2, "pair filter: %u of %u lanes in oriented maps", oriented, lanes);
        CHECK(leaves > 1000 && leaves_decided >= 0.25 * leaves,
              "pair filter: decides %u of %u lanes of view leaves (the cut's filter for the leaf's eye)", leaves_decided,
              leaves);
        mlod_view_tree_destroy(t);
        free_views(&v);
    }
#else
    printf("note: this build has no float lanes (MANYLODS_NO_SIMD, or no SSE2 / NEON): the pair filter is not built, "
           "every pair takes the exact path\n");
#endif
}

/* ============================================================= sizing */

/* mlod_megaviews_bound: what the render's allocator held at once stays
   within the bound for the pairs per view node the render reports, and
   within the bound for any scene of that tree (its node count), over view
   counts from one to thousands and both resolutions; its edges. */
static void test_sizing(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    static const uint32_t counts[4] = {1, 2, 300, 3000}, resolutions[2] = {1, 8};
    uint32_t c, r, checked = 0;
    for (c = 0; c < 4; c++)
        for (r = 0; r < 2; r++) {
            views v = make_views(301 + c, counts[c], lo, hi, 0);
            mlod_view_set s = view_set(&v, c % 2, 0);
            mlod_view_tree *t = build_views(&s, NULL);
            mlod_atlas *a = make_atlas(&v, resolutions[r], 0, NULL, 0);
            tu_counter counter;
            mlod_allocator al = tu_allocator(&counter);
            mlod_megaviews_params p;
            mlod_megaviews_stats st;
            mlod_error e;
            size_t bound, any;
            memset(&p, 0, sizeof p);
            memset(&counter, 0, sizeof counter);
            p.epsilon = 1.0f;
            p.delta = MLOD_MEGAVIEWS_DELTA;
            p.resolution = resolutions[r];
            p.allocator = &al;
            if (!t || !a || mlod_megaviews_render(a, scene, t, &p, &st, &e) != MLOD_OK) {
                CHECK(0, "sizing: %u views at %u px render", counts[c], resolutions[r]);
            } else {
                bound = mlod_megaviews_bound(t, p.resolution, st.node_pairs);
                any = mlod_megaviews_bound(t, p.resolution, scene->node_count);
                CHECK(counter.peak_bytes <= bound && st.peak_bytes == counter.peak_bytes && bound <= any &&
                      st.node_pairs <= scene->node_count,
                      "sizing: %u views at %u px: peak %zu bytes (reported %zu), bound %zu for %llu pairs per view "
                      "node, %zu for any scene", counts[c], resolutions[r], counter.peak_bytes, st.peak_bytes, bound,
                      (unsigned long long)st.node_pairs, any);
                checked++;
            }
            CHECK(mlod_megaviews_bound(t, 0, 1) == 0 && mlod_megaviews_bound(NULL, 8, 1) == 0 &&
                  mlod_megaviews_bound(t, 8, UINT64_MAX) == (size_t)-1,
                  "sizing: 0 for no views or resolution 0, (size_t)-1 beyond size_t");
            mlod_atlas_destroy(a);
            mlod_view_tree_destroy(t);
            free_views(&v);
        }
    CHECK(checked == 8, "sizing: 4 view counts x 2 resolutions checked (%u)", checked);
}

/* ============================================================ threads */

static void test_threads(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    views v = make_views(21, 700, lo, hi, 1);
    mlod_view_set s = view_set(&v, 1, 0);
    mlod_pool *pools[3];
    mlod_parallel hooks[5];
    mlod_view_tree *t0 = build_views(&s, NULL);
    mlod_view *vs = NULL;
    uint32_t channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, h;
    mlod_atlas *ref = make_atlas(&v, 8, channels, &vs, 0);
    mlod_megaviews_params p;
    mlod_megaviews_stats st0, st;
    memset(&st0, 0, sizeof st0);
    mlod_error e;
    tu_hooks(pools, hooks);
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.delta = MLOD_MEGAVIEWS_DELTA;
    p.resolution = 8;
    CHECK(t0 && ref && mlod_megaviews_render(ref, scene, t0, &p, &st0, &e) == MLOD_OK, "threads: reference render");
    CHECK(st0.shared_draws > 1000, "threads: delta %g shares (%llu shared draws)", p.delta,
          (unsigned long long)st0.shared_draws);
    for (h = 0; h < 5 && t0 && ref; h++) {
        mlod_view_tree *t = build_views(&s, &hooks[h]);
        mlod_view *vs2 = NULL;
        mlod_atlas *a = make_atlas(&v, 8, channels, &vs2, 0);
        size_t first = 0;
        p.parallel = &hooks[h];
        CHECK(t && a && mlod_megaviews_render(a, scene, t, &p, &st, &e) == MLOD_OK, "threads: hook %u renders", h);
        if (t && a) {
            CHECK(memcmp(t->eyes->spheres, t0->eyes->spheres, 16 * (size_t)t0->eyes->node_count) == 0 &&
                  memcmp(t->half_fovs, t0->half_fovs, 8 * (size_t)t0->eyes->node_count) == 0,
                  "threads: hook %u builds the same view tree", h);
            int same = same_atlas(a, ref, &first);
            CHECK(same, "threads: hook %u gives another atlas (pixel %zu)", h, first);
            CHECK(st.pairs == st0.pairs && st.shared_draws == st0.shared_draws && st.leaf_draws == st0.leaf_draws &&
                  st.shared_leaves == st0.shared_leaves && st.node_pairs == st0.node_pairs &&
                  st.peak_bytes <= mlod_megaviews_bound(t, p.resolution, st.node_pairs),
                  "threads: hook %u gives other statistics", h);
        }
        mlod_atlas_destroy(a);
        mlod_view_tree_destroy(t);
        free(vs2);
    }
    for (h = 0; h < 3; h++) mlod_pool_destroy(pools[h]);
    mlod_atlas_destroy(ref);
    mlod_view_tree_destroy(t0);
    free(vs);
    free_views(&v);
}

/* ============================================================= errors */

/* A counting allocator (reset) that fails its i-th call. */
static mlod_allocator failing_at(tu_counter *counter, unsigned long i)
{
    memset(counter, 0, sizeof *counter);
    counter->fail_at = i;
    return tu_allocator(counter);
}


/* ======================================================== atlas order */

/* Whether view i's tile holds the same pixels (depth, normal, colour, bit
   for bit) in atlases a and b, wherever each placed it; the first view
   that differs in *first. */
static int same_tiles(const mlod_atlas *a, const mlod_atlas *b, uint32_t *first)
{
    uint32_t i, row;
    for (i = 0; i < a->view_count; i++) {
        const uint32_t *ta = a->tiles + 4 * (size_t)i, *tb = b->tiles + 4 * (size_t)i;
        if (ta[2] != tb[2] || ta[3] != tb[3]) {
            *first = i;
            return 0;
        }
        for (row = 0; row < ta[3]; row++) {
            size_t pa = ((size_t)ta[1] + row) * a->width + ta[0], pb = ((size_t)tb[1] + row) * b->width + tb[0];
            if (memcmp(a->depth + pa, b->depth + pb, 4 * (size_t)ta[2]) ||
                (a->normal && memcmp(a->normal + 3 * pa, b->normal + 3 * pb, 12 * (size_t)ta[2])) ||
                (a->color && memcmp(a->color + 3 * pa, b->color + 3 * pb, 12 * (size_t)ta[2]))) {
                *first = i;
                return 0;
            }
        }
    }
    return 1;
}

/* mlod_atlas_desc.order places view order[k] in cell k and moves no pixel
   within a tile: MegaViews renders (shared and grouped) and the per-view
   splat give each view the same tile as in view order; orders that are no
   permutation are refused, holding nothing. */
static void test_atlas_order(const mlod_tree *scene)
{
    static const float lo[3] = {-1.9f, 0.1f, -1.9f}, hi[3] = {1.9f, 2.9f, 1.9f};
    views v = make_views(23, 500, lo, hi, 1);
    mlod_view_set s = view_set(&v, 1, 0);
    mlod_view_tree *t = build_views(&s, NULL);
    uint32_t channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR, *shuffled = (uint32_t *)malloc(4 * (size_t)v.count);
    uint32_t i, o, g, first = 0;
    uint64_t rng = 77;
    const uint32_t *orders[2];
    mlod_view *vs = NULL;
    mlod_atlas *ref = make_atlas(&v, 8, channels, &vs, 0), *a;
    mlod_megaviews_params p;
    mlod_megaviews_stats st0, st;
    mlod_error e;
    for (i = 0; i < v.count; i++) shuffled[i] = i;
    shuffle(shuffled, v.count, &rng);
    orders[0] = t ? t->eyes->leaf_sources : NULL;
    orders[1] = shuffled;
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.delta = MLOD_MEGAVIEWS_DELTA;
    p.resolution = 8;
    for (o = 0; o < 2 && t && ref; o++) {
        mlod_view *vs2 = NULL;
        mlod_atlas_desc desc;
        a = make_atlas_ordered(&v, 8, channels, &vs2, 0, orders[o]);
        memset(&desc, 0, sizeof desc);
        desc.channels = channels;
        desc.order = orders[o];
        CHECK(a && a->width == ref->width && a->height == ref->height && mlod_atlas_bound(vs2, v.count, &desc) == a->bytes,
              "atlas order %u: the same grid and bytes", o);
        for (i = 0; a && i < v.count; i++) {
            const uint32_t *tile = a->tiles + 4 * (size_t)orders[o][i];
            if (tile[0] != (i % a->columns) * a->cell_width || tile[1] != (i / a->columns) * a->cell_height) break;
        }
        CHECK(a && i == v.count, "atlas order %u: view order[k] in cell k (cell %u is not)", o, i);
        for (g = 0; g < 2 && a; g++) { /* shared, then grouped */
            p.group_radius = g ? 0.3f : 0.0f;
            CHECK(mlod_megaviews_render(ref, scene, t, &p, &st0, &e) == MLOD_OK &&
                      mlod_megaviews_render(a, scene, t, &p, &st, &e) == MLOD_OK,
                  "atlas order %u, group %u: renders", o, g);
            CHECK(st0.shared_draws > 100 && st.pairs == st0.pairs && st.shared_draws == st0.shared_draws,
                  "atlas order %u, group %u: the same statistics (%llu shared draws)", o, g,
                  (unsigned long long)st0.shared_draws);
            CHECK(same_tiles(a, ref, &first), "atlas order %u, group %u: view %u's tile differs", o, g, first);
        }
        if (a) { /* the per-view cut and splat of the same views */
            mlod_cut *cut = NULL;
            mlod_cut_params cp;
            memset(&cp, 0, sizeof cp);
            cp.epsilon = 1.0f;
            CHECK(mlod_cut_create(v.count, NULL, &cut, &e) == MLOD_OK && mlod_cut_update(cut, scene, vs, &cp, &e) == MLOD_OK &&
                      mlod_splat(ref, scene, cut, vs, NULL, &e) == MLOD_OK && mlod_splat(a, scene, cut, vs2, NULL, &e) == MLOD_OK,
                  "atlas order %u: splats", o);
            CHECK(same_tiles(a, ref, &first), "atlas order %u: view %u's splat tile differs", o, first);
            mlod_cut_destroy(cut);
        }
        mlod_atlas_destroy(a);
        free(vs2);
    }
    for (o = 0; o < 2 && vs; o++) { /* not a permutation: a view out of range, a view twice */
        tu_counter counter;
        mlod_allocator al = failing_at(&counter, 0);
        mlod_atlas_desc desc;
        mlod_result r;
        uint32_t keep = shuffled[7];
        shuffled[7] = o ? shuffled[3] : v.count;
        memset(&desc, 0, sizeof desc);
        desc.order = shuffled;
        a = (mlod_atlas *)&desc; /* not NULL: the call must set it */
        r = mlod_atlas_create(vs, v.count, &desc, &al, &a, &e);
        CHECK(r == MLOD_ERROR_INVALID_ARGUMENT && !a && counter.live_blocks == 0 && strstr(e.message, "order[7]"),
              "atlas order: %s refused (%s: %s), nothing held", o ? "a view twice" : "a view out of range",
              mlod_result_name(r), e.message);
        shuffled[7] = keep;
    }
    mlod_atlas_destroy(ref);
    mlod_view_tree_destroy(t);
    free(vs);
    free(shuffled);
    free_views(&v);
}

static int atlas_all_empty(const mlod_atlas *a)
{
    size_t i, n = (size_t)a->width * a->height;
    for (i = 0; i < n; i++)
        if (a->depth[i] < INFINITY) return 0;
    return 1;
}

/* Render with the i-th allocation failing, i = 1, 2, ... (walks from
   walk_level, list room `room`): each failure returns out of memory, holds
   nothing and leaves the atlas empty; the first run without a failure
   gives the atlas `before`.  Returns that i (1000 if none within). */
static uint32_t failing_renders(mlod_atlas *a, const mlod_tree *scene, const mlod_view_tree *t,
                                const mlod_megaviews_params *p, uint32_t walk_level, size_t room, const float *before,
                                const char *what)
{
    size_t bytes = (size_t)a->width * a->height * 4;
    uint32_t i;
    for (i = 1; i < 1000; i++) {
        tu_counter counter;
        mlod_allocator al = failing_at(&counter, i);
        mlod_megaviews_params q = *p;
        mlod_error e;
        mlod_result r;
        q.allocator = &al;
        r = mlod__megaviews_run(a, NULL, scene, t, &q, walk_level, room, 0, 0, NULL, &e);
        CHECK(counter.live_blocks == 0, "%s, allocation %u failing: %lu blocks left", what, i, counter.live_blocks);
        if (r == MLOD_OK) {
            CHECK(memcmp(before, a->depth, bytes) == 0, "%s, allocation %u: no failure, the same atlas", what, i);
            break;
        }
        CHECK(r == MLOD_ERROR_OUT_OF_MEMORY && atlas_all_empty(a), "%s, allocation %u failing: %s and an empty atlas",
              what, i, mlod_result_name(r));
    }
    return i;
}

/* Maps too large to hold: 2 R^2 pixels past 2^32 (a 32-bit count wrapped
   and the maps were written past their end), with an allocator of 64 MiB:
   out of memory, nothing held; bytes past size_t: MLOD_ERROR_OVERFLOW.
   The peak of a render that fits is what the allocator saw. */
static void huge_resolutions(const mlod_tree *scene)
{
    static const float lo[3] = {-1, 0.5f, -1}, hi[3] = {1, 2, 1};
    static const uint32_t R[4] = {46341, 65536, 1u << 20, 0x7fffffffu};
    views v = make_views(33, 2, lo, hi, 0);
    mlod_view_set s = view_set(&v, 0, 0);
    mlod_view_tree *t = build_views(&s, NULL);
    uint32_t i;
    for (i = 0; t && i < 5; i++) {
        tu_counter counter;
        mlod_allocator al = tu_allocator(&counter);
        mlod_megaviews_maps *maps = (mlod_megaviews_maps *)1;
        mlod_megaviews_params p;
        mlod_megaviews_stats st;
        mlod_error e;
        mlod_result r, want = i == 3 && sizeof(size_t) == 8 ? MLOD_ERROR_OVERFLOW : MLOD_ERROR_OUT_OF_MEMORY;
        memset(&counter, 0, sizeof counter);
        counter.budget_bytes = (size_t)64 << 20;
        memset(&p, 0, sizeof p);
        p.epsilon = 1.0f;
        p.resolution = i < 4 ? R[i] : 64;
        p.allocator = &al;
        r = mlod_megaviews_render_maps(scene, t, &p, &maps, &st, &e);
        if (i < 4) {
            CHECK(r == want && maps == NULL && counter.live_blocks == 0,
                  "maps at resolution %u: %s (%s), %lu blocks held", p.resolution, mlod_result_name(r), e.message,
                  counter.live_blocks);
        } else {
            CHECK(r == MLOD_OK && st.peak_bytes == counter.peak_bytes && mlod_megaviews_maps_bytes(maps) == counter.live_bytes,
                  "maps at resolution 64: %s, peak %zu bytes (reported %zu), the maps hold %zu (report %zu)",
                  mlod_result_name(r), counter.peak_bytes, st.peak_bytes, counter.live_bytes, mlod_megaviews_maps_bytes(maps));
            mlod_megaviews_maps_destroy(r == MLOD_OK ? maps : NULL);
        }
    }
    mlod_view_tree_destroy(t);
    free_views(&v);
}

static void test_errors(const mlod_tree *scene, const mlod_tree *bare)
{
    static const float lo[3] = {-1, 0.5f, -1}, hi[3] = {1, 2, 1};
    views v = make_views(31, 40, lo, hi, 0);
    mlod_view_set s = view_set(&v, 1, 1), bad;
    mlod_view_tree *t = build_views(&s, NULL), *none = (mlod_view_tree *)1;
    mlod_view *vs = NULL, *vs2 = NULL;
    mlod_atlas *a = make_atlas(&v, 8, MLOD_ATLAS_NORMAL, &vs, 0), *small = NULL;
    mlod_megaviews_params p, q;
    mlod_error e;
    size_t bytes = (size_t)a->width * a->height * 4;
    float *before = (float *)malloc(bytes);
    uint32_t i;
    float nan = NAN, zero[3] = {0, 0, 0};
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.resolution = 8;
    CHECK(t && a && mlod_megaviews_render(a, scene, t, &p, NULL, &e) == MLOD_OK, "errors: a good render");
    memcpy(before, a->depth, bytes);
    CHECK(mlod_megaviews_render(NULL, scene, t, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL atlas");
    CHECK(mlod_megaviews_render(a, NULL, t, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL scene");
    CHECK(mlod_megaviews_render(a, scene, NULL, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL views");
    CHECK(mlod_megaviews_render(a, scene, t, NULL, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL params");
    q = p;
    q.epsilon = 0.0f;
    CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_BAD_EPSILON, "epsilon 0");
    q.epsilon = nan;
    CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_BAD_EPSILON, "epsilon NaN");
    for (i = 0; i < 2; i++) { /* delta, group_radius: finite and >= 0 */
        const char *name = i ? "group_radius" : "delta";
        float *field;
        q = p;
        field = i ? &q.group_radius : &q.delta;
        *field = -1.0f;
        CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "%s < 0", name);
        *field = INFINITY;
        CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "%s inf", name);
        *field = nan;
        CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_NON_FINITE, "%s NaN", name);
    }
    for (i = 1; i < 32; i++) { /* flags: back-face culling only (a render read unchecked flags into a crash) */
        mlod_megaviews_maps *maps = (mlod_megaviews_maps *)1;
        q = p;
        q.flags = 1u << i;
        CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_BAD_VIEW &&
              mlod_megaviews_render_maps(scene, t, &q, &maps, NULL, &e) == MLOD_ERROR_BAD_VIEW && maps == NULL,
              "flags 0x%x refused", q.flags);
    }
    { /* an allocator without functions means the default one, as everywhere; a view tree without eyes is refused */
        mlod_allocator empty;
        mlod_view_tree hollow = *t;
        memset(&empty, 0, sizeof empty);
        q = p;
        q.allocator = &empty;
        CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_OK && memcmp(before, a->depth, bytes) == 0,
              "an allocator without functions: the default one (%s)", e.message);
        hollow.eyes = NULL;
        CHECK(mlod_megaviews_render(a, scene, &hollow, &p, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT,
              "a view tree without eyes refused");
        CHECK(mlod_megaviews_bound(t, 0x80000000u, 1) == 0, "sizing: 0 for a resolution the render refuses");
    }
    { /* the orientation: both 0, or a frame mlod_view_check takes */
        static const struct {
            float forward[3], up[3];
            mlod_result code;
        } frames[] = {{{0, -1, 0}, {0, 2, 0}, MLOD_ERROR_BAD_VIEW},        /* parallel */
                      {{1, 1, 0}, {-3, -3, 0}, MLOD_ERROR_BAD_VIEW},       /* opposite */
                      {{0, 0, 0}, {0, 1, 0}, MLOD_ERROR_BAD_VIEW},         /* forward 0, up not */
                      {{0, -1, 0}, {0, 0, 0}, MLOD_ERROR_BAD_VIEW},        /* up 0, forward not */
                      {{0, 0, 1}, {0, 1, 1e-30f}, MLOD_OK},                /* nearly the default */
                      {{0, -1, 0}, {0, 0, 1}, MLOD_OK}};
        mlod_megaviews_maps *maps = (mlod_megaviews_maps *)1;
        for (i = 0; i < sizeof frames / sizeof frames[0]; i++) {
            q = p;
            memcpy(q.forward, frames[i].forward, 12);
            memcpy(q.up, frames[i].up, 12);
            CHECK(mlod_megaviews_check(&q, &e) == frames[i].code &&
                      (frames[i].code == MLOD_OK || (mlod_megaviews_render(a, scene, t, &q, NULL, &e) == frames[i].code &&
                                                     strstr(e.message, "forward") != NULL &&
                                                     mlod_megaviews_render_maps(scene, t, &q, &maps, NULL, &e) ==
                                                         frames[i].code &&
                                                     maps == NULL)),
                  "orientation %u: forward (%g, %g, %g), up (%g, %g, %g): %s (%s)", i, frames[i].forward[0],
                  frames[i].forward[1], frames[i].forward[2], frames[i].up[0], frames[i].up[1], frames[i].up[2],
                  mlod_result_name(frames[i].code), e.message);
            maps = (mlod_megaviews_maps *)1;
        }
        for (i = 0; i < 6; i++) { /* NaN or infinite in any of the six */
            float *field = i < 3 ? &q.forward[i] : &q.up[i - 3];
            q = p;
            q.forward[1] = -1.0f;
            q.up[2] = 1.0f;
            *field = i % 2 ? INFINITY : nan;
            CHECK(mlod_megaviews_check(&q, &e) == MLOD_ERROR_NON_FINITE &&
                      mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_NON_FINITE,
                  "orientation: %s in %s[%u] refused (%s)", i % 2 ? "inf" : "NaN", i < 3 ? "forward" : "up", i % 3,
                  e.message);
        }
    }
    q = p;
    q.resolution = 0;
    CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "resolution 0");
    q.resolution = 9;
    CHECK(mlod_megaviews_render(a, scene, t, &q, NULL, &e) == MLOD_ERROR_MISMATCH, "tiles of another resolution");
    CHECK(mlod_megaviews_render(a, bare, t, &p, NULL, &e) == MLOD_ERROR_MISMATCH, "normals without cones");
    small = make_atlas(&v, 8, 0, &vs2, 0);
    {
        views w = v;
        w.count = 39;
        free(vs2);
        mlod_atlas_destroy(small);
        small = make_atlas(&w, 8, 0, &vs2, 0);
        CHECK(mlod_megaviews_render(small, scene, t, &p, NULL, &e) == MLOD_ERROR_MISMATCH, "an atlas of 39 views for 40");
    }
    CHECK(memcmp(before, a->depth, bytes) == 0, "errors: the atlas is untouched by refused calls");
    { /* an atlas created for other eyes of the same count holds the view tree's maps (documented, not refused) */
        static const float lo2[3] = {5, 5, 5}, hi2[3] = {9, 9, 9};
        views w = make_views(32, v.count, lo2, hi2, 0);
        mlod_atlas *other = make_atlas(&w, 8, MLOD_ATLAS_NORMAL, NULL, 0);
        CHECK(other && other->width == a->width && other->height == a->height &&
              mlod_megaviews_render(other, scene, t, &p, NULL, &e) == MLOD_OK &&
              memcmp(before, other->depth, bytes) == 0,
              "errors: an atlas made for other eyes gets the view tree's maps");
        mlod_atlas_destroy(other);
        free_views(&w);
    }
    /* failing allocators: an error, nothing held, the atlas empty */
    i = failing_renders(a, scene, t, &p, MLOD__MV_WALK_LEVEL, MLOD__MV_WALK_ROOM, before, "fused");
    CHECK(i < 1000, "a render without failures within 1000 allocations (%u)", i);
    /* the same, walking from the root with a list room of 1: the walks outgrow their lists again and again, and
       any of those allocations may fail */
    i = failing_renders(a, scene, t, &p, 0, 1, before, "walks");
    CHECK(i > 10 && i < 1000, "walks: a render without failures after %u allocations (seven for the walk, the rest "
                              "its list growing)", i);
    /* the unfused maps: refusals, failing allocators */
    {
        mlod_megaviews_maps *maps = (mlod_megaviews_maps *)1;
        CHECK(mlod_megaviews_render_maps(scene, t, &p, NULL, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "maps: NULL out");
        CHECK(mlod_megaviews_render_maps(NULL, t, &p, &maps, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT && maps == NULL,
              "maps: NULL scene");
        q = p;
        q.epsilon = -1.0f;
        CHECK(mlod_megaviews_render_maps(scene, t, &q, &maps, NULL, &e) == MLOD_ERROR_BAD_EPSILON && maps == NULL,
              "maps: bad epsilon");
        for (i = 1; i < 1000; i++) {
            tu_counter counter;
            mlod_allocator al = failing_at(&counter, i);
            mlod_result r;
            q = p;
            q.allocator = &al;
            r = mlod_megaviews_render_maps(scene, t, &q, &maps, NULL, &e);
            if (r == MLOD_OK) {
                mlod_megaviews_maps_destroy(maps);
                CHECK(counter.live_blocks == 0, "maps: destroy gives everything back");
                break;
            }
            CHECK(r == MLOD_ERROR_OUT_OF_MEMORY && maps == NULL && counter.live_blocks == 0,
                  "maps, allocation %u failing: %s, %lu blocks left", i, mlod_result_name(r), counter.live_blocks);
        }
        CHECK(i < 1000, "maps: a render without failures within 1000 allocations (%u)", i);
        mlod_megaviews_maps_destroy(NULL);
        huge_resolutions(scene);
    }
    for (i = 0; i < 3; i++) { /* the build's peak within the documented bound (the struct was left out once) */
        static const uint32_t counts[3] = {1, 2, 40};
        tu_counter counter;
        mlod_allocator al = tu_allocator(&counter);
        mlod_view_set few = view_set(&v, i == 2, 0);
        mlod_view_tree *out = NULL;
        size_t bound;
        few.count = counts[i];
        bound = mlod_build_points_bound(few.count, MLOD_ATTR_REFIT | (few.directions ? (uint32_t)MLOD_ATTR_CONE : 0u)) +
                sizeof(mlod_view_tree) + 4 * (size_t)few.count + (few.directions ? 32 * (size_t)few.count : 0);
        memset(&counter, 0, sizeof counter);
        CHECK(mlod_view_tree_build(&few, &al, NULL, &out, &e) == MLOD_OK && counter.peak_bytes <= bound &&
                  out->bytes == counter.live_bytes,
              "view tree of %u views: peak %zu bytes, the documented bound %zu; holds %zu, reports %zu", few.count,
              counter.peak_bytes, bound, counter.live_bytes, out ? out->bytes : 0);
        mlod_view_tree_destroy(out);
    }
    /* view sets */
    CHECK(mlod_view_tree_build(NULL, NULL, NULL, &none, &e) == MLOD_ERROR_INVALID_ARGUMENT && none == NULL,
          "NULL view set");
    CHECK(mlod_view_tree_build(&s, NULL, NULL, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL out");
    bad = s;
    bad.count = 0;
    CHECK(mlod_view_tree_build(&bad, NULL, NULL, &none, &e) == MLOD_ERROR_EMPTY, "no views");
    bad = s;
    bad.eyes = NULL;
    CHECK(mlod_view_tree_build(&bad, NULL, NULL, &none, &e) == MLOD_ERROR_INVALID_ARGUMENT, "NULL eyes");
    v.eyes[7] = nan;
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_NON_FINITE, "NaN eye");
    CHECK(mlod_view_tree_refit(t, &s, NULL, &e) == MLOD_ERROR_NON_FINITE, "refit: NaN eye");
    v.eyes[7] = 1e37f;
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_RANGE, "eye beyond 1e36");
    v.eyes[7] = 0.5f;
    memcpy(v.directions + 6, zero, 12);
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_BAD_VIEW, "zero direction");
    v.directions[6] = 1.0f;
    v.fovs[3] = 0.0f;
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_BAD_VIEW, "half fov 0 per view");
    v.fovs[3] = 3.5f;
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_BAD_VIEW, "half fov above pi");
    v.fovs[3] = nan;
    CHECK(mlod_view_tree_build(&s, NULL, NULL, &none, &e) == MLOD_ERROR_NON_FINITE, "half fov NaN");
    v.fovs[3] = 1.0f;
    bad = s;
    bad.half_fovs = NULL;
    bad.half_fov = -1.0f;
    CHECK(mlod_view_tree_build(&bad, NULL, NULL, &none, &e) == MLOD_ERROR_BAD_VIEW, "negative half_fov");
    bad.half_fov = nan;
    CHECK(mlod_view_tree_build(&bad, NULL, NULL, &none, &e) == MLOD_ERROR_NON_FINITE, "NaN half_fov");
    bad = s;
    bad.count = 39;
    CHECK(mlod_view_tree_refit(t, &bad, NULL, &e) == MLOD_ERROR_MISMATCH, "refit: another count");
    bad = s;
    bad.directions = NULL;
    CHECK(mlod_view_tree_refit(t, &bad, NULL, &e) == MLOD_ERROR_MISMATCH, "refit: without directions");
    CHECK(mlod_view_tree_refit(NULL, &s, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "refit: NULL tree");
    for (i = 1; i < 20; i++) {
        tu_counter counter;
        mlod_allocator al = failing_at(&counter, i);
        mlod_view_tree *out = (mlod_view_tree *)1;
        mlod_result r;
        r = mlod_view_tree_build(&s, &al, NULL, &out, &e);
        if (r == MLOD_OK) {
            mlod_view_tree_destroy(out);
            CHECK(counter.live_blocks == 0, "view tree: destroy gives everything back");
            break;
        }
        CHECK(r == MLOD_ERROR_OUT_OF_MEMORY && out == NULL && counter.live_blocks == 0,
              "view tree, allocation %u failing: %s, %lu blocks left", i, mlod_result_name(r), counter.live_blocks);
    }
    mlod_view_tree_destroy(NULL);
    free(before);
    free(vs);
    free(vs2);
    mlod_atlas_destroy(a);
    mlod_atlas_destroy(small);
    mlod_view_tree_destroy(t);
    free_views(&v);
}

/* test_megaviews [GROUP...]: every group, or those named (ThreadSanitizer
   runs the groups that use threads: threads, groups). */
int main(int argc, char **argv)
{
    scene_mesh room;
    mlod_tree *scene, *bare;
    test_groups_begin(argc, argv);
    if (!scene_room(&room)) return 1;
    scene = tu_build(&room, 8192, 1, MLOD_ATTR_CONE | MLOD_ATTR_COLOR);
    bare = tu_build(&room, 3000, 2, 0);
    if (!scene || !bare) return 1;
    TEST_GROUP("view_tree", test_view_tree());
    TEST_GROUP("view_order", test_view_order());
    TEST_GROUP("equals_per_view", (test_equals_per_view(scene, "room with cones and colours"),
                                   test_equals_per_view(bare, "room without attributes")));
    TEST_GROUP("culling", test_culling(scene));
    TEST_GROUP("bounds", test_bounds());
    TEST_GROUP("fast_paths", test_fast_paths());
    TEST_GROUP("cone_fast_paths", test_cone_fast_paths());
    TEST_GROUP("pair_filter", test_pair_filter(scene));
    TEST_GROUP("threads", test_threads(scene));
    TEST_GROUP("sizing", test_sizing(scene));
    TEST_GROUP("walks", test_walks(scene));
    TEST_GROUP("descend", test_descend(scene));
    TEST_GROUP("fusion", test_fusion(scene)); /* it overwrites the scene's colours with node indices */
    TEST_GROUP("groups", test_groups(scene));
    TEST_GROUP("query", test_query(scene));
    TEST_GROUP("orientation", test_orientation(scene, bare));
    TEST_GROUP("atlas_order", test_atlas_order(scene));
    TEST_GROUP("errors", test_errors(scene, bare));
    test_groups_end();
    mlod_tree_destroy(scene);
    mlod_tree_destroy(bare);
    scene_free(&room);
    return test_finish();
}
