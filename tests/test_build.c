/* tests/test_build.c - sampling and build: tree shape, exact containment of
   spheres and cones, samples on the surface, stratified area-uniform
   sampling, coverage by the splats, attributes and their bytes, areas,
   colours, determinism (also through parallel-for hooks), point clouds. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

/* ---------------------------------------------------------- tree sizes */

static void test_sizes(void)
{
    static const uint32_t sizes[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 31, 32, 33, 97, 127, 128, 129, 257, 1000, 1009, 4099};
    const uint32_t all = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT;
    scene_mesh s;
    uint32_t si, T;
    double A;
    scene_uv_sphere(&s, 1.5f, 10, 20);
    T = s.index_count / 3;
    A = scene_area(&s);
    for (si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        uint32_t N = sizes[si], j, n, bad_pos = 0, bad_bary = 0, bad_radius = 0, bad_sum = 0, bad_color = 0,
                 bad_mean = 0, bad_axis = 0, bad_tri = 0, first_pos = 0;
        double worst_pos = 0;
        char what[64];
        tu_layout L;
        mlod_tree *t = tu_build(&s, N, 1000 + N, all);
        snprintf(what, sizeof what, "sphere N=%u", N);
        CHECK(t != NULL, "%s: build", what);
        if (!t) continue;
        CHECK(t->leaf_count == N && t->node_count == 2 * N - 1, "%s: %u leaves, %u nodes", what, t->leaf_count,
              t->node_count);
        CHECK(t->attributes == all, "%s: attributes 0x%x, asked 0x%x", what, t->attributes, all);
        CHECK(t->bytes_per_node == 52, "%s: bytes_per_node %u, expected 16 + 16 + 4 + 12 + 4", what,
              (unsigned)t->bytes_per_node);
        CHECK(t->triangle_count == T && t->vertex_count == s.vertex_count, "%s: triangle_count %u vertex_count %u", what,
              t->triangle_count, t->vertex_count);
        tu_check_containment(t, what);
        tu_layout_init(&L, N);
        for (j = 0; j < N; j++) {
            uint32_t tri = t->leaf_sources[j], node = N - 1 + j;
            double st = t->leaf_barycentrics[2 * j], tt = t->leaf_barycentrics[2 * j + 1], p[3], nrm[3], col[3], d;
            const float *c = t->spheres + 4 * node;
            if (tri >= T) {
                bad_tri++;
                continue;
            }
            if (!(st >= 0 && tt >= 0 && st + tt <= 1 + 1e-6)) bad_bary++;
            tu_eval_on_triangle(s.positions, s.indices + 3 * tri, st, tt, p);
            d = fmax(fabs(p[0] - c[0]), fmax(fabs(p[1] - c[1]), fabs(p[2] - c[2])));
            if (d > 8 * FLT_EPSILON * tu_max_abs_coordinate(&s, s.indices + 3 * tri)) {
                if (!bad_pos++) first_pos = j;
                if (d > worst_pos) worst_pos = d;
            }
            if (fabs(c[3] - sqrt(A / N)) > 1e-4 * sqrt(A / N)) bad_radius++;
            tu_eval_on_triangle(s.colors, s.indices + 3 * tri, st, tt, col);
            for (n = 0; n < 3; n++)
                if (fabs(col[n] - t->colors[3 * node + n]) > 1e-5) bad_color++;
            tu_normalize3(p);
            nrm[0] = t->cones[4 * node];
            nrm[1] = t->cones[4 * node + 1];
            nrm[2] = t->cones[4 * node + 2];
            if (tu_dot3(p, nrm) < 0.95) bad_axis++;
        }
        for (n = 0; n + 1 < N; n++) {
            uint32_t l = 2 * n + 1, r = 2 * n + 2, k;
            double sum = (double)t->areas[l] + t->areas[r];
            if (fabs(t->areas[n] - sum) > 1e-5 * sum) bad_sum++;
            for (k = 0; k < 3; k++) {
                double m = (L.count[l] * (double)t->colors[3 * l + k] + L.count[r] * (double)t->colors[3 * r + k]) /
                           L.count[n];
                if (fabs(m - t->colors[3 * n + k]) > 1e-5) bad_mean++;
            }
        }
        CHECK(bad_tri == 0, "%s: %u leaf_sources out of range", what, bad_tri);
        CHECK(bad_bary == 0, "%s: %u barycentrics outside the triangle", what, bad_bary);
        CHECK(bad_pos == 0, "%s: %u leaf centres off V0 + s(V1-V0) + t(V2-V0), first leaf %u, worst %.3g", what,
              bad_pos, first_pos, worst_pos);
        CHECK(bad_radius == 0, "%s: %u leaf radii differ from sqrt(A/N) = %.9g", what, bad_radius, sqrt(A / N));
        CHECK(fabs(t->area_unit - A / N) <= 1e-6 * A / N, "%s: area_unit %.9g, A/N %.9g", what, t->area_unit, A / N);
        CHECK(fabs(t->areas[0] * t->area_unit - A) <= 1e-4 * A, "%s: root area %.9g x area_unit %.9g, mesh area %.9g",
              what, t->areas[0], t->area_unit, A);
        CHECK(bad_sum == 0, "%s: %u internal areas differ from the sum of their children", what, bad_sum);
        CHECK(bad_color == 0, "%s: %u leaf colour components differ from the interpolated vertex colour", what, bad_color);
        CHECK(bad_mean == 0, "%s: %u internal colour components differ from the mean of their leaves", what, bad_mean);
        CHECK(bad_axis == 0, "%s: %u leaf normals more than 18 degrees off the sphere's normal", what, bad_axis);
        for (j = 0, bad_tri = 0; j < T; j++)
            if (fabs(t->triangle_areas[j] - tu_triangle_area(&s, j)) > 1e-4 * tu_triangle_area(&s, j) + 1e-12) bad_tri++;
        CHECK(bad_tri == 0, "%s: %u triangle_areas differ from the triangles' areas", what, bad_tri);
        tu_layout_free(&L);
        mlod_tree_destroy(t);
    }
    scene_free(&s);
}

/* ------------------------------------------------------------ sampling */

