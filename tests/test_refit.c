/* tests/test_refit.c - refit of a deforming mesh (and of moving points):
   leaves on the deformed surface, bounds that still contain them exactly,
   the rest pose reproducing the build, identical results for any hook, and
   errors that leave the tree byte for byte as it was. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

#define ALL_ATTRIBUTES (MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT)

/* ------------------------------------------------------------ snapshots */

/* A copy of everything a tree owns, to see that a failed call changed
   nothing. */
typedef struct snapshot {
    mlod_tree header;
    void *arrays[8];
    size_t sizes[8];
} snapshot;

static void snapshot_arrays(const mlod_tree *t, const void **ptr, size_t *size)
{
    size_t nodes = t->node_count, leaves = t->leaf_count;
    ptr[0] = t->spheres, size[0] = 16 * nodes;
    ptr[1] = t->cones, size[1] = 16 * nodes;
    ptr[2] = t->areas, size[2] = 4 * nodes;
    ptr[3] = t->colors, size[3] = 12 * nodes;
    ptr[4] = t->leaf_sources, size[4] = 4 * leaves;
    ptr[5] = t->leaf_barycentrics, size[5] = 8 * leaves;
    ptr[6] = t->triangle_areas, size[6] = 8 * (size_t)t->triangle_count;
    ptr[7] = t->changes, size[7] = t->changes ? 4 * nodes : 0;
}

static void snapshot_take(snapshot *s, const mlod_tree *t)
{
    const void *ptr[8];
    int i;
    s->header = *t;
    snapshot_arrays(t, ptr, s->sizes);
    for (i = 0; i < 8; i++) {
        s->arrays[i] = ptr[i] ? malloc(s->sizes[i] ? s->sizes[i] : 1) : NULL;
        if (ptr[i] && s->arrays[i]) memcpy(s->arrays[i], ptr[i], s->sizes[i]);
    }
}

static int snapshot_same(const snapshot *s, const mlod_tree *t)
{
    const void *ptr[8];
    size_t size[8];
    int i;
    if (memcmp(&s->header, t, sizeof *t) != 0) return 0;
    snapshot_arrays(t, ptr, size);
    for (i = 0; i < 8; i++) {
        if (!ptr[i] != !s->arrays[i]) return 0;
        if (ptr[i] && memcmp(ptr[i], s->arrays[i], size[i]) != 0) return 0;
    }
    return 1;
}

static void snapshot_free(snapshot *s)
{
    int i;
    for (i = 0; i < 8; i++) free(s->arrays[i]);
}

static int same_bounds(const mlod_tree *a, const mlod_tree *b)
{
    size_t n = a->node_count;
    return a->node_count == b->node_count && memcmp(a->spheres, b->spheres, 16 * n) == 0 &&
           (!a->cones || memcmp(a->cones, b->cones, 16 * n) == 0) && (!a->areas || memcmp(a->areas, b->areas, 4 * n) == 0) &&
           (!a->colors || memcmp(a->colors, b->colors, 12 * n) == 0);
}

/* ------------------------------------------------------------- deforming */

