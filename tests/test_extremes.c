/* tests/test_extremes.c - the whole pipeline (build, refit, cut in every
   mode, splat) at the extremes of scale, geometry, views and epsilon.

   For every case: no NaN or infinity in the tree, containment exact, every
   view's cut a partition of the leaves equal to the brute-force cut of the
   definition (small trees) and listed with consistent counts, the criterion
   monotone on sampled node-views, incremental equal to basic and lazy
   converging to it from another frame's cuts, and a splat atlas holding
   only finite depths or +inf (empty).  Invalid input must give the
   documented error instead.  Each case prints one row of the table in
   docs/GUIDE.md ("case | expected | result"). */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "harness.h"
#include "testutil.h"

#if defined(__SANITIZE_ADDRESS__)
#define EXT_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define EXT_SANITIZED 1
#endif
#endif
#ifndef EXT_SANITIZED
#define EXT_SANITIZED 0
#endif

static mlod_pool *ext_pool;
static mlod_parallel ext_parallel;

static void row(const char *name, const char *expected, const char *result)
{
    printf("| %s | %s | %s |\n", name, expected, result);
}

/* Every float the tree holds is finite. */
static int tree_finite(const mlod_tree *t)
{
    size_t i, n = t->node_count;
    for (i = 0; i < 4 * n; i++)
        if (!isfinite(t->spheres[i]) || (t->cones && !isfinite(t->cones[i]))) return 0;
    for (i = 0; i < n; i++)
        if ((t->areas && !isfinite(t->areas[i])) || (t->colors && !isfinite(t->colors[3 * i]))) return 0;
    return 1;
}

/* Containment on every node of small trees, on a deterministic sample of
   large ones (the exact test costs microseconds per node). */
static int containment_ok(const mlod_tree *t)
{
    uint32_t n, step = t->node_count > 400000 ? t->node_count / 200000 : 1, bad = 0;
    for (n = 1; n < t->node_count; n += step) {
        const float *p = t->spheres + 4 * ((n - 1) / 2), *c = t->spheres + 4 * n;
        if (!exact_sphere_contains_slack(p, c)) bad++;
        if (t->cones && !exact_cone_contains(t->cones + 4 * ((n - 1) / 2), t->cones + 4 * n, TU_CONE_SLACK)) bad++;
    }
    return bad == 0;
}

/* c(child) <= c(parent) on sampled nodes of every view. */
static uint32_t monotone_violations(const mlod_tree *t, const mlod_view *views, uint32_t view_count)
{
    uint32_t v, bad = 0, samples = t->node_count < 2000 ? t->node_count : 2000, k;
    uint64_t rng = 99;
    for (v = 0; v < view_count && v < 16; v++)
        for (k = 1; k < samples; k++) {
            uint32_t n = t->node_count < 2000 ? k : 1 + (uint32_t)(scene_rng_double(&rng) * (t->node_count - 1));
            double c = mlod_criterion(t, n, &views[v]), p = mlod_criterion(t, (n - 1) / 2, &views[v]);
            if (!(c <= p)) bad++;
        }
    return bad;
}

/* The views moved: each eye pushed away from the scene centre by 30 % and
   turned a little, to start incremental and lazy from other cuts. */
static void move_views(const mlod_tree *t, const mlod_view *views, mlod_view *moved, uint32_t count)
{
    uint32_t v;
    int k;
    for (v = 0; v < count; v++) {
        moved[v] = views[v];
        for (k = 0; k < 3; k++) {
            double d = (double)views[v].position[k] - t->spheres[k];
            moved[v].position[k] = (float)(t->spheres[k] + 1.3 * d);
        }
        moved[v].forward[0] += 0.1f * (fabsf(moved[v].forward[0]) + fabsf(moved[v].forward[1]) + fabsf(moved[v].forward[2]));
    }
}

typedef struct ext_result {
    int ok;
    double mean_cut;
    char detail[160];
} ext_result;

/* The whole pipeline; returns whether every invariant held (each is also
   one CHECK). */