static void test_square_strata(void)
{
    scene_mesh s;
    mlod_tree *t;
    const uint32_t N = 4096;
    uint32_t cells[64], j, outside = 0;
    double mean = N / 64.0, var = 0;
    scene_unit_square(&s);
    t = tu_build(&s, N, 7, 0);
    CHECK(t != NULL, "square: build");
    if (!t) return;
    memset(cells, 0, sizeof cells);
    for (j = 0; j < N; j++) {
        const float *c = t->spheres + 4 * (N - 1 + j);
        int x = (int)(c[0] * 8), y = (int)(c[1] * 8);
        if (c[0] < 0 || c[0] > 1 || c[1] < 0 || c[1] > 1 || c[2] != 0) {
            outside++;
            continue;
        }
        if (x > 7) x = 7;
        if (y > 7) y = 7;
        cells[8 * y + x]++;
    }
    for (j = 0; j < 64; j++) var += (cells[j] - mean) * (cells[j] - mean) / 64;
    CHECK(outside == 0, "square: %u samples off the unit square", outside);
    CHECK(var < mean / 4, "square: variance of the 8x8 cell counts %.3g, expected < mean/4 = %.3g (random: %.3g)", var,
          mean / 4, mean);
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* Per-triangle counts against the area share N a_k / A: the documented
   sampling ((i + xi_i)/N of the cumulative area) puts floor(share) - 1 ..
   ceil(share) + 1 samples on a triangle; zero-area triangles get none. */
static void check_triangle_shares(const scene_mesh *s, uint32_t N, const char *what)
{
    uint32_t T = s->index_count / 3, j, *count = (uint32_t *)calloc(T, sizeof(uint32_t)), bad = 0, strict = 0,
             zero_hit = 0, first = 0;
    double A = scene_area(s), chi2 = 0, worst = 0;
    mlod_tree *t = tu_build(s, N, 99, MLOD_ATTR_REFIT);
    CHECK(t != NULL, "%s: build", what);
    if (!t || !count) return;
    for (j = 0; j < N; j++) count[t->leaf_sources[j] < T ? t->leaf_sources[j] : 0]++;
    for (j = 0; j < T; j++) {
        double a = tu_triangle_area(s, j), share = a * N / A;
        if (a == 0.0) {
            zero_hit += count[j];
            continue;
        }
        if (count[j] + 1 < floor(share - 1e-3) || count[j] > ceil(share + 1e-3) + 1) {
            if (!bad++) first = j;
        }
        if (fabs(count[j] - share) > 1.0) strict++;
        if (fabs(count[j] - share) > worst) worst = fabs(count[j] - share);
        chi2 += (count[j] - share) * (count[j] - share) / share;
    }
    CHECK(zero_hit == 0, "%s: %u samples on zero-area triangles", what, zero_hit);
    CHECK(bad == 0, "%s: %u triangles outside floor(share)-1 .. ceil(share)+1, first %u: %u samples, share %.4f", what,
          bad, first, count[first], tu_triangle_area(s, first) * N / A);
    if (N >= 4 * T)
        CHECK(chi2 < 0.5 * T, "%s: chi-square %.1f over %u triangles, expected far below the random %u", what, chi2, T, T);
    printf("  %s: %u triangles, %u of them more than 1 off their share (worst %.3f), chi-square %.1f\n", what, T, strict,
           worst, chi2);
    free(count);
    mlod_tree_destroy(t);
}

static void test_shares(void)
{
    scene_mesh s;
    scene_uv_sphere(&s, 1.0f, 12, 24);
    check_triangle_shares(&s, 3000, "sphere shares");
    check_triangle_shares(&s, 200, "sphere shares, N < triangles");
    scene_free(&s);
    scene_soup(&s, 400, 5);
    check_triangle_shares(&s, 5000, "soup shares");
    scene_free(&s);
    scene_room(&s);
    check_triangle_shares(&s, 777, "room shares");
    scene_free(&s);
}

/* ------------------------------------------------------------- coverage */

static int covered(const mlod_tree *t, const double *p)
{
    uint32_t stack[128], top = 0;
    stack[top++] = 0;
    while (top) {
        uint32_t n = stack[--top];
        const float *s = t->spheres + 4 * n;
        double d[3] = {p[0] - s[0], p[1] - s[1], p[2] - s[2]};
        if (tu_dot3(d, d) > (double)s[3] * s[3] * (1 + 1e-9)) continue;
        if (n >= t->leaf_count - 1) return 1;
        stack[top++] = 2 * n + 2;
        stack[top++] = 2 * n + 1;
    }
    return 0;
}

static void check_coverage(const scene_mesh *s, uint32_t N, const char *what)
{
    uint32_t T = s->index_count / 3, i, k, hits = 0, M = 20000;
    double *cum = (double *)malloc(sizeof(double) * T), total = 0;
    uint64_t rng = 12345;
    mlod_tree *t = tu_build(s, N, 3, 0);
    CHECK(t != NULL, "%s: build", what);
    if (!t || !cum) return;
    for (i = 0; i < T; i++) cum[i] = (total += tu_triangle_area(s, i));
    for (i = 0; i < M; i++) {
        double u = scene_rng_double(&rng) * total, r1 = sqrt(scene_rng_double(&rng)), r2 = scene_rng_double(&rng), p[3];
        uint32_t lo = 0, hi = T - 1;
        const uint32_t *tri;
        while (lo < hi) {
            uint32_t mid = (lo + hi) / 2;
            if (cum[mid] <= u) lo = mid + 1;
            else hi = mid;
        }
        tri = s->indices + 3 * lo;
        for (k = 0; k < 3; k++)
            p[k] = (1 - r1) * s->positions[3 * tri[0] + k] + r1 * (1 - r2) * s->positions[3 * tri[1] + k] +
                   r1 * r2 * s->positions[3 * tri[2] + k];
        hits += covered(t, p);
    }
    CHECK(hits >= 0.995 * M, "%s: %.3f%% of surface points inside a leaf sphere, expected >= 99.5%%", what,
          100.0 * hits / M);
    printf("  %s: %.3f%% covered\n", what, 100.0 * hits / M);
    mlod_tree_destroy(t);
    free(cum);
}

static void test_coverage(void)
{
    scene_mesh s;
    scene_unit_square(&s);
    check_coverage(&s, 2000, "square coverage");
    check_coverage(&s, 37, "square coverage, N=37");
    scene_free(&s);
    scene_uv_sphere(&s, 1.0f, 16, 32);
    check_coverage(&s, 3000, "sphere coverage");
    scene_free(&s);
    scene_torus(&s, 1.0f, 0.3f, 32, 16);
    check_coverage(&s, 4000, "torus coverage");
    scene_free(&s);
}

/* ------------------------------------------------ determinism, attributes */

static int same_array(const void *a, const void *b, size_t bytes)
{
    if (!a || !b) return a == b;
    return memcmp(a, b, bytes) == 0;
}

static int same_tree(const mlod_tree *a, const mlod_tree *b)
{
    size_t nodes = a->node_count;
    if (a->node_count != b->node_count || a->attributes != b->attributes) return 0;
    return same_array(a->spheres, b->spheres, 16 * nodes) && same_array(a->cones, b->cones, 16 * nodes) &&
           same_array(a->areas, b->areas, 4 * nodes) && same_array(a->colors, b->colors, 12 * nodes) &&
           same_array(a->leaf_sources, b->leaf_sources, 4 * (size_t)a->leaf_count) &&
           same_array(a->leaf_barycentrics, b->leaf_barycentrics, 8 * (size_t)a->leaf_count) &&
           same_array(a->triangle_areas, b->triangle_areas, 8 * (size_t)a->triangle_count);
}

static void test_determinism(void)
{
    const uint32_t all = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT;
    scene_mesh s;
    mlod_tree *a, *b, *c;
    scene_torus(&s, 1.0f, 0.4f, 24, 12);
    a = tu_build(&s, 3001, 42, all);
    b = tu_build(&s, 3001, 42, all);
    c = tu_build(&s, 3001, 43, all);
    CHECK(a && b && c, "determinism: builds");
    if (a && b && c) {
        CHECK(same_tree(a, b), "determinism: same seed gave different arrays");
        CHECK(memcmp(a->spheres, c->spheres, 16 * (size_t)a->node_count) != 0, "determinism: seeds 42 and 43 gave the same spheres");
        CHECK(memcmp(a->leaf_barycentrics, c->leaf_barycentrics, 8 * (size_t)a->leaf_count) != 0,
              "determinism: seeds 42 and 43 gave the same samples");
    }
    mlod_tree_destroy(a);
    mlod_tree_destroy(b);
    mlod_tree_destroy(c);
    scene_free(&s);
}

static void test_attributes(void)
{
    static const struct {
        uint32_t attributes, bytes_per_node;
    } cases[] = {{0, 16},
                 {MLOD_ATTR_CONE, 32},
                 {MLOD_ATTR_AREA, 20},
                 {MLOD_ATTR_COLOR, 28},
                 {MLOD_ATTR_REFIT, 20}, /* the record of changes */
                 {MLOD_ATTR_CONE | MLOD_ATTR_COLOR, 44},
                 {MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT, 52},
                 {MLOD_ATTR_REFIT | MLOD_ATTR_REFIT_CACHE, 20},
                 {MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT | MLOD_ATTR_REFIT_CACHE, 48}};
    const uint32_t N = 1000;
    scene_mesh s;
    mlod_tree *base, *t;
    size_t i;
    scene_uv_sphere(&s, 1.0f, 8, 16);
    base = tu_build(&s, N, 1, 0);
    CHECK(base != NULL, "attributes: build");
    if (!base) return;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        uint32_t a = cases[i].attributes;
        size_t extra = (size_t)(cases[i].bytes_per_node - 16) * base->node_count, lo, hi;
        t = tu_build(&s, N, 1, a);
        CHECK(t != NULL, "attributes 0x%x: build", a);
        if (!t) continue;
        CHECK(t->attributes == a, "attributes 0x%x: tree says 0x%x", a, t->attributes);
        CHECK(t->bytes_per_node == cases[i].bytes_per_node, "attributes 0x%x: bytes_per_node %u, expected %u", a,
              (unsigned)t->bytes_per_node, cases[i].bytes_per_node);
        CHECK(!(a & MLOD_ATTR_CONE) == !t->cones && !(a & MLOD_ATTR_AREA) == !t->areas &&
                  !(a & MLOD_ATTR_COLOR) == !t->colors,
              "attributes 0x%x: arrays cones %p areas %p colors %p", a, (void *)t->cones, (void *)t->areas,
              (void *)t->colors);
        CHECK(!(a & MLOD_ATTR_REFIT) == !t->leaf_sources && !(a & MLOD_ATTR_REFIT) == !t->leaf_barycentrics &&
                  !(a & MLOD_ATTR_REFIT) == !t->triangle_areas && !(a & MLOD_ATTR_REFIT) == !t->triangle_leaves &&
                  !(a & MLOD_ATTR_REFIT) == !t->changes && !(a & MLOD_ATTR_REFIT_CACHE) == !t->corners &&
                  !(a & MLOD_ATTR_REFIT_CACHE) == !t->corners_changed,
              "attributes 0x%x: refit arrays present iff asked", a);
        CHECK(same_array(t->spheres, base->spheres, 16 * (size_t)N * 2 - 16),
              "attributes 0x%x: the spheres depend on the attributes", a);
        /* refit: source and barycentrics per leaf, build area and refit scratch per triangle */
        lo = extra + ((a & MLOD_ATTR_REFIT) ? 12 * (size_t)N + 40 * (s.index_count / 3) : 0);
        /* the corners: positions, normals with cones, colours with colours; a byte of scratch */
        if (a & MLOD_ATTR_REFIT_CACHE)
            lo += (36 * (1 + !!(a & MLOD_ATTR_CONE) + !!(a & MLOD_ATTR_COLOR)) + 1) * (size_t)(s.index_count / 3);
        hi = lo + 256;
        CHECK(t->bytes >= base->bytes + lo && t->bytes <= base->bytes + hi,
              "attributes 0x%x: bytes %zu, without attributes %zu, expected %zu more (+256)", a, t->bytes, base->bytes, lo);
        CHECK(t->bytes >= t->bytes_per_node * t->node_count, "attributes 0x%x: bytes %zu below bytes_per_node x nodes", a,
              t->bytes);
        mlod_tree_destroy(t);
    }
    mlod_tree_destroy(base);
    { /* fewer leaves than triangles: no per-triangle refit scratch */
        const uint32_t few = 100, triangles = s.index_count / 3;
        base = tu_build(&s, few, 1, 0);
        t = tu_build(&s, few, 1, MLOD_ATTR_REFIT);
        CHECK(base && t && few < triangles, "attributes, %u leaves on %u triangles: builds", few, triangles);
        if (base && t) {
            /* source and barycentrics per leaf, the record of changes per node, an area per triangle */
            size_t lo = 12 * (size_t)few + 4 * (2 * (size_t)few - 1) + 8 * (size_t)triangles;
            CHECK(t->triangle_areas && !t->triangle_leaves, "attributes, %u leaves: refit scratch %p, expected none", few,
                  t->triangle_leaves);
            CHECK(t->bytes >= base->bytes + lo && t->bytes <= base->bytes + lo + 256,
                  "attributes, %u leaves: bytes %zu, without refit data %zu, expected %zu more (+256)", few, t->bytes,
                  base->bytes, lo);
        }
        mlod_tree_destroy(base);
        mlod_tree_destroy(t);
    }
    scene_free(&s);
}