/* The refitted tree against the deformed scene `now` (topology of rest). */
static void check_refitted(const mlod_tree *t, const scene_mesh *rest, const scene_mesh *now, const char *what)
{
    uint32_t N = t->leaf_count, j, bad_pos = 0, bad_radius = 0, bad_anc = 0, bad_point = 0, bad_color = 0, bad_normal = 0,
             bad_sum = 0, n, first_pos = 0;
    double A0 = scene_area(rest), Anow = scene_area(now), worst_pos = 0;
    for (j = 0; j < N; j++) {
        uint32_t tri = t->leaf_sources[j], leaf = N - 1 + j, a;
        const uint32_t *idx = now->indices + 3 * tri;
        double s = t->leaf_barycentrics[2 * j], tt = t->leaf_barycentrics[2 * j + 1], p[3], col[3], nrm[3], ax[3], d;
        double expected_r = sqrt(A0 / N) * sqrt(tu_triangle_area(now, tri) / tu_triangle_area(rest, tri));
        const float *c = t->spheres + 4 * leaf;
        tu_eval_on_triangle(now->positions, idx, s, tt, p);
        d = fmax(fabs(p[0] - c[0]), fmax(fabs(p[1] - c[1]), fabs(p[2] - c[2])));
        if (d > 8 * FLT_EPSILON * tu_max_abs_coordinate(now, idx)) {
            if (!bad_pos++) first_pos = j;
            if (d > worst_pos) worst_pos = d;
        }
        if (fabs(c[3] - expected_r) > 1e-5 * expected_r + 1e-30) bad_radius++;
        /* every ancestor contains the leaf's sphere exactly and the freshly
           evaluated sample point */
        for (a = leaf; a > 0;) {
            const float *sa;
            double q[3];
            a = (a - 1) / 2;
            sa = t->spheres + 4 * a;
            if (!exact_sphere_contains(sa, c)) bad_anc++;
            q[0] = p[0] - sa[0];
            q[1] = p[1] - sa[1];
            q[2] = p[2] - sa[2];
            if (tu_norm3(q) > sa[3] * (1 + 1e-7)) bad_point++;
        }
        tu_eval_on_triangle(now->colors, idx, s, tt, col);
        for (a = 0; a < 3; a++)
            if (fabs(col[a] - t->colors[3 * leaf + a]) > 1e-5) bad_color++;
        tu_eval_on_triangle(now->normals, idx, s, tt, nrm);
        tu_normalize3(nrm);
        for (a = 0; a < 3; a++) ax[a] = t->cones[4 * leaf + a];
        if (tu_dot3(nrm, ax) < 0.999) bad_normal++;
    }
    for (n = 0; n + 1 < N; n++) {
        double sum = (double)t->areas[2 * n + 1] + t->areas[2 * n + 2];
        if (fabs(t->areas[n] - sum) > 1e-5 * sum) bad_sum++;
    }
    CHECK(bad_pos == 0, "%s: %u leaf centres off the deformed surface at their (s, t), first leaf %u, worst %.3g", what,
          bad_pos, first_pos, worst_pos);
    CHECK(bad_radius == 0, "%s: %u leaf radii not sqrt(A/N) sqrt(area_now / area_at_build)", what, bad_radius);
    CHECK(bad_anc == 0, "%s: %u (ancestor, leaf) pairs where the ancestor does not contain the leaf sphere exactly", what,
          bad_anc);
    CHECK(bad_point == 0, "%s: %u (ancestor, leaf) pairs where the ancestor misses the deformed sample point", what,
          bad_point);
    CHECK(bad_color == 0, "%s: %u leaf colour components not the interpolated vertex colour", what, bad_color);
    CHECK(bad_normal == 0, "%s: %u leaf cone axes off the interpolated deformed normal", what, bad_normal);
    CHECK(bad_sum == 0, "%s: %u internal areas not the sum of their children", what, bad_sum);
    CHECK(fabs(t->areas[0] * t->area_unit - Anow) <= 0.02 * Anow, "%s: root area %.6g, deformed mesh area %.6g", what,
          t->areas[0] * t->area_unit, Anow);
    tu_check_containment(t, what);
}

/* N leaves on 1024 triangles: with N >= 1024 refit shares each triangle's
   work among its samples (mlod_tree.triangle_leaves), below that each
   leaf does its own; either way the same properties hold. */
static void test_deform(uint32_t N)
{
    static const float times[] = {0.3f, 0.7f, 1.5f, 3.0f, 6.0f};
    scene_mesh rest, now;
    mlod_tree *t;
    mlod_mesh m;
    snapshot build;
    uint32_t i, leaf;
    scene_torus(&rest, 1.0f, 0.35f, 32, 16);
    scene_torus(&now, 1.0f, 0.35f, 32, 16);
    t = tu_build(&rest, N, 17, ALL_ATTRIBUTES);
    CHECK(t != NULL, "deform: build");
    if (!t) return;
    CHECK(!t->triangle_leaves == (N < rest.index_count / 3), "deform, N %u: per-triangle scratch %p with %u triangles",
          N, t->triangle_leaves, rest.index_count / 3);
    snapshot_take(&build, t);
    m = tu_mesh(&now);
    for (i = 0; i < sizeof times / sizeof times[0]; i++) {
        char what[64];
        mlod_error e;
        snprintf(what, sizeof what, "N %u, refit at t=%g", N, times[i]);
        scene_deform(&rest, times[i], now.positions, now.normals);
        CHECK(mlod_refit_mesh(t, &m, NULL, &e) == MLOD_OK, "%s: %s", what, e.message);
        check_refitted(t, &rest, &now, what);
    }
    /* back to the rest pose: the build's leaves again */
    memcpy(now.positions, rest.positions, sizeof(float) * 3 * rest.vertex_count);
    memcpy(now.normals, rest.normals, sizeof(float) * 3 * rest.vertex_count);
    CHECK(mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK, "refit to the rest pose");
    leaf = N - 1;
    CHECK(memcmp(t->spheres + 4 * leaf, ((float *)build.arrays[0]) + 4 * leaf, 16 * (size_t)N) == 0,
          "refit to the rest pose: leaf spheres differ from the build's");
    CHECK(memcmp(t->cones + 4 * leaf, ((float *)build.arrays[1]) + 4 * leaf, 16 * (size_t)N) == 0,
          "refit to the rest pose: leaf cones differ from the build's");
    CHECK(memcmp(t->colors + 3 * leaf, ((float *)build.arrays[3]) + 3 * leaf, 12 * (size_t)N) == 0,
          "refit to the rest pose: leaf colours differ from the build's");
    check_refitted(t, &rest, &now, "refit to the rest pose");
    CHECK(t->precision == 0, "refit to the rest pose: precision flags 0x%x", t->precision);
    /* far from the origin the positions are coarse, and the flag says so;
       back home it clears */
    for (i = 0; i < now.vertex_count; i++) now.positions[3 * i + 2] += 1e8f;
    CHECK(mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK && (t->precision & MLOD_PRECISION_COARSE_POSITIONS),
          "refit at 1e8: precision flags 0x%x, expected MLOD_PRECISION_COARSE_POSITIONS", t->precision);
    tu_check_containment(t, "refit at 1e8");
    memcpy(now.positions, rest.positions, sizeof(float) * 3 * rest.vertex_count);
    CHECK(mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK && t->precision == 0,
          "refit back at the origin: precision flags 0x%x", t->precision);
    snapshot_free(&build);
    mlod_tree_destroy(t);
    scene_free(&rest);
    scene_free(&now);
}