static ext_result check_pipeline(const char *name, const mlod_tree *t, const mlod_view *views, uint32_t view_count,
                                 float eps)
{
    ext_result out;
    mlod_cut *basic = NULL, *inc = NULL, *lazy = NULL;
    mlod_cut_params params;
    mlod_error err;
    mlod_view *moved = (mlod_view *)malloc(sizeof(mlod_view) * view_count);
    tu_layout L;
    uint32_t v, bad_partition = 0, bad_counts = 0, bad_reference = 0, bad_inc = 0, calls, lazy_bad = 0, *hits;
    uint64_t total = 0;
    int ok = 1, converged = 0, layout = tu_layout_init(&L, t->leaf_count);
    char why[200] = "";
    memset(&out, 0, sizeof out);
    hits = (uint32_t *)malloc(sizeof(uint32_t) * t->leaf_count);
    CHECK(layout && moved && hits, "%s: test memory", name);
    if (!layout || !moved || !hits) {
        ok = 0;
        goto done;
    }
    ok &= tree_finite(t);
    CHECK(tree_finite(t), "%s: the tree holds NaN or infinity", name);
    {
        int c = containment_ok(t);
        CHECK(c, "%s: containment (with slack) fails", name);
        ok &= c;
    }
    memset(&params, 0, sizeof params);
    params.epsilon = eps;
    params.lazy_steps = 1;
    params.parallel = &ext_parallel;
    if (mlod_cut_create(view_count, NULL, &basic, &err) != MLOD_OK || mlod_cut_create(view_count, NULL, &inc, &err) ||
        mlod_cut_create(view_count, NULL, &lazy, &err)) {
        CHECK(0, "%s: cut create: %s", name, err.message);
        ok = 0;
        goto done;
    }
    params.mode = MLOD_CUT_BASIC;
    if (mlod_cut_update(basic, t, views, &params, &err) != MLOD_OK) {
        CHECK(0, "%s: basic cut: %s", name, err.message);
        ok = 0;
        goto done;
    }
    for (v = 0; v < view_count; v++) {
        mlod_cut_view cv = mlod_cut_get(basic, v);
        total += cv.count;
        if (tu_partition_errors(&L, cv.nodes, cv.count, hits)) bad_partition++;
        if (!tu_counts_ok(&cv)) bad_counts++;
    }
    /* the brute-force cut of the definition, where it is affordable */
    if ((uint64_t)t->node_count * (view_count < 8 ? view_count : 8) <= 4000000) {
        double *crit = (double *)malloc(sizeof(double) * t->node_count);
        uint64_t *keys = (uint64_t *)malloc(sizeof(uint64_t) * 2 * t->node_count);
        uint32_t *nodes = (uint32_t *)malloc(sizeof(uint32_t) * t->node_count);
        uint8_t *status = (uint8_t *)malloc(t->node_count);
        uint8_t *mine = (uint8_t *)malloc(t->node_count);
        for (v = 0; v < view_count && v < 8 && crit && keys && nodes && status && mine; v++) {
            mlod_cut_view cv = mlod_cut_get(basic, v);
            uint32_t count = tu_reference_cut(t, &L, &views[v], eps, crit, keys, nodes, status), i;
            /* c = 0 means culled or a sphere of radius 0: only the cut's
               status tells them apart, so compare those as culled */
            for (i = 0; i < cv.count && i < t->node_count; i++)
                mine[i] = (cv.status[i] == MLOD_STATUS_DRAWN && t->spheres[4 * (size_t)cv.nodes[i] + 3] == 0.0f)
                              ? (uint8_t)MLOD_STATUS_CULLED
                              : cv.status[i];
            cv.status = mine;
            if (tu_cut_differs(&cv, nodes, status, count, &L, keys, why, sizeof why)) bad_reference++;
        }
        free(mine);
        free(crit);
        free(keys);
        free(nodes);
        free(status);
    }
    CHECK(bad_partition == 0, "%s: %u views whose cut is not a partition", name, bad_partition);
    CHECK(bad_counts == 0, "%s: %u views with inconsistent counts", name, bad_counts);
    CHECK(bad_reference == 0, "%s: %u views differ from the brute-force cut (%s)", name, bad_reference, why);
    {
        uint32_t m = monotone_violations(t, views, view_count);
        CHECK(m == 0, "%s: %u node-views with c(child) > c(parent)", name, m);
        ok &= m == 0;
    }
    ok &= bad_partition == 0 && bad_counts == 0 && bad_reference == 0;
    /* incremental and lazy from the moved views' cuts */
    move_views(t, views, moved, view_count);
    params.mode = MLOD_CUT_INCREMENTAL;
    ok &= mlod_cut_update(inc, t, moved, &params, &err) == MLOD_OK && mlod_cut_update(inc, t, views, &params, &err) == MLOD_OK;
    params.mode = MLOD_CUT_LAZY;
    ok &= mlod_cut_update(lazy, t, moved, &params, &err) == MLOD_OK;
    for (v = 0; v < view_count; v++) {
        mlod_cut_view a = mlod_cut_get(basic, v), b = mlod_cut_get(inc, v);
        if (!tu_same_cut(&a, &b)) bad_inc++;
    }
    CHECK(bad_inc == 0, "%s: incremental differs from basic in %u views", name, bad_inc);
    for (calls = 1; calls <= 2 * L.max_depth + 4 && !converged; calls++) {
        uint32_t differ = 0;
        ok &= mlod_cut_update(lazy, t, views, &params, &err) == MLOD_OK;
        for (v = 0; v < view_count; v++) {
            mlod_cut_view a = mlod_cut_get(basic, v), b = mlod_cut_get(lazy, v);
            if (tu_partition_errors(&L, b.nodes, b.count, hits)) lazy_bad++;
            if (!tu_same_cut(&a, &b)) differ++;
        }
        converged = differ == 0;
    }
    CHECK(lazy_bad == 0, "%s: lazy cuts that are not partitions: %u", name, lazy_bad);
    CHECK(converged, "%s: lazy did not converge to basic within %u calls", name, 2 * L.max_depth + 4);
    ok &= bad_inc == 0 && lazy_bad == 0 && converged;
    /* the splat: finite depths or +inf, never NaN */
    {
        uint64_t pixels = 0;
        for (v = 0; v < view_count; v++) pixels += (uint64_t)views[v].width * views[v].height;
        if (pixels <= 20000000u) {
            mlod_atlas *atlas = NULL;
            mlod_atlas_desc ad;
            uint32_t bad = 0;
            size_t i, n;
            memset(&ad, 0, sizeof ad);
            ad.columns = view_count > 64 ? 64 : 0;
            if (mlod_atlas_create(views, view_count, &ad, NULL, &atlas, &err) == MLOD_OK &&
                mlod_splat(atlas, t, basic, views, &ext_parallel, &err) == MLOD_OK) {
                n = (size_t)atlas->width * atlas->height;
                for (i = 0; i < n; i++) bad += isnan(atlas->depth[i]) || atlas->depth[i] == -INFINITY;
            } else {
                bad = 1;
            }
            CHECK(bad == 0, "%s: splat atlas: %u NaN or -inf depths (%s)", name, bad, bad ? err.message : "");
            ok &= bad == 0;
            mlod_atlas_destroy(atlas);
        }
    }
    out.mean_cut = (double)total / view_count;
done:
    out.ok = ok;
    snprintf(out.detail, sizeof out.detail, "%s; mean cut %.0f nodes", ok ? "holds" : "FAILS", out.mean_cut);
    mlod_cut_destroy(basic);
    mlod_cut_destroy(inc);
    mlod_cut_destroy(lazy);
    if (layout) tu_layout_free(&L);
    free(moved);
    free(hits);
    return out;
}