static void test_constant_color_and_scale(void)
{
    scene_mesh s;
    mlod_tree *t, *t2, *t0;
    mlod_mesh m;
    mlod_build_desc d;
    uint32_t i, bad = 0, badr = 0;
    const uint32_t N = 1500;
    scene_torus(&s, 1.0f, 0.25f, 20, 10);
    for (i = 0; i < s.vertex_count; i++) scene_set3(s.colors, i, 0.25, 0.5, 0.75);
    t = tu_build(&s, N, 5, MLOD_ATTR_COLOR);
    CHECK(t != NULL, "constant colour: build");
    if (!t) return;
    for (i = 0; i < t->node_count; i++)
        if (fabs(t->colors[3 * i] - 0.25) > 1e-6 || fabs(t->colors[3 * i + 1] - 0.5) > 1e-6 ||
            fabs(t->colors[3 * i + 2] - 0.75) > 1e-6)
            bad++;
    CHECK(bad == 0, "constant colour: %u nodes whose mean colour is not (0.25, 0.5, 0.75)", bad);
    /* radius_scale multiplies the leaf radii; 0 means 1 */
    m = tu_mesh(&s);
    d = tu_desc(N, 5, MLOD_ATTR_COLOR);
    d.radius_scale = 2.5f;
    t2 = NULL;
    CHECK(mlod_build_mesh(&m, &d, &t2, NULL) == MLOD_OK && t2, "radius_scale 2.5: build");
    d.radius_scale = 1.0f;
    t0 = NULL;
    CHECK(mlod_build_mesh(&m, &d, &t0, NULL) == MLOD_OK && t0, "radius_scale 1: build");
    if (t2 && t0) {
        for (i = N - 1; i < t->node_count; i++) {
            if (fabs(t2->spheres[4 * i + 3] - 2.5 * t->spheres[4 * i + 3]) > 1e-6 * t2->spheres[4 * i + 3]) badr++;
            if (memcmp(t->spheres + 4 * i, t2->spheres + 4 * i, 12) != 0) badr++;
        }
        CHECK(badr == 0, "radius_scale 2.5: %u leaves not at the same centres with 2.5x the radius", badr);
        CHECK(t2->radius_scale == 2.5f, "radius_scale 2.5: tree says %g", t2->radius_scale);
        CHECK(memcmp(t0->spheres, t->spheres, 16 * (size_t)t->node_count) == 0, "radius_scale 0 and 1 differ");
        tu_check_containment(t2, "radius_scale 2.5");
    }
    mlod_tree_destroy(t0);
    mlod_tree_destroy(t2);
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* Interleaved vertices (stride 36: position, normal, colour) give the same
   tree as packed arrays. */
static void test_strides(void)
{
    scene_mesh s;
    float *inter;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(2000, 9, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_AREA);
    mlod_tree *a = NULL, *b = NULL;
    uint32_t i;
    scene_torus(&s, 1.0f, 0.3f, 16, 8);
    inter = (float *)malloc(sizeof(float) * 9 * s.vertex_count);
    for (i = 0; i < s.vertex_count; i++) {
        memcpy(inter + 9 * i, s.positions + 3 * i, 12);
        memcpy(inter + 9 * i + 3, s.normals + 3 * i, 12);
        memcpy(inter + 9 * i + 6, s.colors + 3 * i, 12);
    }
    m = tu_mesh(&s);
    CHECK(mlod_build_mesh(&m, &d, &a, NULL) == MLOD_OK, "strides: packed build");
    m.positions = inter;
    m.normals = inter + 3;
    m.colors = inter + 6;
    m.position_stride = m.normal_stride = m.color_stride = 36;
    CHECK(mlod_build_mesh(&m, &d, &b, NULL) == MLOD_OK, "strides: interleaved build");
    if (a && b) CHECK(same_tree(a, b), "strides: interleaved vertices gave another tree than packed ones");
    m.position_stride = m.normal_stride = m.color_stride = 12;
    m.positions = s.positions;
    m.normals = s.normals;
    m.colors = s.colors;
    mlod_tree_destroy(b);
    b = NULL;
    CHECK(mlod_build_mesh(&m, &d, &b, NULL) == MLOD_OK && b && a && same_tree(a, b), "strides: stride 12 equals stride 0");
    {
        /* strides that are not 0 or a multiple of 4 of at least 12 (radii:
           a multiple of 4) are refused, before any float is read */
        static const size_t bad[5] = {4, 8, 11, 13, 38};
        mlod_points p;
        mlod_tree *c = NULL;
        mlod_error e;
        int k, refused = 0;
        for (k = 0; k < 5; k++) {
            m.position_stride = bad[k];
            refused += mlod_build_mesh(&m, &d, &c, &e) == MLOD_ERROR_INVALID_ARGUMENT && c == NULL;
            m.position_stride = 0;
            m.normal_stride = bad[k];
            refused += mlod_build_mesh(&m, &d, &c, &e) == MLOD_ERROR_INVALID_ARGUMENT && c == NULL;
            m.normal_stride = 0;
        }
        CHECK(refused == 10, "strides: %d of 10 bad position and normal strides refused", refused);
        memset(&p, 0, sizeof p);
        p.positions = s.positions;
        p.count = s.vertex_count;
        p.radii = s.positions; /* any non-negative floats would do; only the stride matters here */
        p.radius_stride = 6;
        CHECK(mlod_build_points(&p, &d, &c, &e) == MLOD_ERROR_INVALID_ARGUMENT && c == NULL, "strides: radius stride 6 refused");
        p.color_stride = 0;
        p.radius_stride = 12;
        p.radii = NULL;
        p.position_stride = 14;
        CHECK(mlod_build_points(&p, &d, &c, &e) == MLOD_ERROR_INVALID_ARGUMENT && c == NULL, "strides: point stride 14 refused");
        mlod_tree_destroy(c);
    }
    mlod_tree_destroy(a);
    mlod_tree_destroy(b);
    free(inter);
    scene_free(&s);
}

/* Flat square without normals: every leaf normal is the face normal (+z,
   the counter-clockwise one) and the root cone stays narrow. */
static void test_flat_cones(void)
{
    scene_mesh s;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(500, 2, MLOD_ATTR_CONE);
    mlod_tree *t = NULL;
    uint32_t j, bad = 0;
    scene_unit_square(&s);
    m = tu_mesh(&s);
    m.normals = NULL;
    CHECK(mlod_build_mesh(&m, &d, &t, NULL) == MLOD_OK && t, "flat cones: build");
    if (t) {
        for (j = 0; j < 500; j++)
            if (t->cones[4 * (499 + j) + 2] < 0.99999f) bad++;
        CHECK(bad == 0, "flat cones: %u leaf normals are not the counter-clockwise face normal +z", bad);
        CHECK(t->cones[3] < 1e-3f, "flat cones: root half-angle %g on a flat mesh", t->cones[3]);
        tu_check_containment(t, "flat cones");
    }
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* Cones of nearly opposite normals (the merge's axis then rotates by about
   pi/2 from a direction found as the difference of nearly equal vectors):
   pairs and quadruples of points whose normals are n and -n turned by
   0 to 1e-3 rad, their tree's cones checked exactly for containment. */
static void test_opposite_cones(void)
{
    static const double turns[6] = {0.0, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3};
    uint64_t rng = 31337;
    uint32_t trial, built = 0;
    for (trial = 0; trial < 600; trial++) {
        float pos[12], nrm[12];
        double n[3], d[3], turn = turns[trial % 6];
        uint32_t i, count = trial % 2 ? 4 : 2;
        mlod_points pts;
        mlod_build_desc desc = tu_desc(0, 1, MLOD_ATTR_CONE);
        mlod_tree *t = NULL;
        tu_random_unit(&rng, n);
        for (i = 0; i < count; i++) {
            double sign = i % 2 ? -1.0 : 1.0, len;
            int k;
            tu_random_unit(&rng, d);
            for (k = 0; k < 3; k++) d[k] = sign * n[k] + turn * d[k];
            len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (k = 0; k < 3; k++) {
                nrm[3 * i + k] = (float)(d[k] / len);
                pos[3 * i + k] = (float)(0.01 * i + 0.001 * k);
            }
        }
        memset(&pts, 0, sizeof pts);
        pts.positions = pos;
        pts.normals = nrm;
        pts.count = count;
        if (mlod_build_points(&pts, &desc, &t, NULL) != MLOD_OK || !t) {
            CHECK(0, "opposite cones: trial %u: build", trial);
            continue;
        }
        built++;
        tu_check_containment(t, "opposite cones");
        mlod_tree_destroy(t);
    }
    CHECK(built == 600, "opposite cones: %u of 600 trees built", built);
}

/* MLOD_PRECISION_COARSE_POSITIONS: set iff max(|x|max 2^-23, 2^-149) >
   radius_scale sqrt(A/N) / 4 (2^-149: the spacing of denormal floats); bounds
   stay exact either way.  Cases sit a factor >= 1.6 away from the threshold. */
static void check_precision(const scene_mesh *rest, double offset, float scale, uint32_t N, const char *what)
{
    scene_mesh s;
    mlod_tree *t;
    uint32_t i;
    double xmax = 0, A, spacing, limit;
    scene_uv_sphere(&s, 1.0f, 8, 16);
    for (i = 0; i < 3 * s.vertex_count; i++) {
        s.positions[i] = (float)(rest->positions[i] * scale + (i % 3 == 0 ? offset : 0.0));
        if (fabs(s.positions[i]) > xmax) xmax = fabs(s.positions[i]);
    }
    A = scene_area(&s);
    spacing = fmax(xmax * pow(2.0, -23), pow(2.0, -149));
    limit = sqrt(A / N) / 4;
    t = tu_build(&s, N, 1, MLOD_ATTR_CONE);
    CHECK(t != NULL, "%s: build", what);
    if (t) {
        int expect = spacing > limit;
        CHECK(!(t->precision & MLOD_PRECISION_COARSE_POSITIONS) == !expect,
              "%s: precision 0x%x, float spacing %.3g vs sqrt(A/N)/4 %.3g", what, t->precision, spacing, limit);
        tu_check_containment(t, what);
    }
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* The build keeps each triangle's own area for refit (its growth is area now
   over area then): a triangle a million-billionth of the mesh's area keeps
   its area, not what is left of it after a difference of running sums. */
static void test_triangle_areas(void)
{
    /* a unit square, then slivers of area 1e-16 .. 1e-12 after it */
    static float positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2.0f + 1e-6f, 0, 0, 2, 2e-10f, 0,
                                3, 0, 0, 3.0f + 1e-4f, 0, 0, 3, 2e-8f, 0, 4, 0, 0, 4.001f, 0, 0, 4, 2e-9f, 0};
    static uint32_t indices[] = {0, 1, 2, 0, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    scene_mesh s;
    mlod_tree *t;
    uint32_t i;
    memset(&s, 0, sizeof s);
    s.positions = positions;
    s.vertex_count = 13;
    s.indices = indices;
    s.index_count = 15;
    t = tu_build(&s, 500, 3, MLOD_ATTR_REFIT);
    CHECK(t && t->triangle_areas, "triangle areas: build");
    if (!t || !t->triangle_areas) return;
    for (i = 0; i < 5; i++) {
        double area = tu_triangle_area(&s, i);
        CHECK(fabs(t->triangle_areas[i] - area) <= 1e-12 * area,
              "triangle areas: triangle %u of area %.17g is kept as %.17g", i, area, t->triangle_areas[i]);
    }
    mlod_tree_destroy(t);
}

static void test_coarse_positions(void)
{
    scene_mesh s;
    scene_uv_sphere(&s, 1.0f, 8, 16);
    check_precision(&s, 0.0, 1.0f, 2000, "precision: unit sphere at the origin");
    check_precision(&s, 1e8, 1.0f, 2000, "precision: unit sphere at 1e8");
    check_precision(&s, 1e5, 1.0f, 2000, "precision: unit sphere at 1e5, N=2000");
    check_precision(&s, 1e5, 1.0f, 20000, "precision: unit sphere at 1e5, N=20000");
    check_precision(&s, 0.0, 1e-15f, 2000, "precision: sphere of radius 1e-15");
    check_precision(&s, 0.0, 1e15f, 2000, "precision: sphere of radius 1e15");
    /* Denormal scales: the float spacing is 2^-149 there, however small |x|. */
    check_precision(&s, 0.0, 1e-36f, 2000, "precision: sphere of radius 1e-36 (normal floats)");
    check_precision(&s, 0.0, 1e-44f, 2000, "precision: sphere of radius 1e-44 (denormal floats, leaves finer)");
    check_precision(&s, 0.0, 1e-41f, 2000, "precision: sphere of radius 1e-41 (denormal floats, leaves coarser)");
    scene_free(&s);
}

/* ------------------------------------------------------------- progress */

typedef struct progress_log {
    unsigned calls, bad;
    float last;
} progress_log;

static int log_progress(void *user, float f)
{
    progress_log *p = (progress_log *)user;
    if (!(f >= 0 && f <= 1) || f < p->last) p->bad++;
    p->last = f;
    p->calls++;
    return 0;
}

static void test_progress(void)
{
    scene_mesh s;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(30000, 1, 0);
    mlod_tree *t = NULL;
    progress_log log = {0, 0, 0.0f};
    scene_torus(&s, 1.0f, 0.3f, 16, 8);
    m = tu_mesh(&s);
    d.progress = log_progress;
    d.progress_user = &log;
    CHECK(mlod_build_mesh(&m, &d, &t, NULL) == MLOD_OK && t, "progress: build");
    CHECK(log.bad == 0, "progress: %u fractions outside [0,1] or decreasing", log.bad);
    printf("  progress: %u calls, last %.3f\n", log.calls, log.last);
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* The documented sampling, one sample after the other (the reference for
   the build's, which places samples in chunks, each finding where it
   starts by binary search): sample i at u_i = (i + hash(seed, 0, i)) / N
   * A along the running areas, in the first triangle whose running sum
   passes u_i (the last with area at most), at x = (u_i - start) / area,
   y = frac(hash(seed, 1, tri) + run * golden) where run counts the
   samples before it in its triangle; (s, t) = sqrt(x) (1 - y, y). */
typedef struct sample_ref {
    uint32_t tri;
    float s, t;
} sample_ref;

static int sample_ref_order(const void *a, const void *b)
{
    const sample_ref *x = (const sample_ref *)a, *y = (const sample_ref *)b;
    uint32_t xs, ys, xt, yt;
    memcpy(&xs, &x->s, 4);
    memcpy(&ys, &y->s, 4);
    memcpy(&xt, &x->t, 4);
    memcpy(&yt, &y->t, 4);
    if (x->tri != y->tri) return x->tri < y->tri ? -1 : 1;
    if (xs != ys) return xs < ys ? -1 : 1;
    return xt < yt ? -1 : xt > yt;
}

static void reference_samples(const mlod_mesh *m, uint32_t n, uint64_t seed, sample_ref *out)
{
    uint32_t T = m->index_count / 3, tri = 0, last = 0, i, run = 0, k;
    double *sum = (double *)malloc(sizeof(double) * (T + 1));
    sum[0] = 0.0;
    for (k = 0; k < T; k++) {
        sum[k + 1] = sum[k] + mlod__triangle_area(m, k);
        if (sum[k + 1] > sum[k]) last = k;
    }
    for (i = 0; i < n; i++) {
        double u = ((double)i + mlod__hash01(seed, 0, i)) / n * sum[T], x, y;
        uint32_t was = tri;
        while (tri < last && sum[tri + 1] <= u) tri++;
        run = i > 0 && tri == was ? run + 1 : 0;
        x = (u - sum[tri]) / (sum[tri + 1] - sum[tri]);
        x = x < 0.0 ? 0.0 : x > 1.0 ? 1.0 : x;
        y = mlod__hash01(seed, 1, tri) + run * 0.6180339887498948482;
        y -= floor(y);
        out[i].tri = tri;
        out[i].s = (float)(sqrt(x) * (1.0 - y));
        out[i].t = (float)(sqrt(x) * y);
    }
    free(sum);
}

/* The build's samples (the leaves' triangles and barycentrics) are the
   reference's, as a set, for meshes whose triangles hold runs of samples
   longer than a chunk and zero-area triangles among them, with and
   without a pool. */
static void test_sampling_reference(void)
{
    static const float square[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const uint32_t two[6] = {0, 1, 2, 0, 2, 3};
    static const uint32_t holes[15] = {0, 0, 0, 0, 1, 2, 1, 1, 2, 0, 2, 3, 2, 2, 2}; /* zero areas first, between, last */
    scene_mesh sphere;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel hook = mlod_pool_parallel(pool);
    int c, h;
    scene_uv_sphere(&sphere, 1.0f, 12, 24);
    for (c = 0; c < 3; c++) {
        mlod_mesh m;
        uint32_t n = c == 0 ? 300000u : c == 1 ? 200003u : 140001u, j, differ;
        sample_ref *ref = (sample_ref *)malloc(sizeof(sample_ref) * n), *got = (sample_ref *)malloc(sizeof(sample_ref) * n);
        const char *name = c == 0 ? "two triangles" : c == 1 ? "zero-area triangles among two" : "sphere";
        memset(&m, 0, sizeof m);
        if (c < 2) {
            m.positions = square;
            m.vertex_count = 4;
            m.indices = c == 0 ? two : holes;
            m.index_count = c == 0 ? 6 : 15;
        } else {
            m = tu_mesh(&sphere);
        }
        reference_samples(&m, n, 5, ref);
        qsort(ref, n, sizeof *ref, sample_ref_order);
        for (h = 0; h < 2; h++) {
            mlod_build_desc d = tu_desc(n, 5, MLOD_ATTR_REFIT);
            mlod_tree *t = NULL;
            d.parallel = h ? &hook : NULL;
            CHECK(mlod_build_mesh(&m, &d, &t, NULL) == MLOD_OK && t, "samples, %s: build", name);
            if (!t) continue;
            for (j = 0; j < n; j++) {
                got[j].tri = t->leaf_sources[j];
                got[j].s = t->leaf_barycentrics[2 * (size_t)j];
                got[j].t = t->leaf_barycentrics[2 * (size_t)j + 1];
            }
            qsort(got, n, sizeof *got, sample_ref_order);
            for (j = 0, differ = 0; j < n; j++) differ += sample_ref_order(&ref[j], &got[j]) != 0;
            CHECK(differ == 0, "samples, %s, %s: %u of %u differ from the one-by-one reference", name,
                  h ? "pool of 2" : "no hook", differ, n);
            mlod_tree_destroy(t);
        }
        free(ref);
        free(got);
    }
    mlod_pool_destroy(pool);
    scene_free(&sphere);
}

/* The build through a parallel-for hook (pools of 1, 2 and 3 threads, and
   hooks that run tasks backwards or odds first) gives the tree it gives
   without one, bit for bit, for a mesh and for points with and without
   radii; progress is reported the same way. */
static void test_parallel_build(void)
{
    const uint32_t all = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT, N = 30011, P = 20000;
    scene_mesh s;
    mlod_mesh m;
    mlod_points pts;
    mlod_pool *pools[3];
    mlod_parallel hooks[5];
    mlod_tree *base[3] = {NULL, NULL, NULL};
    float *pos = (float *)malloc(sizeof(float) * 3 * P), *rad = (float *)malloc(sizeof(float) * P);
    uint64_t rng = 5;
    uint32_t h, i, kind, differ[3] = {0, 0, 0}, progress_differ = 0;
    progress_log base_log = {0, 0, 0.0f};
    if (!pos || !rad || !scene_torus(&s, 1.0f, 0.4f, 48, 24)) {
        CHECK(0, "parallel build: set-up failed");
        free(pos);
        free(rad);
        return;
    }
    m = tu_mesh(&s);
    for (i = 0; i < P; i++) {
        double n[3];
        tu_random_unit(&rng, n);
        scene_set3(pos, i, 2 * n[0], n[1], 0.5 * n[2] + 0.1 * scene_rng_double(&rng));
        rad[i] = scene_rng_range(&rng, 0.01f, 0.05f);
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.count = P;
    tu_hooks(pools, hooks);
    for (h = 0; h <= 5; h++) { /* h == 5: no hook, the reference; built first */
        uint32_t which = h == 0 ? 5 : h - 1;
        for (kind = 0; kind < 3; kind++) {
            mlod_build_desc d = tu_desc(N, 9, kind == 0 ? all : MLOD_ATTR_REFIT);
            mlod_tree *t = NULL;
            progress_log log = {0, 0, 0.0f};
            mlod_result r;
            d.parallel = which == 5 ? NULL : &hooks[which];
            if (kind == 0) {
                d.progress = log_progress;
                d.progress_user = &log;
            }
            pts.radii = kind == 1 ? rad : NULL;
            r = kind == 0 ? mlod_build_mesh(&m, &d, &t, NULL) : mlod_build_points(&pts, &d, &t, NULL);
            CHECK(r == MLOD_OK && t, "parallel build: hook %u, %s: build", which, kind == 0 ? "mesh" : "points");
            if (!t) continue;
            if (which == 5) {
                base[kind] = t;
                if (kind == 0) base_log = log;
                continue;
            }
            differ[kind] += base[kind] && !same_tree(base[kind], t);
            if (kind == 0) progress_differ += log.calls != base_log.calls || log.last != base_log.last || log.bad;
            mlod_tree_destroy(t);
        }
    }
    CHECK(differ[0] == 0, "parallel build, mesh: %u of 5 hooks built another tree than no hook", differ[0]);
    CHECK(differ[1] == 0, "parallel build, points with radii: %u of 5 hooks built another tree", differ[1]);
    CHECK(differ[2] == 0, "parallel build, points without radii: %u of 5 hooks built another tree", differ[2]);
    CHECK(progress_differ == 0 && base_log.calls > 10, "parallel build: progress differs under %u hooks (%u calls without)",
          progress_differ, base_log.calls);
    if (base[0]) tu_check_containment(base[0], "parallel build, mesh");
    for (kind = 0; kind < 3; kind++) mlod_tree_destroy(base[kind]);
    for (h = 0; h < 3; h++) mlod_pool_destroy(pools[h]);
    free(pos);
    free(rad);
    scene_free(&s);
}

/* ---------------------------------------------------------- split rule */

/* The order of the leaves against a reference written from the rule
   (DESIGN.md, tree layout): a node's items go to its children, the first
   (leaves below the left child) of them to the left, in the order of their
   coordinate along the axis whose two halves' boxes have the smaller sum
   of diagonal^3 (the first axis on a tie), equal coordinates by item
   index.  Sorted afresh at every node, with plain float comparisons. */
static const float *ref_pos;
static int ref_axis;
static int ref_compare(const void *a, const void *b)
{
    uint32_t i = *(const uint32_t *)a, j = *(const uint32_t *)b;
    float x = ref_pos[3 * (size_t)i + ref_axis], y = ref_pos[3 * (size_t)j + ref_axis];
    return x < y ? -1 : x > y ? 1 : (i > j) - (i < j);
}

static double ref_box_volume(const uint32_t *items, uint32_t count)
{
    float lo[3], hi[3];
    double d2 = 0.0;
    uint32_t i;
    int k;
    for (k = 0; k < 3; k++) lo[k] = hi[k] = ref_pos[3 * (size_t)items[0] + k];
    for (i = 1; i < count; i++)
        for (k = 0; k < 3; k++) {
            float x = ref_pos[3 * (size_t)items[i] + k];
            if (x < lo[k]) lo[k] = x;
            if (x > hi[k]) hi[k] = x;
        }
    for (k = 0; k < 3; k++) d2 += ((double)hi[k] - lo[k]) * ((double)hi[k] - lo[k]);
    return d2 * sqrt(d2);
}

static void ref_order(uint32_t *items, uint32_t count, uint32_t node, uint32_t n, uint32_t *leaf_item)
{
    uint32_t nl;
    double best = 0.0;
    int k, axis = 0;
    if (node >= n - 1) {
        leaf_item[node - (n - 1)] = items[0];
        return;
    }
    nl = tu_leaves_below(2 * (uint64_t)node + 1, n);
    for (k = 0; k < 3; k++) {
        double v;
        ref_axis = k;
        qsort(items, count, sizeof(uint32_t), ref_compare);
        v = ref_box_volume(items, nl) + ref_box_volume(items + nl, count - nl);
        if (k == 0 || v < best) {
            best = v;
            axis = k;
        }
    }
    ref_axis = axis;
    qsort(items, count, sizeof(uint32_t), ref_compare);
    ref_order(items, nl, 2 * node + 1, n, leaf_item);
    ref_order(items + nl, count - nl, 2 * node + 2, n, leaf_item);
}

/* The build's order against the reference's, with and without a pool of
   3 threads: sizes below and above the split's pieces (the top depths
   move each axis in MLOD__SPLIT_PARTS parts: fewer items than parts at
   the smallest sizes, uneven parts and nodes at the larger) and the depth
   whose subtrees are split whole (MLOD__SPLIT_SUBTREES nodes: 40000
   leaves reach it). */
static void test_split_rule(void)
{
    static const uint32_t sizes[] = {2, 3, 7, 8, 9, 17, 64, 257, 1000, 3001, 40000, 40001};
    uint64_t rng = 0x5b1175ull;
    uint32_t si;
    mlod_pool *pool = mlod_pool_create(3);
    mlod_parallel hook = mlod_pool_parallel(pool);
    for (si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        uint32_t n = sizes[si], i, grid = si % 2 ? 8 : 1u << 20;
        float *pos = (float *)malloc(sizeof(float) * 3 * n);
        uint32_t *items = (uint32_t *)malloc(sizeof(uint32_t) * n), *leaf_item = (uint32_t *)malloc(sizeof(uint32_t) * n);
        mlod_points pts;
        int h;
        /* a coarse grid (every other size): many equal coordinates */
        for (i = 0; i < 3 * n; i++) pos[i] = (float)((uint32_t)(scene_rng_double(&rng) * grid) + 1) / (float)grid;
        memset(&pts, 0, sizeof pts);
        pts.positions = pos;
        pts.count = n;
        for (i = 0; i < n; i++) items[i] = i;
        ref_pos = pos;
        ref_order(items, n, 0, n, leaf_item);
        for (h = 0; h < 2; h++) {
            mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_REFIT);
            mlod_tree *t = NULL;
            uint32_t bad = 0;
            d.parallel = h ? &hook : NULL;
            CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t && t->leaf_sources,
                  "split rule: build of %u points (%s)", n, h ? "3 threads" : "no pool");
            for (i = 0; t && t->leaf_sources && i < n; i++) bad += t->leaf_sources[i] != leaf_item[i];
            CHECK(t && bad == 0, "split rule: %u of %u leaves (grid %u, %s) hold another item than the reference's", bad,
                  n, grid, h ? "3 threads" : "no pool");
            mlod_tree_destroy(t);
        }
        free(pos);
        free(items);
        free(leaf_item);
    }
    mlod_pool_destroy(pool);
}

/* --------------------------------------------------------------- points */

static void test_points(void)
{
    const uint32_t N = 1000;
    float *pos = (float *)malloc(sizeof(float) * 3 * N), *nrm = (float *)malloc(sizeof(float) * 3 * N),
          *rad = (float *)malloc(sizeof(float) * N), *col = (float *)malloc(sizeof(float) * 3 * N);
    uint64_t rng = 77;
    uint32_t i, bad = 0, badc = 0, badn = 0, badr = 0;
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    mlod_tree *t = NULL, *u = NULL;
    tu_layout L;
    for (i = 0; i < N; i++) {
        double n[3];
        tu_random_unit(&rng, n);
        scene_set3(pos, i, 3 * n[0], 3 * n[1] + 0.01 * scene_rng_double(&rng), 3 * n[2]);
        scene_set3(nrm, i, n[0], n[1], n[2]);
        rad[i] = scene_rng_range(&rng, 0.01f, 0.2f);
        scene_set3(col, i, scene_rng_double(&rng), scene_rng_double(&rng), scene_rng_double(&rng));
    }
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.normals = nrm;
    pts.radii = rad;
    pts.colors = col;
    pts.count = N;
    d.radius_scale = 1.5f;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t, "points with radii: build");
    if (t) {
        CHECK(t->leaf_count == N && t->node_count == 2 * N - 1, "points: %u leaves", t->leaf_count);
        CHECK(t->leaf_barycentrics == NULL && t->triangle_areas == NULL && t->triangle_count == 0,
              "points: mesh refit arrays present");
        CHECK(t->leaf_sources != NULL, "points: leaf_sources missing with MLOD_ATTR_REFIT");
        for (i = 0; t->leaf_sources && i < N; i++) {
            uint32_t p = t->leaf_sources[i], node = N - 1 + i, k;
            if (p >= N) {
                bad++;
                continue;
            }
            if (memcmp(t->spheres + 4 * node, pos + 3 * p, 12) != 0) bad++;
            if (!(t->spheres[4 * node + 3] >= 1.5f * rad[p] && t->spheres[4 * node + 3] <= 1.5f * rad[p] * (1 + 1e-6)))
                badr++;
            for (k = 0; k < 3; k++) {
                if (t->colors[3 * node + k] != col[3 * p + k]) badc++;
                if (fabs(t->cones[4 * node + k] - nrm[3 * p + k]) > 1e-6) badn++;
            }
        }
        CHECK(bad == 0, "points: %u leaves not centred on their source point", bad);
        CHECK(badr == 0, "points: %u leaf radii not radius_scale x radius", badr);
        CHECK(badc == 0, "points: %u leaf colour components not the point's colour", badc);
        CHECK(badn == 0, "points: %u leaf cone axes not the point's normal", badn);
        tu_check_containment(t, "points with radii");
    }
    /* without radii: radius = radius_scale * R * sqrt(pi / L), R and L >= 8
       the radius and leaf count of the lowest node above the point with at
       least 8 leaves (R taken before the leaf radii were added, so at most
       that node's final radius); a point leaf's area is (radius /
       radius_scale)^2, area_unit their mean; no normals: full-sphere cones */
    pts.radii = NULL;
    pts.normals = NULL;
    d.attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA;
    CHECK(mlod_build_points(&pts, &d, &u, NULL) == MLOD_OK && u, "points without radii: build");
    if (u) {
        double mean = 0;
        uint32_t bad_area = 0, bad_cone = 0;
        tu_layout_init(&L, N);
        CHECK(u->leaf_sources == NULL, "points without MLOD_ATTR_REFIT have leaf_sources");
        for (i = 0, bad = 0; i < N; i++) {
            uint32_t n = N - 1 + i;
            double r = u->spheres[4 * n + 3], own = (r / 1.5) * (r / 1.5);
            while (L.count[n] < 8 && n > 0) n = (n - 1) / 2;
            if (!(r > 0 && r <= 1.5 * u->spheres[4 * n + 3] * sqrt(TU_PI / L.count[n]) * (1 + 1e-6))) bad++;
            mean += own / N;
            if (fabs(u->areas[N - 1 + i] * u->area_unit - own) > 1e-5 * own) bad_area++;
            if (!(u->cones[4 * (N - 1 + i) + 3] >= TU_PI)) bad_cone++;
        }
        CHECK(bad == 0, "points without radii: %u leaf radii not in (0, 1.5 R sqrt(pi/L)]", bad);
        CHECK(bad_area == 0, "points without radii: %u leaf areas not (radius / radius_scale)^2", bad_area);
        CHECK(fabs(u->area_unit - mean) <= 1e-5 * mean, "points: area_unit %.9g, mean leaf area %.9g", u->area_unit, mean);
        CHECK(bad_cone == 0, "points without normals: %u leaf cones not the full sphere", bad_cone);
        tu_check_containment(u, "points without radii");
        tu_layout_free(&L);
    }
    mlod_tree_destroy(u);
    mlod_tree_destroy(t);
    /* a single point */
    pts.count = 1;
    pts.radii = rad;
    t = NULL;
    pts.normals = nrm;
    CHECK(mlod_build_points(&pts, &d, &t, NULL) == MLOD_OK && t && t->node_count == 1, "one point: build");
    if (t) CHECK(memcmp(t->spheres, pos, 12) == 0, "one point: root not on the point");
    mlod_tree_destroy(t);
    free(pos);
    free(nrm);
    free(rad);
    free(col);
}

int main(void)
{
    int rc;
    test_sizes();
    test_square_strata();
    test_shares();
    test_coverage();
    test_determinism();
    test_attributes();
    test_constant_color_and_scale();
    test_strides();
    test_flat_cones();
    test_opposite_cones();
    test_coarse_positions();
    test_triangle_areas();
    test_progress();
    test_parallel_build();
    test_sampling_reference();
    test_points();
    test_split_rule();
    rc = test_finish();
    fflush(stdout); /* keep the result line even if a sanitizer reports at exit */
    return rc;
}