/* A triangle collapsing to a point: its samples get radius 0, the bounds
   still contain everything. */
static void test_collapse(void)
{
    scene_mesh rest;
    mlod_tree *t;
    mlod_mesh m;
    float *pos;
    uint32_t i;
    scene_soup(&rest, 200, 4);
    pos = (float *)malloc(sizeof(float) * 3 * rest.vertex_count);
    memcpy(pos, rest.positions, sizeof(float) * 3 * rest.vertex_count);
    for (i = 0; i < 30; i++) { /* collapse triangle i onto its first vertex */
        memcpy(pos + 9 * i + 3, pos + 9 * i, 12);
        memcpy(pos + 9 * i + 6, pos + 9 * i, 12);
    }
    t = tu_build(&rest, 1000, 2, MLOD_ATTR_REFIT | MLOD_ATTR_CONE);
    m = tu_mesh(&rest);
    m.positions = pos;
    CHECK(t && mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK, "collapse: refit");
    if (t) {
        uint32_t j, bad = 0;
        for (j = 0; j < t->leaf_count; j++)
            if (t->leaf_sources[j] < 30 && (t->spheres[4 * (t->leaf_count - 1 + j) + 3] != 0.0f ||
                                            memcmp(t->spheres + 4 * (t->leaf_count - 1 + j), pos + 9 * t->leaf_sources[j], 12)))
                bad++;
        CHECK(bad == 0, "collapse: %u samples of collapsed triangles not a point of radius 0 at the vertex", bad);
        tu_check_containment(t, "collapse");
    }
    mlod_tree_destroy(t);
    free(pos);
    scene_free(&rest);
}

/* ---------------------------------------------------------------- threads */

static void test_threads(uint32_t N)
{
    enum { CONFIGS = 5 };
    scene_mesh rest, now;
    mlod_tree *t[CONFIGS];
    mlod_pool *pool1 = mlod_pool_create(1), *pool2 = mlod_pool_create(2), *pool3 = mlod_pool_create(3);
    mlod_parallel hooks[CONFIGS];
    mlod_mesh m;
    uint32_t cfg, frame, mismatch[CONFIGS] = {0};
    static const char *names[CONFIGS] = {"no hook", "pool of 1", "pool of 2", "pool of 3", "reverse order"};
    CHECK(pool1 && pool2 && pool3, "refit threads: pools");
    if (!pool1 || !pool2 || !pool3) return;
    memset(hooks, 0, sizeof hooks);
    hooks[1] = mlod_pool_parallel(pool1);
    hooks[2] = mlod_pool_parallel(pool2);
    hooks[3] = mlod_pool_parallel(pool3);
    hooks[4].run = tu_run_reverse;
    scene_uv_sphere(&rest, 1.0f, 24, 48);
    scene_uv_sphere(&now, 1.0f, 24, 48);
    for (cfg = 0; cfg < CONFIGS; cfg++) t[cfg] = tu_build(&rest, N, 3, ALL_ATTRIBUTES);
    m = tu_mesh(&now);
    for (frame = 1; frame <= 3; frame++) {
        scene_deform(&rest, 0.5f * frame, now.positions, now.normals);
        for (cfg = 0; cfg < CONFIGS; cfg++) {
            CHECK(t[cfg] && mlod_refit_mesh(t[cfg], &m, cfg ? &hooks[cfg] : NULL, NULL) == MLOD_OK,
                  "refit threads %s frame %u: refit", names[cfg], frame);
            if (cfg && t[cfg] && t[0]) mismatch[cfg] += !same_bounds(t[0], t[cfg]);
        }
    }
    for (cfg = 1; cfg < CONFIGS; cfg++)
        CHECK(mismatch[cfg] == 0, "refit threads, N %u: %s differs from no hook in %u frames", N, names[cfg], mismatch[cfg]);
    if (t[2]) check_refitted(t[2], &rest, &now, "refit with a pool of 2");
    for (cfg = 0; cfg < CONFIGS; cfg++) mlod_tree_destroy(t[cfg]);
    mlod_pool_destroy(pool1);
    mlod_pool_destroy(pool2);
    mlod_pool_destroy(pool3);
    scene_free(&rest);
    scene_free(&now);
}

/* ----------------------------------------------------------------- errors */