/* Views of every kind around a centre at distance dist (world units); tile
   x tile pixels, cube maps six faces of tile/2 (at least 1) in 3s x 2s. */
static void views_around(mlod_view *views, uint32_t count, const double *centre, double dist, uint32_t tile)
{
    uint32_t v;
    uint64_t rng = 5;
    for (v = 0; v < count; v++) {
        double dir[3], eye[3];
        int k;
        views[v] = tu_view((mlod_view_kind)(v % 5));
        tu_random_unit(&rng, dir);
        for (k = 0; k < 3; k++) eye[k] = centre[k] + dist * dir[k];
        tu_look(&rng, &views[v], eye, centre);
        views[v].width = views[v].height = tile;
        if (views[v].kind == MLOD_VIEW_CUBE) {
            views[v].width = 3 * (tile > 1 ? tile / 2 : 1);
            views[v].height = 2 * (tile > 1 ? tile / 2 : 1);
        }
        views[v].near_plane = views[v].kind == MLOD_VIEW_ORTHOGRAPHIC ? (float)(-3 * dist) : (float)(1e-3 * dist);
        views[v].far_plane = INFINITY;
        views[v].half_width = views[v].half_height = (float)dist;
        if (v % 3 == 0) views[v].flags = MLOD_VIEW_CULL_BACKFACES;
    }
}

/* A sphere mesh scaled by s, stretched by `stretch` along x and moved by
   `offset` along every axis. */
static int sphere_mesh(scene_mesh *m, double s, double stretch, double offset)
{
    uint32_t i;
    if (!scene_uv_sphere(m, 1.0f, 16, 32)) return 0;
    for (i = 0; i < m->vertex_count; i++) {
        float *p = m->positions + 3 * i;
        p[0] = (float)(offset + s * stretch * p[0]);
        p[1] = (float)(offset + s * p[1]);
        p[2] = (float)(offset + s * p[2]);
    }
    return 1;
}

static void case_mesh(const char *name, const char *expected, scene_mesh *m, uint32_t n, double view_dist, float eps)
{
    mlod_tree *t = tu_build(m, n, 1, MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_REFIT);
    mlod_view views[8];
    double c[3], R;
    ext_result r;
    mlod_mesh mesh = tu_mesh(m);
    CHECK(t != NULL, "%s: build", name);
    if (!t) return;
    tu_bounds(m, c, &R);
    views_around(views, 8, c, view_dist * R, 32);
    CHECK(mlod_refit_mesh(t, &mesh, &ext_parallel, NULL) == MLOD_OK, "%s: refit", name);
    r = check_pipeline(name, t, views, 8, eps);
    row(name, expected, r.detail);
    mlod_tree_destroy(t);
}

static void test_scales(void)
{
    static const double scales[] = {1e-30, 1e-12, 1.0, 1e12, 1e30};
    static const char *names[] = {"scale 1e-30", "scale 1e-12", "scale 1", "scale 1e12", "scale 1e30"};
    double cut_at_one = 0.0;
    int i;
    for (i = 0; i < 5; i++) {
        scene_mesh m;
        mlod_tree *t;
        mlod_view views[8];
        double c[3] = {0, 0, 0};
        ext_result r;
        CHECK(sphere_mesh(&m, scales[i], 1.0, 0.0), "sphere mesh");
        t = tu_build(&m, 3000, 1, MLOD_ATTR_CONE | MLOD_ATTR_AREA);
        CHECK(t != NULL, "%s: build", names[i]);
        if (t) {
            views_around(views, 8, c, 3.0 * scales[i], 32);
            r = check_pipeline(names[i], t, views, 8, 1.0f);
            if (i == 2) cut_at_one = r.mean_cut;
            row(names[i], "same cuts as at scale 1, all invariants", r.detail);
            CHECK(t->precision == 0, "%s: precision flag set", names[i]);
            if (i > 2)
                CHECK(fabs(r.mean_cut - cut_at_one) <= 0.01 * cut_at_one, "%s: mean cut %.1f, at scale 1 %.1f",
                      names[i], r.mean_cut, cut_at_one);
            mlod_tree_destroy(t);
        }
        scene_free(&m);
    }
}

static void test_offsets(void)
{
    /* the flag is set exactly when float spacing at the farthest
       coordinate exceeds a quarter of the leaf radius sqrt(A/N) */
    static const double offsets[] = {2e2, 2e4, 2e5, 2e7};
    static const char *names[] = {"offset 1e2 diameters", "offset 1e4 diameters", "offset 1e5 diameters",
                                  "offset 1e7 diameters"};
    int i;
    for (i = 0; i < 4; i++) {
        scene_mesh m;
        mlod_tree *t = NULL;
        mlod_mesh mesh;
        mlod_build_desc d = tu_desc(3000, 1, MLOD_ATTR_CONE);
        mlod_error err;
        mlod_result res;
        CHECK(sphere_mesh(&m, 1.0, 1.0, offsets[i]), "sphere mesh");
        mesh = tu_mesh(&m);
        res = mlod_build_mesh(&mesh, &d, &t, &err);
        if (res == MLOD_OK) {
            mlod_view views[8];
            double c[3], R, far_coordinate = 0.0, radius = sqrt(mlod_mesh_area(&mesh) / 3000);
            int expect_flag = far_coordinate * ldexp(1.0, -23) > 0.25 * radius;
            ext_result r;
            uint32_t j;
            for (j = 0; j < 3 * m.vertex_count; j++)
                if (fabs(m.positions[j]) > far_coordinate) far_coordinate = fabs(m.positions[j]);
            expect_flag = far_coordinate * ldexp(1.0, -23) > 0.25 * radius;
            tu_bounds(&m, c, &R);
            views_around(views, 8, c, 3.0 * R, 32);
            r = check_pipeline(names[i], t, views, 8, 1.0f);
            CHECK((t->precision != 0) == expect_flag, "%s: precision flag %u, expected %d", names[i], t->precision,
                  expect_flag);
            row(names[i], "valid partitions; MLOD_PRECISION_COARSE_POSITIONS where floats are coarser than a quarter leaf",
                t->precision ? "flag set; invariants hold" : r.detail);
            mlod_tree_destroy(t);
        } else {
            /* the input floats themselves collapsed: every triangle is flat */
            CHECK(res == MLOD_ERROR_EMPTY && strstr(err.message, "precision") != NULL,
                  "%s: build returned %s (%s), expected MLOD_ERROR_EMPTY naming float precision", names[i],
                  mlod_result_name(res), err.message);
            row(names[i], "MLOD_ERROR_EMPTY naming float precision when the input itself collapsed",
                "MLOD_ERROR_EMPTY, message names float precision");
        }
        scene_free(&m);
    }
}