static void expect_refit_error(mlod_tree *t, const mlod_mesh *m, mlod_result a, mlod_result b, const char *what)
{
    snapshot s;
    mlod_error e;
    mlod_result r;
    memset(&e, 0, sizeof e);
    snapshot_take(&s, t);
    r = mlod_refit_mesh(t, m, NULL, &e);
    CHECK(r == a || r == b, "%s: returned %s, expected %s", what, mlod_result_name(r), mlod_result_name(a));
    CHECK(e.code == r && e.message[0] != 0, "%s: error code %d / message \"%s\"", what, (int)e.code, e.message);
    CHECK(snapshot_same(&s, t), "%s: the tree changed", what);
    snapshot_free(&s);
}

static void test_errors(uint32_t N)
{
    scene_mesh rest, now;
    mlod_tree *t, *plain, *pts_tree = NULL;
    mlod_mesh m;
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_REFIT);
    uint32_t last_vertex;
    float keep;
    scene_torus(&rest, 1.0f, 0.3f, 16, 8);
    scene_torus(&now, 1.0f, 0.3f, 16, 8);
    scene_deform(&rest, 1.0f, now.positions, now.normals);
    t = tu_build(&rest, N, 5, ALL_ATTRIBUTES);
    plain = tu_build(&rest, N, 5, MLOD_ATTR_CONE);
    CHECK(t && plain, "refit errors, N %u: builds", N);
    if (!t || !plain) return;
    m = tu_mesh(&now);
    expect_refit_error(plain, &m, MLOD_ERROR_MISMATCH, MLOD_ERROR_INVALID_ARGUMENT, "refit of a tree without MLOD_ATTR_REFIT");
    m.index_count -= 3;
    expect_refit_error(t, &m, MLOD_ERROR_MISMATCH, MLOD_ERROR_MISMATCH, "refit with one triangle less");
    m = tu_mesh(&now);
    m.vertex_count -= 1; /* the last vertex is used: either code describes it */
    expect_refit_error(t, &m, MLOD_ERROR_MISMATCH, MLOD_ERROR_INDEX_OUT_OF_RANGE, "refit with one vertex less");
    {
        float *more = (float *)calloc(3 * (now.vertex_count + 1), sizeof(float));
        memcpy(more, now.positions, sizeof(float) * 3 * now.vertex_count);
        m = tu_mesh(&now);
        m.positions = more;
        m.normals = NULL;
        m.colors = NULL;
        m.vertex_count += 1;
        expect_refit_error(t, &m, MLOD_ERROR_MISMATCH, MLOD_ERROR_MISMATCH, "refit with one (unused) vertex more");
        free(more);
    }
    m = tu_mesh(&now);
    m.index_count += 1;
    expect_refit_error(t, &m, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_MISMATCH, "refit with index_count not a multiple of 3");
    m = tu_mesh(&now);
    last_vertex = now.indices[now.index_count - 1];
    keep = now.positions[3 * last_vertex + 1];
    now.positions[3 * last_vertex + 1] = NAN;
    expect_refit_error(t, &m, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "refit with a NaN position in the last triangle");
    now.positions[3 * last_vertex + 1] = INFINITY;
    expect_refit_error(t, &m, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "refit with an infinite position");
    now.positions[3 * last_vertex + 1] = keep;
    keep = now.normals[3 * last_vertex];
    now.normals[3 * last_vertex] = NAN;
    expect_refit_error(t, &m, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "refit with a NaN normal");
    now.normals[3 * last_vertex] = keep;
    keep = now.colors[3 * last_vertex + 2];
    now.colors[3 * last_vertex + 2] = -INFINITY;
    expect_refit_error(t, &m, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "refit with an infinite colour");
    now.colors[3 * last_vertex + 2] = keep;
    now.indices[now.index_count - 1] = now.vertex_count;
    expect_refit_error(t, &m, MLOD_ERROR_INDEX_OUT_OF_RANGE, MLOD_ERROR_INDEX_OUT_OF_RANGE, "refit with an index out of range");
    now.indices[now.index_count - 1] = last_vertex;
    {
        uint32_t i;
        float *big = (float *)malloc(sizeof(float) * 3 * now.vertex_count);
        for (i = 0; i < 3 * now.vertex_count; i++) big[i] = now.positions[i] * 2e38f; /* |coordinates| <= 1.3: all finite */
        m.positions = big;
        expect_refit_error(t, &m, MLOD_ERROR_RANGE, MLOD_ERROR_RANGE, "refit with coordinates near FLT_MAX");
        m.positions = now.positions;
        free(big);
    }
    expect_refit_error(t, NULL, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "refit with a NULL mesh");
    m.positions = NULL;
    expect_refit_error(t, &m, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "refit with NULL positions");
    m.positions = now.positions;
    CHECK(mlod_refit_mesh(NULL, &m, NULL, NULL) == MLOD_ERROR_INVALID_ARGUMENT, "refit of a NULL tree");
    /* a point tree is not a mesh tree and vice versa */
    memset(&pts, 0, sizeof pts);
    pts.positions = rest.positions;
    pts.count = rest.vertex_count;
    CHECK(mlod_build_points(&pts, &d, &pts_tree, NULL) == MLOD_OK && pts_tree, "refit errors: point build");
    if (pts_tree) {
        mlod_error e;
        snapshot s;
        expect_refit_error(pts_tree, &m, MLOD_ERROR_MISMATCH, MLOD_ERROR_MISMATCH, "mesh refit of a point tree");
        snapshot_take(&s, t);
        CHECK(mlod_refit_points(t, &pts, NULL, &e) == MLOD_ERROR_MISMATCH, "point refit of a mesh tree: %s", e.message);
        CHECK(snapshot_same(&s, t), "point refit of a mesh tree changed it");
        snapshot_free(&s);
    }
    /* after all that, a good refit still works */
    m = tu_mesh(&now);
    CHECK(mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK, "refit after the errors");
    check_refitted(t, &rest, &now, "refit after the errors");
    mlod_tree_destroy(pts_tree);
    mlod_tree_destroy(plain);
    mlod_tree_destroy(t);
    scene_free(&rest);
    scene_free(&now);
}