static void test_geometry(void)
{
    scene_mesh m;
    uint32_t i;
    static const uint32_t sizes[] = {1, 2, 3, 7919};
    /* elongated 1e6 : 1 */
    CHECK(sphere_mesh(&m, 1.0, 1e6, 0.0), "mesh");
    case_mesh("elongated 1e6 : 1", "all invariants", &m, 5000, 3.0, 1.0f);
    scene_free(&m);
    /* zero-area and sliver triangles */
    CHECK(scene_soup(&m, 300, 3), "soup");
    case_mesh("zero-area and sliver triangles", "no samples on zero area, all invariants", &m, 4000, 3.0, 1.0f);
    scene_free(&m);
    /* duplicate vertices: every triangle with its own three vertices */
    {
        scene_mesh s, u;
        CHECK(scene_torus(&s, 1.0f, 0.3f, 24, 12), "torus");
        CHECK(scene_alloc(&u, s.index_count, s.index_count, 0, 0), "alloc");
        for (i = 0; i < s.index_count; i++) {
            memcpy(u.positions + 3 * i, s.positions + 3 * s.indices[i], 3 * sizeof(float));
            u.indices[i] = i;
        }
        case_mesh("duplicate vertices", "all invariants", &u, 4000, 3.0, 1.0f);
        scene_free(&s);
        scene_free(&u);
    }
    for (i = 0; i < 4; i++) {
        char name[64];
        CHECK(sphere_mesh(&m, 1.0, 1.0, 0.0), "mesh");
        snprintf(name, sizeof name, "N = %u", sizes[i]);
        case_mesh(name, "2N-1 nodes, all invariants", &m, sizes[i], 3.0, 1.0f);
        scene_free(&m);
    }
}

/* Point clouds: all points at one spot, zero and opposite normals. */
static void test_points(void)
{
    enum { n = 200 };
    float pos[3 * n], nrm[3 * n];
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_CONE);
    mlod_tree *t = NULL;
    mlod_view views[8];
    double c[3] = {0.5, 0.5, 0.5};
    ext_result r;
    uint32_t i;
    for (i = 0; i < 3 * n; i++) {
        pos[i] = 0.5f;
        nrm[i] = 0.0f;
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.count = n;
    pts.normals = nrm;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t, "one spot: build");
    if (t) {
        views_around(views, 8, c, 1.0, 32);
        CHECK(t->spheres[3] == 0.0f && t->cones[3] >= (float)TU_PI, "one spot: root radius %g, cone %g", t->spheres[3],
              t->cones[3]);
        r = check_pipeline("all samples at one point", t, views, 8, 1.0f);
        row("all samples at one point, zero-length normals", "radius 0 everywhere, full cones, all invariants", r.detail);
        mlod_tree_destroy(t);
    }
    /* opposite normals side by side: their parent cone is the full sphere */
    for (i = 0; i < n; i++) {
        pos[3 * i] = (float)(i / 2) / n;
        pos[3 * i + 1] = 0.0f;
        pos[3 * i + 2] = 0.0f;
        nrm[3 * i] = nrm[3 * i + 1] = 0.0f;
        nrm[3 * i + 2] = (i & 1) ? -1.0f : 1.0f;
    }
    t = NULL;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t, "opposite normals: build");
    if (t) {
        /* the smallest cone holding two opposite directions is a hemisphere
           (half-angle pi/2 around any perpendicular axis): never back-facing */
        CHECK(t->cones[3] >= (float)(TU_PI / 2), "opposite normals: root cone %g below pi/2", t->cones[3]);
        views_around(views, 8, c, 1.0, 32);
        r = check_pipeline("opposite normals in one node", t, views, 8, 1.0f);
        row("opposite normals in one node", "cone of half-angle >= pi/2 (never back-face culled)", r.detail);
        mlod_tree_destroy(t);
    }
}

/* N = 2^24 + 1: a point cloud on a grid (too large for the sanitizer run). */
static void test_huge(void)
{
    uint32_t n = (1u << 24) + 1, i;
    float *pos;
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, 0);
    mlod_tree *t = NULL;
    mlod_view views[4];
    double c[3] = {0.5, 0.5, 0.0};
    ext_result r;
    if (EXT_SANITIZED) {
        printf("(N = 2^24 + 1 runs in the -O2 build only: %s)\n", "too slow under the sanitizers");
        return;
    }
    pos = (float *)malloc(sizeof(float) * 3 * (size_t)n);
    CHECK(pos != NULL, "memory");
    if (!pos) return;
    for (i = 0; i < n; i++) {
        pos[3 * i] = (float)(i % 4096) / 4096.0f;
        pos[3 * i + 1] = (float)(i / 4096) / 4096.0f;
        pos[3 * i + 2] = 0.0f;
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.count = n;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t && t->node_count == 2 * n - 1, "N = 2^24+1: build");
    if (t) {
        views_around(views, 4, c, 2.0, 32);
        r = check_pipeline("N = 2^24 + 1", t, views, 4, 1.0f);
        row("N = 2^24 + 1 (points)", "2^25 + 1 nodes, all invariants (sampled containment)", r.detail);
        mlod_tree_destroy(t);
    }
    free(pos);
}