/* ----------------------------------------------------------------- points */

static void test_points(void)
{
    const uint32_t N = 2000;
    float *pos = (float *)malloc(sizeof(float) * 3 * N), *nrm = (float *)malloc(sizeof(float) * 3 * N),
          *rad = (float *)malloc(sizeof(float) * N), *col = (float *)malloc(sizeof(float) * 3 * N);
    uint64_t rng = 8;
    uint32_t i, j, bad = 0, badr = 0, badn = 0;
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, ALL_ATTRIBUTES);
    mlod_tree *t = NULL;
    snapshot s;
    for (i = 0; i < N; i++) {
        double n[3];
        tu_random_unit(&rng, n);
        scene_set3(pos, i, scene_rng_range(&rng, -1, 1), scene_rng_range(&rng, -1, 1), scene_rng_range(&rng, -1, 1));
        scene_set3(nrm, i, n[0], n[1], n[2]);
        scene_set3(col, i, 0.5, 0.25, 1);
        rad[i] = scene_rng_range(&rng, 0.01f, 0.05f);
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.normals = nrm;
    pts.radii = rad;
    pts.colors = col;
    pts.count = N;
    d.radius_scale = 2.0f;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t, "point refit: build");
    if (!t) return;
    for (i = 0; i < N; i++) { /* move every point, double its radius, turn its normal */
        pos[3 * i] = pos[3 * i] * 1.5f + 0.25f;
        pos[3 * i + 2] -= 0.5f * pos[3 * i + 1];
        rad[i] *= 2;
        nrm[3 * i] = -nrm[3 * i];
    }
    CHECK(mlod_refit_points(t, &pts, NULL, NULL) == MLOD_OK, "point refit");
    for (j = 0; j < N; j++) {
        uint32_t p = t->leaf_sources[j], leaf = N - 1 + j, k;
        if (p >= N || memcmp(t->spheres + 4 * leaf, pos + 3 * p, 12) != 0) {
            bad++;
            continue;
        }
        if (!(t->spheres[4 * leaf + 3] >= 2 * rad[p] && t->spheres[4 * leaf + 3] <= 2 * rad[p] * (1 + 1e-6))) badr++;
        for (k = 0; k < 3; k++)
            if (fabs(t->cones[4 * leaf + k] - nrm[3 * p + k]) > 1e-6) badn++;
    }
    CHECK(bad == 0, "point refit: %u leaves not on their moved point", bad);
    CHECK(badr == 0, "point refit: %u leaf radii not radius_scale x the new radius", badr);
    CHECK(badn == 0, "point refit: %u leaf cone axes not the new normal", badn);
    tu_check_containment(t, "point refit");
    snapshot_take(&s, t);
    pts.count = N - 1;
    CHECK(mlod_refit_points(t, &pts, NULL, NULL) == MLOD_ERROR_MISMATCH, "point refit with one point less");
    pts.count = N;
    pos[3 * 7] = NAN;
    CHECK(mlod_refit_points(t, &pts, NULL, NULL) == MLOD_ERROR_NON_FINITE, "point refit with a NaN position");
    pos[3 * 7] = 0;
    rad[N - 1] = -1;
    {
        mlod_result r = mlod_refit_points(t, &pts, NULL, NULL);
        CHECK(r == MLOD_ERROR_INVALID_ARGUMENT || r == MLOD_ERROR_RANGE, "point refit with a negative radius: %s",
              mlod_result_name(r));
    }
    CHECK(snapshot_same(&s, t), "failed point refits changed the tree");
    snapshot_free(&s);
    mlod_tree_destroy(t);
    free(pos);
    free(nrm);
    free(rad);
    free(col);
}

/* ------------------------------------------------ the record of changes */

/* What a refit's record of changes is checked against: the spheres,
   cones and changes[] before it. */
typedef struct changes_before {
    float *spheres, *cones;
    uint32_t *changes;
} changes_before;

static void changes_take(changes_before *b, const mlod_tree *t)
{
    size_t n = t->node_count;
    b->spheres = (float *)malloc(16 * n);
    b->cones = t->cones ? (float *)malloc(16 * n) : NULL;
    b->changes = (uint32_t *)malloc(4 * n);
    memcpy(b->spheres, t->spheres, 16 * n);
    if (t->cones) memcpy(b->cones, t->cones, 16 * n);
    memcpy(b->changes, t->changes, 4 * n);
}