static void test_views(void)
{
    scene_mesh m;
    mlod_tree *t;
    mlod_view views[8], base;
    double c[3] = {0, 0, 0};
    ext_result r;
    uint32_t leaf, v;
    int k;
    CHECK(sphere_mesh(&m, 1.0, 1.0, 0.0), "mesh");
    t = tu_build(&m, 3000, 1, MLOD_ATTR_CONE);
    CHECK(t != NULL, "build");
    if (!t) return;
    leaf = t->leaf_count - 1 + t->leaf_count / 3;
    views_around(views, 8, c, 3.0, 32);
    /* eye inside a leaf's sphere, on a sphere's surface, at a node's centre */
    for (v = 0; v < 8; v++) {
        const float *s = t->spheres + 4 * (v < 3 ? leaf : v < 6 ? 5 : 0);
        for (k = 0; k < 3; k++) views[v].position[k] = s[k];
        if (v == 1 || v == 4) views[v].position[0] = s[0] + s[3]; /* on the surface, to float rounding */
    }
    r = check_pipeline("eye inside / on / at the centre of spheres", t, views, 8, 1.0f);
    row("eye inside a leaf, on a sphere, at a node centre", "c = +inf there, all invariants", r.detail);
    CHECK(isinf(mlod_criterion(t, leaf, &views[0])) || mlod_criterion(t, leaf, &views[0]) == 0.0,
          "eye at a leaf centre: c = %g", mlod_criterion(t, leaf, &views[0]));
    /* near 1e-7, far 1e30; fov 1e-4 degrees and 179.9 degrees */
    views_around(views, 8, c, 3.0, 32);
    for (v = 0; v < 8; v++) {
        if (views[v].kind != MLOD_VIEW_CUBE) views[v].kind = MLOD_VIEW_PERSPECTIVE; /* a cube map keeps its own */
        views[v].near_plane = 1e-7f;
        views[v].far_plane = 1e30f;
        views[v].fov_y = (float)((v & 1 ? 179.9 : 1e-4) * TU_PI / 180.0);
    }
    r = check_pipeline("near 1e-7, far 1e30, fov 1e-4 and 179.9 degrees", t, views, 8, 1.0f);
    row("near 1e-7, far 1e30, fov 1e-4 and 179.9 degrees", "all invariants", r.detail);
    /* tiles of 1 x 1 and 4096 x 4096; coinciding views */
    views_around(views, 8, c, 3.0, 32);
    for (v = 0; v < 5; v++) { /* one of each kind; a cube map's smallest is six 1 x 1 faces */
        views[v].width = views[v].kind == MLOD_VIEW_CUBE ? 3 : 1;
        views[v].height = views[v].kind == MLOD_VIEW_CUBE ? 2 : 1;
    }
    r = check_pipeline("1x1 tiles", t, views, 8, 1.0f);
    row("tiles of 1 x 1 pixel", "all invariants", r.detail);
    views_around(views, 1, c, 3.0, 4096);
    r = check_pipeline("a 4096x4096 tile", t, views, 1, 1.0f);
    row("a tile of 4096 x 4096 pixels", "all invariants", r.detail);
    base = views[0];
    for (v = 0; v < 8; v++) views[v] = base;
    r = check_pipeline("coinciding views", t, views, 8, 1.0f);
    row("8 coinciding views", "identical cuts, all invariants", r.detail);
    {
        mlod_cut *cut = NULL;
        CHECK(mlod_cut_create(0, NULL, &cut, NULL) == MLOD_ERROR_INVALID_ARGUMENT && cut == NULL, "zero views");
        row("zero views", "MLOD_ERROR_INVALID_ARGUMENT", "MLOD_ERROR_INVALID_ARGUMENT");
    }
    mlod_tree_destroy(t);
    scene_free(&m);
    /* a paraboloid whose plane is tangent to a flat surface */
    {
        mlod_view tangent[4];
        double centre[3] = {0.5, 0.5, 0.0};
        CHECK(scene_unit_square(&m), "square");
        t = tu_build(&m, 2000, 1, MLOD_ATTR_CONE);
        for (v = 0; v < 4; v++) {
            tangent[v] = tu_view(MLOD_VIEW_PARABOLOID);
            tangent[v].position[0] = 0.25f * (float)v;
            tangent[v].position[1] = 0.5f;
            tangent[v].position[2] = 0.0f;
            tangent[v].forward[0] = 1.0f;
            tangent[v].forward[1] = tangent[v].forward[2] = 0.0f;
            tangent[v].up[0] = 0.0f;
            tangent[v].up[1] = 0.0f;
            tangent[v].up[2] = 1.0f;
            tangent[v].width = tangent[v].height = 32;
            tangent[v].flags = v & 1 ? MLOD_VIEW_CULL_BACKFACES : 0u;
        }
        (void)centre;
        r = check_pipeline("paraboloid tangent to a surface", t, tangent, 4, 1.0f);
        row("paraboloid normal tangent to the surface", "all invariants", r.detail);
        mlod_tree_destroy(t);
        scene_free(&m);
    }
}

/* A million views on a small tree. */
static void test_million_views(void)
{
    uint32_t count = 1000000, v, bad = 0;
    scene_mesh m;
    mlod_tree *t;
    mlod_view *views = (mlod_view *)malloc(sizeof(mlod_view) * count);
    mlod_cut *cut = NULL;
    mlod_cut_params params;
    tu_layout L;
    uint32_t hits[64];
    uint64_t rng = 11;
    double c[3] = {0, 0, 0};
    mlod_error err;
    CHECK(views != NULL && sphere_mesh(&m, 1.0, 1.0, 0.0), "memory");
    t = tu_build(&m, 64, 1, MLOD_ATTR_CONE);
    CHECK(t && tu_layout_init(&L, t->leaf_count), "build");
    for (v = 0; v < count; v++) views[v] = tu_random_view(&rng, (mlod_view_kind)(v % 5), c, 1.0);
    memset(&params, 0, sizeof params);
    params.epsilon = 1.0f;
    params.lazy_steps = 1;
    params.parallel = &ext_parallel;
    CHECK(mlod_cut_create(count, NULL, &cut, &err) == MLOD_OK, "create: %s", err.message);
    params.mode = MLOD_CUT_BASIC;
    CHECK(mlod_cut_update(cut, t, views, &params, &err) == MLOD_OK, "basic: %s", err.message);
    for (v = 0; v < count; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        if (tu_partition_errors(&L, cv.nodes, cv.count, hits) || !tu_counts_ok(&cv)) bad++;
    }
    params.mode = MLOD_CUT_INCREMENTAL;
    CHECK(mlod_cut_update(cut, t, views, &params, &err) == MLOD_OK, "incremental: %s", err.message);
    for (v = 0; v < count; v += 97) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        if (tu_partition_errors(&L, cv.nodes, cv.count, hits)) bad++;
    }
    CHECK(bad == 0, "a million views: %u views with a bad cut", bad);
    {
        char detail[96];
        snprintf(detail, sizeof detail, "%s; cut object %.1f MiB", bad ? "FAILS" : "holds",
                 mlod_cut_bytes(cut) / 1048576.0);
        row("1,000,000 views on a 64-leaf tree", "every cut a partition", detail);
    }
    mlod_cut_destroy(cut);
    tu_layout_free(&L);
    mlod_tree_destroy(t);
    scene_free(&m);
    free(views);
}

static void test_epsilon(void)
{
    static const float good[] = {1.401298464e-45f, 1e-6f, 1e6f, INFINITY};
    static const char *names[] = {"epsilon = smallest float", "epsilon = 1e-6", "epsilon = 1e6", "epsilon = +inf"};
    static const float bad[] = {0.0f, -1.0f, NAN};
    scene_mesh m;
    mlod_tree *t;
    mlod_view views[8];
    double c[3] = {0, 0, 0};
    mlod_cut *cut = NULL;
    mlod_cut_params params;
    int i;
    CHECK(sphere_mesh(&m, 1.0, 1.0, 0.0), "mesh");
    t = tu_build(&m, 2000, 1, MLOD_ATTR_CONE);
    if (!t) return;
    views_around(views, 8, c, 3.0, 32);
    for (i = 0; i < 4; i++) {
        ext_result r = check_pipeline(names[i], t, views, 8, good[i]);
        row(names[i],
            i < 2    ? "leaves (oversize) or culled nodes"
            : i == 2 ? "the root alone (or culled; below it where c = +inf: a cube face the root reaches sideways)"
                     : "the root alone (or culled)",
            r.detail);
    }
    memset(&params, 0, sizeof params);
    params.mode = MLOD_CUT_BASIC;
    CHECK(mlod_cut_create(8, NULL, &cut, NULL) == MLOD_OK, "create");
    for (i = 0; i < 3; i++) {
        params.epsilon = bad[i];
        CHECK(mlod_cut_update(cut, t, views, &params, NULL) == MLOD_ERROR_BAD_EPSILON, "epsilon %g accepted", bad[i]);
    }
    row("epsilon 0, -1, NaN", "MLOD_ERROR_BAD_EPSILON", "MLOD_ERROR_BAD_EPSILON");
    mlod_cut_destroy(cut);
    mlod_tree_destroy(t);
    scene_free(&m);
}

static void test_invalid_geometry(void)
{
    scene_mesh m;
    mlod_mesh mesh;
    mlod_build_desc d = tu_desc(100, 1, 0);
    mlod_tree *t = NULL;
    float saved;
    CHECK(sphere_mesh(&m, 1.0, 1.0, 0.0), "mesh");
    mesh = tu_mesh(&m);
    saved = m.positions[7];
    m.positions[7] = NAN;
    CHECK(mlod_build_mesh(&mesh, &d, &t, NULL) == MLOD_ERROR_NON_FINITE && !t, "NaN coordinate");
    m.positions[7] = INFINITY;
    CHECK(mlod_build_mesh(&mesh, &d, &t, NULL) == MLOD_ERROR_NON_FINITE && !t, "Inf coordinate");
    m.positions[7] = saved;
    m.indices[5] = m.vertex_count;
    CHECK(mlod_build_mesh(&mesh, &d, &t, NULL) == MLOD_ERROR_INDEX_OUT_OF_RANGE && !t, "index out of range");
    row("NaN or Inf coordinates", "MLOD_ERROR_NON_FINITE", "MLOD_ERROR_NON_FINITE");
    row("indices out of range", "MLOD_ERROR_INDEX_OUT_OF_RANGE", "MLOD_ERROR_INDEX_OUT_OF_RANGE");
    scene_free(&m);
}

int main(void)
{
    ext_pool = mlod_pool_create(2);
    if (!ext_pool) {
        CHECK(0, "thread pool");
        return test_finish();
    }
    ext_parallel = mlod_pool_parallel(ext_pool);
    printf("| case | expected | result |\n| --- | --- | --- |\n");
    test_scales();
    test_offsets();
    test_geometry();
    test_points();
    test_views();
    test_epsilon();
    test_invalid_geometry();
    test_million_views();
    test_huge();
    mlod_pool_destroy(ext_pool);
    return test_finish();
}