/* After a refit (all: one that must mark every node): exactly the nodes
   whose sphere or cone bits differ from before carry the new revision's
   low bits, the others what they carried, compared node by node.  Returns
   how many changed. */
static uint32_t changes_check(changes_before *b, const mlod_tree *t, int all, const char *what)
{
    uint32_t n, changed = 0, wrong = 0, first = 0;
    CHECK(t->changes_revision == t->revision, "%s: the record describes revision %llx, the tree is at %llx", what,
          (unsigned long long)t->changes_revision, (unsigned long long)t->revision);
    for (n = 0; n < t->node_count; n++) {
        int differ = memcmp(b->spheres + 4 * (size_t)n, t->spheres + 4 * (size_t)n, 16) != 0 ||
                     (t->cones && memcmp(b->cones + 4 * (size_t)n, t->cones + 4 * (size_t)n, 16) != 0);
        uint32_t expected = all || differ ? (uint32_t)t->revision : b->changes[n];
        changed += differ;
        if (t->changes[n] != expected && !wrong++) first = n;
    }
    CHECK(wrong == 0, "%s: %u of %u nodes recorded wrongly; first node %u: %u, expected %s", what, wrong,
          t->node_count, first, t->changes[first], all ? "all marked" : "its own");
    {
        /* changes_share: the share of the internal nodes at depth 10 (or
           the deepest that has some) this refit changed */
        uint32_t depth = 0, lo = 0, hi = 0, marked = 0, d;
        for (d = 0; d <= 10; d++) {
            uint64_t a = ((uint64_t)1 << d) - 1, b = ((uint64_t)1 << (d + 1)) - 2;
            if (a > (uint64_t)t->leaf_count - 2 || t->leaf_count < 2) break;
            depth = d;
            lo = (uint32_t)a;
            hi = (uint32_t)(b < (uint64_t)t->leaf_count - 2 ? b : (uint64_t)t->leaf_count - 2);
        }
        for (n = lo; n <= hi; n++) marked += t->changes[n] == (uint32_t)t->revision;
        CHECK(fabs(t->changes_share - (double)marked / (hi - lo + 1)) < 1e-6,
              "%s: changes_share %g, %u of the %u internal nodes at depth %u changed", what, t->changes_share, marked,
              hi - lo + 1, depth);
    }
    free(b->spheres);
    free(b->cones);
    free(b->changes);
    return changed;
}

/* mlod_tree.changes, which lets a cut skip what no refit moved: zero
   after a build; after each refit, the new revision on exactly the nodes
   whose bounds changed (a region of a mesh moved, one point moved, on one
   and two threads), nothing after a refit to the same positions, every
   node after a write the tree did not record (revision counted up by
   hand) and after a point refit that estimates its radii. */
static void test_changes(void)
{
    scene_mesh s;
    mlod_mesh mesh;
    mlod_tree *t;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel hook = mlod_pool_parallel(pool);
    changes_before b;
    float *moved;
    uint32_t i, n, changed;
    int pass;
    scene_torus(&s, 1.0f, 0.35f, 24, 12);
    mesh = tu_mesh(&s);
    t = tu_build(&s, 3000, 5, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
    moved = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
    CHECK(t != NULL && t->changes != NULL, "changes: build");
    if (!t || !t->changes) return;
    for (n = 0, changed = 0; n < t->node_count; n++) changed += t->changes[n] != 0;
    CHECK(changed == 0 && t->changes_revision == t->revision, "changes: %u nodes marked after the build", changed);
    for (pass = 0; pass < 2; pass++) {
        const mlod_parallel *par = pass ? &hook : NULL;
        char what[96];
        memcpy(moved, s.positions, sizeof(float) * 3 * s.vertex_count);
        for (i = 0; i < s.vertex_count; i++)
            if (moved[3 * i] > 0.8f) moved[3 * i + 1] += 0.05f * (float)(pass + 1); /* one end of the torus */
        mesh.positions = moved;
        changes_take(&b, t);
        CHECK(mlod_refit_mesh(t, &mesh, par, NULL) == MLOD_OK, "changes: refit");
        snprintf(what, sizeof what, "changes, a region moved (%d thread%s)", pass + 1, pass ? "s" : "");
        changed = changes_check(&b, t, 0, what);
        CHECK(changed > 0 && changed < t->node_count / 2, "%s: %u of %u nodes changed", what, changed, t->node_count);
        changes_take(&b, t);
        CHECK(mlod_refit_mesh(t, &mesh, par, NULL) == MLOD_OK, "changes: refit");
        snprintf(what, sizeof what, "changes, the same positions again (%d thread%s)", pass + 1, pass ? "s" : "");
        CHECK(changes_check(&b, t, 0, what) == 0, "%s: nodes changed", what);
    }
    t->revision++; /* as a user who wrote the arrays does */
    changes_take(&b, t);
    CHECK(mlod_refit_mesh(t, &mesh, NULL, NULL) == MLOD_OK, "changes: refit");
    changes_check(&b, t, 1, "changes, after a write the tree did not record");
    mlod_tree_destroy(t);
    {
        const uint32_t N = 500;
        float *pos = (float *)malloc(sizeof(float) * 3 * N), *rad = (float *)malloc(sizeof(float) * N);
        uint64_t rng = 31;
        mlod_points pts;
        mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_REFIT);
        for (i = 0; i < N; i++) {
            scene_set3(pos, i, scene_rng_range(&rng, -1, 1), scene_rng_range(&rng, -1, 1), scene_rng_range(&rng, -1, 1));
            rad[i] = scene_rng_range(&rng, 0.01f, 0.05f);
        }
        memset(&pts, 0, sizeof pts);
        pts.positions = pos;
        pts.radii = rad;
        pts.count = N;
        t = NULL;
        CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t, "changes, points: build");
        if (t) {
            pos[3 * 123] += 0.2f; /* one point */
            changes_take(&b, t);
            CHECK(mlod_refit_points(t, &pts, NULL, NULL) == MLOD_OK, "changes, points: refit");
            changed = changes_check(&b, t, 0, "changes, one point moved");
            CHECK(changed >= 1 && changed <= 12, "changes, one point moved: %u nodes changed", changed);
            pts.radii = NULL;
            changes_take(&b, t);
            CHECK(mlod_refit_points(t, &pts, NULL, NULL) == MLOD_OK, "changes, points: refit");
            changes_check(&b, t, 1, "changes, points without radii");
            mlod_tree_destroy(t);
        }
        free(pos);
        free(rad);
    }
    mlod_pool_destroy(pool);
    free(moved);
    scene_free(&s);
}

/* A refit merges only the internal nodes above what changed
   (mlod__merge_task), and with MLOD_ATTR_REFIT_CACHE computes only the
   leaves of triangles whose corners changed: the trees it leaves equal,
   bit for bit, a twin built alike whose refits compute and merge
   everything (its revision counted up by hand before each, so that it
   marks all), and mark the same nodes as changed.  Frames move a region,
   move nothing, move everything, change a colour alone, drop the normals,
   turn some triangles' corners round (the same triangles, other leaves),
   or count the cached tree's revision up by hand; then nudge vertices by
   an ulp (areas that change where radii may not); with cones, areas and
   colours (merged with the areas as weights), on one and two threads. */
static int same_marks(const mlod_tree *a, const mlod_tree *b)
{
    uint32_t i;
    for (i = 0; i < a->node_count; i++)
        if ((a->changes[i] == (uint32_t)a->revision) != (b->changes[i] == (uint32_t)b->revision)) return 0;
    return 1;
}

static void test_partial_merge(void)
{
    scene_mesh s, square;
    mlod_mesh mesh;
    mlod_tree *t, *twin, *cached;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel hook = mlod_pool_parallel(pool);
    const uint32_t attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT;
    float *moved;
    uint64_t rng = 77;
    uint32_t i, frame, bad = 0, bad_cached = 0, bad_marks = 0, merged_less = 0, area_only = 0, skipped = 0;
    scene_torus(&s, 1.0f, 0.35f, 40, 20);
    mesh = tu_mesh(&s);
    t = tu_build(&s, 5000, 9, attributes);
    twin = tu_build(&s, 5000, 9, attributes);
    cached = tu_build(&s, 5000, 9, attributes | MLOD_ATTR_REFIT_CACHE);
    moved = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
    CHECK(t && twin && cached && same_bounds(t, twin) && same_bounds(t, cached), "partial merge: twin builds");
    if (!t || !twin || !cached) return;
    CHECK(cached->corners != NULL && t->corners == NULL, "partial merge: MLOD_ATTR_REFIT_CACHE keeps the corners");
    memcpy(moved, s.positions, sizeof(float) * 3 * s.vertex_count);
    for (frame = 0; frame < 36; frame++) {
        const mlod_parallel *par = frame % 2 ? &hook : NULL;
        int kind = (int)(frame % 6);
        uint32_t changed = 0;
        float x0 = scene_rng_range(&rng, -1.2f, 1.2f);
        for (i = 0; i < s.vertex_count; i++) {
            float *p = moved + 3 * i;
            if ((kind == 0 || kind == 3) && p[0] > x0 && p[0] < x0 + 0.3f) p[1] += scene_rng_range(&rng, -0.02f, 0.02f);
            if (kind == 2) p[2] += 0.001f * (float)frame;
        }
        if (kind == 1) s.colors[3 * (frame * 37 % s.vertex_count)] += 0.25f; /* a colour alone */
        if (kind == 4) /* some triangles' corners turned round */
            for (i = frame; i < s.index_count / 3; i += 97) {
                uint32_t *c = s.indices + 3 * (size_t)i, first = c[0];
                c[0] = c[1], c[1] = c[2], c[2] = first;
            }
        if (kind == 5) cached->revision++; /* as a user who wrote its arrays does */
        mesh.positions = moved;
        mesh.normals = kind == 3 || (kind == 0 && frame > 20) ? NULL : s.normals;
        CHECK(mlod_refit_mesh(t, &mesh, par, NULL) == MLOD_OK, "partial merge: refit");
        memset(cached->corners_changed, 2, cached->triangle_count); /* what the comparison did, seen below */
        CHECK(mlod_refit_mesh(cached, &mesh, par, NULL) == MLOD_OK, "partial merge: refit with the cache");
        if (kind == 0 && mesh.normals) { /* a region moved: the cache compared every triangle, and kept most */
            uint32_t same = 0, other = 0;
            for (i = 0; i < cached->triangle_count; i++) {
                same += cached->corners_changed[i] == 0;
                other += cached->corners_changed[i] > 1;
            }
            skipped += frame > 0 && other == 0 && same > cached->triangle_count / 2;
        }
        twin->revision++; /* the twin's record is unknown: it computes and merges every node */
        CHECK(mlod_refit_mesh(twin, &mesh, par, NULL) == MLOD_OK, "partial merge: twin refit");
        bad += !same_bounds(t, twin);
        bad_cached += !same_bounds(cached, twin);
        bad_marks += kind != 5 && !same_marks(t, cached);
        for (i = 0; i < t->leaf_count - 1; i++) changed += t->changes[i] == (uint32_t)t->revision;
        merged_less += changed < t->leaf_count - 1;
    }
    CHECK(bad == 0, "partial merge: %u of 36 refits left other bits than computing everything", bad);
    CHECK(bad_cached == 0, "partial merge, cache: %u of 36 refits left other bits than computing everything", bad_cached);
    CHECK(bad_marks == 0, "partial merge, cache: %u refits marked other nodes than without it", bad_marks);
    CHECK(merged_less >= 12, "partial merge: only %u of 36 refits changed fewer than every internal node", merged_less);
    CHECK(skipped == 3, "partial merge, cache: %u of the 3 refits of a moved region kept most triangles' leaves", skipped);
    mlod_tree_destroy(t);
    mlod_tree_destroy(twin);
    mlod_tree_destroy(cached);
    free(moved);
    scene_free(&s);

    /* the square [-1, 1]^2, one corner moved towards the centre by an ulp
       at a time (a growth of about 2^-25): some leaves' areas change
       where their radii, centres and cones keep their bits (counted:
       area_only) */
    scene_unit_square(&square);
    for (i = 0; i < 2 * 4; i++) square.positions[3 * (i / 2) + i % 2] = 2.0f * square.positions[3 * (i / 2) + i % 2] - 1.0f;
    mesh = tu_mesh(&square);
    t = tu_build(&square, 3000, 4, attributes);
    twin = tu_build(&square, 3000, 4, attributes);
    cached = tu_build(&square, 3000, 4, attributes | MLOD_ATTR_REFIT_CACHE);
    CHECK(t && twin && cached, "partial merge, square: builds");
    if (!t || !twin || !cached) return;
    for (frame = 0, bad = 0; frame < 16; frame++) {
        float *p = square.positions + 3 * 2;
        snapshot before;
        p[frame % 2] = nextafterf(p[frame % 2], 0.0f);
        snapshot_take(&before, t);
        CHECK(mlod_refit_mesh(t, &mesh, frame % 2 ? &hook : NULL, NULL) == MLOD_OK, "partial merge, square: refit");
        CHECK(mlod_refit_mesh(cached, &mesh, frame % 2 ? &hook : NULL, NULL) == MLOD_OK, "partial merge, square: cache");
        twin->revision++;
        CHECK(mlod_refit_mesh(twin, &mesh, frame % 2 ? &hook : NULL, NULL) == MLOD_OK, "partial merge, square: twin");
        bad += !same_bounds(t, twin) || !same_bounds(cached, twin) || !same_marks(t, cached);
        for (i = t->leaf_count - 1; i < t->node_count; i++)
            area_only += memcmp((const float *)before.arrays[2] + i, t->areas + i, 4) != 0 &&
                         memcmp((const float *)before.arrays[0] + 4 * (size_t)i, t->spheres + 4 * (size_t)i, 16) == 0 &&
                         memcmp((const float *)before.arrays[1] + 4 * (size_t)i, t->cones + 4 * (size_t)i, 16) == 0;
        snapshot_free(&before);
    }
    CHECK(bad == 0, "partial merge, square: %u of 16 refits left other bits than computing everything, or other marks", bad);
    CHECK(area_only > 0, "partial merge, square: no leaf's area changed alone (the case this part is for)");
    mlod_tree_destroy(t);
    mlod_tree_destroy(twin);
    mlod_tree_destroy(cached);
    mlod_pool_destroy(pool);
    scene_free(&square);
}

int main(void)
{
    int rc;
    test_deform(3000); /* more leaves than triangles */
    test_deform(300);  /* fewer */
    test_collapse();
    test_threads(9000); /* 3 tasks of 4096 leaves, more than the 2208 triangles */
    test_threads(1000);
    test_errors(2000); /* 256 triangles */
    test_errors(100);
    test_points();
    test_changes();
    test_partial_merge();
    rc = test_finish();
    fflush(stdout); /* keep the result line even if a sanitizer reports at exit */
    return rc;
}
