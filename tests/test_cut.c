/* tests/test_cut.c - the criterion and the cut.

   - the cut against a brute-force reference straight from the definition
     (every node's mlod_criterion), as sets, statuses and left-to-right
     order, for every view kind (cube maps included), with and without
     back-face culling, on random trees and hand-made cases; the partition
     of the leaves;
   - monotonicity c(child) <= c(parent) on random and adversarial views;
   - the criterion against an independent projection of points sampled on
     the sphere (upper bound, exact image diameter, culling) and against the
     documented formulas in long double;
   - incremental == basic frame after frame on a deforming mesh; lazy is a
     partition, moves at most lazy_steps edges, and converges;
   - identical results for any parallel hook and thread count;
   - unchanged views are skipped: a view whose view bytes, tree (object and
     revision) and epsilon did not change, and whose cut was exact, is not
     evaluated and keeps its list (checked against the reference); any
     change (one byte, epsilon, a refit, another tree, a reset) recomputes
     it, and a lazy cut still converging is never skipped. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"
#include <pthread.h>

/* ------------------------------------------------------------ workspace */

typedef struct workspace {
    double *crit;
    uint64_t *keys, *scratch;
    uint32_t *nodes, *hits;
    uint8_t *status;
} workspace;

static void ws_init(workspace *w, uint32_t nodes)
{
    w->crit = (double *)malloc(sizeof(double) * nodes);
    w->keys = (uint64_t *)malloc(sizeof(uint64_t) * nodes);
    w->scratch = (uint64_t *)malloc(sizeof(uint64_t) * 2 * nodes);
    w->nodes = (uint32_t *)malloc(sizeof(uint32_t) * nodes);
    w->hits = (uint32_t *)malloc(sizeof(uint32_t) * nodes);
    w->status = (uint8_t *)malloc(nodes);
}

static void ws_free(workspace *w)
{
    free(w->crit);
    free(w->keys);
    free(w->scratch);
    free(w->nodes);
    free(w->hits);
    free(w->status);
}

/* Failures of one scenario, counted per property. */
typedef struct tally {
    uint32_t views, reference, partition, counts;
    char first_reference[300], first_partition[200], first_counts[200];
} tally;

static void tally_report(const tally *t, const char *what)
{
    CHECK(t->reference == 0, "%s: %u of %u views differ from the reference cut; first: %s", what, t->reference, t->views,
          t->first_reference);
    CHECK(t->partition == 0, "%s: %u of %u views do not partition the leaves; first: %s", what, t->partition, t->views,
          t->first_partition);
    CHECK(t->counts == 0, "%s: %u of %u views with counts that disagree with the statuses; first: %s", what, t->counts,
          t->views, t->first_counts);
}

/* Check every view of a basic-mode cut against the reference. */
static void check_against_reference(const mlod_tree *tree, const tu_layout *L, const mlod_view *views, uint32_t first,
                                    uint32_t count, float eps, const mlod_cut *cut, workspace *w, tally *t)
{
    uint32_t v;
    for (v = first; v < first + count; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        uint32_t n = tu_reference_cut(tree, L, views + v, eps, w->crit, w->keys, w->nodes, w->status), bad;
        char why[200];
        t->views++;
        if (tu_cut_differs(&cv, w->nodes, w->status, n, L, w->scratch, why, sizeof why)) {
            if (!t->reference++)
                snprintf(t->first_reference, sizeof t->first_reference, "view %u (kind %d, flags %u), eps %g: %s", v,
                         (int)views[v].kind, views[v].flags, eps, why);
        }
        bad = tu_partition_errors(L, cv.nodes, cv.count, w->hits);
        if (bad && !t->partition++)
            snprintf(t->first_partition, sizeof t->first_partition, "view %u: %u leaves covered != 1 times", v, bad);
        if (!tu_counts_ok(&cv) && !t->counts++)
            snprintf(t->first_counts, sizeof t->first_counts, "view %u: count %u drawn %u culled %u oversize %u coarse %u", v,
                     cv.count, cv.drawn, cv.culled, cv.oversize, cv.coarse);
    }
}

static mlod_cut_params params(mlod_cut_mode mode, float eps, uint32_t lazy_steps, const mlod_parallel *par)
{
    mlod_cut_params p;
    memset(&p, 0, sizeof p);
    p.mode = mode;
    p.epsilon = eps;
    p.lazy_steps = lazy_steps;
    p.parallel = par;
    return p;
}

/* The tree of N points (positions, normals and radii; freed here), built
   with this seed. */
static mlod_tree *points_tree(float *pos, float *nrm, float *rad, uint32_t N, uint64_t seed)
{
    mlod_points pts;
    mlod_build_desc d = tu_desc(0, seed, MLOD_ATTR_CONE);
    mlod_tree *t = NULL;
    memset(&pts, 0, sizeof pts);
    pts.positions = pos;
    pts.normals = nrm;
    pts.radii = rad;
    pts.count = N;
    if (mlod_build_points(&pts, &d, &t, NULL) != MLOD_OK) t = NULL;
    free(pos);
    free(nrm);
    free(rad);
    return t;
}

static mlod_tree *random_points_tree(uint32_t N, uint64_t seed, double radius_lo, double radius_hi)
{
    uint64_t build_seed = seed;
    float *pos = (float *)malloc(sizeof(float) * 3 * N), *nrm = (float *)malloc(sizeof(float) * 3 * N),
          *rad = (float *)malloc(sizeof(float) * N);
    uint32_t i;
    for (i = 0; i < N; i++) {
        double n[3];
        scene_set3(pos, i, scene_rng_range(&seed, -1, 1), scene_rng_range(&seed, -1, 1), scene_rng_range(&seed, -1, 1));
        tu_random_unit(&seed, n);
        scene_set3(nrm, i, n[0], n[1], n[2]);
        rad[i] = (float)(radius_lo * pow(radius_hi / radius_lo, scene_rng_double(&seed)));
    }
    return points_tree(pos, nrm, rad, N, build_seed);
}

/* N points on the unit sphere, facing out, of radius `radius`: a surface,
   whose cuts coarsen with epsilon as its image's area. */
static mlod_tree *sphere_points_tree(uint32_t N, uint64_t seed, double radius)
{
    uint64_t build_seed = seed;
    float *pos = (float *)malloc(sizeof(float) * 3 * N), *nrm = (float *)malloc(sizeof(float) * 3 * N),
          *rad = (float *)malloc(sizeof(float) * N);
    uint32_t i;
    for (i = 0; i < N; i++) {
        double n[3];
        tu_random_unit(&seed, n);
        scene_set3(pos, i, n[0], n[1], n[2]);
        scene_set3(nrm, i, n[0], n[1], n[2]);
        rad[i] = (float)radius;
    }
    return points_tree(pos, nrm, rad, N, build_seed);
}

/* -------------------------------------------------- cuts vs reference */

static void test_random_trees(void)
{
    static const float epsilons[] = {0.5f, 3.0f, 40.0f};
    uint64_t rng = 2024;
    int scene_kind, rep;
    for (scene_kind = 0; scene_kind < 5; scene_kind++) {
        for (rep = 0; rep < 2; rep++) {
            scene_mesh s;
            mlod_tree *tree;
            uint32_t N = rep == 0 ? 1 + (uint32_t)(scene_rng_double(&rng) * 3000) : (scene_kind == 0 ? 1u : 2u + (uint32_t)scene_kind),
                     nv = 16, v, e;
            double c[3] = {0, 0, 0}, R = 1.5;
            mlod_view views[16];
            mlod_cut *cut_b = NULL, *cut_i = NULL;
            tu_layout L;
            workspace w;
            tally t;
            char what[96];
            memset(&s, 0, sizeof s);
            switch (scene_kind) {
            case 0: scene_uv_sphere(&s, 1.0f, 10, 20); break;
            case 1: scene_torus(&s, 1.0f, 0.3f, 24, 12); break;
            case 2: scene_room(&s); break;
            case 3: scene_soup(&s, 300, rng); break;
            default: break;
            }
            if (scene_kind < 4) {
                tu_bounds(&s, c, &R);
                tree = tu_build(&s, N, N * 7 + scene_kind, scene_kind == 3 ? 0 : MLOD_ATTR_CONE);
            } else {
                tree = random_points_tree(N, N, 0.005, 0.2);
            }
            snprintf(what, sizeof what, "scene %d N=%u", scene_kind, N);
            CHECK(tree != NULL, "%s: build", what);
            if (!tree) {
                scene_free(&s);
                continue;
            }
            for (v = 0; v < nv; v++) views[v] = tu_random_view(&rng, (mlod_view_kind)(v % 5), c, R);
            tu_layout_init(&L, N);
            ws_init(&w, tree->node_count);
            mlod_cut_create(nv, NULL, &cut_b, NULL);
            mlod_cut_create(nv, NULL, &cut_i, NULL);
            for (e = 0; e < sizeof epsilons / sizeof epsilons[0]; e++) {
                mlod_cut_params pb = params(MLOD_CUT_BASIC, epsilons[e], 1, NULL);
                mlod_cut_params pi = params(MLOD_CUT_INCREMENTAL, epsilons[e], 1, NULL);
                uint32_t same = 0;
                char label[128];
                memset(&t, 0, sizeof t);
                CHECK(mlod_cut_update(cut_b, tree, views, &pb, NULL) == MLOD_OK, "%s eps %g: basic update", what,
                      epsilons[e]);
                check_against_reference(tree, &L, views, 0, nv, epsilons[e], cut_b, &w, &t);
                snprintf(label, sizeof label, "%s eps %g basic", what, epsilons[e]);
                tally_report(&t, label);
                /* incremental from the previous eps's cut equals basic */
                CHECK(mlod_cut_update(cut_i, tree, views, &pi, NULL) == MLOD_OK, "%s: incremental update", what);
                for (v = 0; v < nv; v++) {
                    mlod_cut_view a = mlod_cut_get(cut_b, v), b = mlod_cut_get(cut_i, v);
                    same += tu_same_cut(&a, &b);
                }
                CHECK(same == nv, "%s eps %g: incremental (from the previous epsilon) equals basic in %u of %u views", what,
                      epsilons[e], same, nv);
            }
            mlod_cut_destroy(cut_b);
            mlod_cut_destroy(cut_i);
            ws_free(&w);
            tu_layout_free(&L);
            mlod_tree_destroy(tree);
            scene_free(&s);
        }
    }
}

/* Far views see the root alone; eps = +inf gives the root alone; a tiny
   eps gives leaves and culled nodes only. */
/* Spheres of radius 0 (points): c = 0 for every view kind, except at a
   paraboloid's eye (d = r = 0), where the paraboloid's rule d <= r gives
   +inf; perspective and cube views cull a point at the eye by their near
   plane, an orthographic view draws it as a point (c = 0).  The manual
   states both. */
static void test_zero_radius(void)
{
    static const float at[2][3] = {{0, 0, 0}, {0.3f, 0.2f, -2.0f}}, zero[2] = {0, 0};
    mlod_points pts;
    mlod_build_desc desc;
    mlod_tree *tree = NULL;
    mlod_error e;
    uint32_t k, leaf, checked = 0, infinite = 0;
    memset(&pts, 0, sizeof pts);
    pts.positions = &at[0][0];
    pts.count = 2;
    pts.radii = zero;
    memset(&desc, 0, sizeof desc);
    CHECK(mlod_build_points(&pts, &desc, &tree, &e) == MLOD_OK, "zero radius: build (%s)", e.message);
    if (!tree) return;
    for (k = 0; k <= MLOD_VIEW_CUBE; k++) {
        mlod_view view = tu_view((mlod_view_kind)k);
        for (leaf = tree->leaf_count - 1; leaf < tree->node_count; leaf++) {
            const float *sphere = tree->spheres + 4 * (size_t)leaf;
            int at_eye = sphere[0] == 0.0f && sphere[1] == 0.0f && sphere[2] == 0.0f;
            int paraboloid = k == MLOD_VIEW_PARABOLOID || k == MLOD_VIEW_DUAL_PARABOLOID;
            double c = mlod_criterion(tree, leaf, &view);
            CHECK(sphere[3] == 0.0f && c == (at_eye && paraboloid ? INFINITY : 0.0),
                  "zero radius: view kind %u, leaf at (%g, %g, %g): c = %g", k, sphere[0], sphere[1], sphere[2], c);
            checked++;
            infinite += c == INFINITY;
        }
    }
    CHECK(checked == 10 && infinite == 2, "zero radius: 5 kinds x 2 leaves (%u), +inf at both paraboloids' eye (%u)",
          checked, infinite);
    mlod_tree_destroy(tree);
}

static void test_hand_made(void)
{
    scene_mesh s;
    mlod_tree *tree;
    mlod_cut *cut = NULL;
    enum { KINDS = 5 }; /* views [0, KINDS) far away, [KINDS, 2 KINDS) inside the root */
    mlod_view views[2 * KINDS];
    tu_layout L;
    workspace w;
    tally t;
    uint32_t v, bad_root = 0, bad_inf = 0, bad_tiny = 0, k;
    uint64_t rng = 5;
    double c[3] = {0, 0, 0};
    mlod_cut_params p;
    scene_uv_sphere(&s, 1.0f, 12, 24);
    tree = tu_build(&s, 5000, 1, MLOD_ATTR_CONE);
    CHECK(tree != NULL, "hand-made: build");
    if (!tree) return;
    tu_layout_init(&L, tree->leaf_count);
    ws_init(&w, tree->node_count);
    mlod_cut_create(2 * KINDS, NULL, &cut, NULL);
    for (k = 0; k < KINDS; k++) {
        double eye[3] = {0, 0, 1e5}, target[3] = {0, 0, 0};
        views[k] = tu_view((mlod_view_kind)k);
        views[k + KINDS] = tu_view((mlod_view_kind)k);
        views[k].far_plane = INFINITY;
        if (k == MLOD_VIEW_ORTHOGRAPHIC) {
            eye[2] = 10;
            views[k].half_width = views[k].half_height = 1e5f;
        }
        tu_look(&rng, views + k, eye, target);
        /* an eye inside the root sphere, looking at the surface */
        eye[2] = 0.5;
        target[0] = 1;
        tu_look(&rng, views + k + KINDS, eye, target);
        views[k + KINDS].flags = MLOD_VIEW_CULL_BACKFACES;
    }
    p = params(MLOD_CUT_BASIC, 1.0f, 1, NULL);
    CHECK(mlod_cut_update(cut, tree, views, &p, NULL) == MLOD_OK, "far views: update");
    for (v = 0; v < KINDS; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        if (!(cv.count == 1 && cv.nodes[0] == 0 && cv.status[0] == MLOD_STATUS_DRAWN && cv.drawn == 1)) bad_root++;
    }
    CHECK(bad_root == 0, "far views: %u of %d views do not see the root alone, drawn", bad_root, KINDS);
    p.epsilon = INFINITY;
    CHECK(mlod_cut_update(cut, tree, views, &p, NULL) == MLOD_OK, "eps=inf: update");
    for (v = 0; v < 2 * KINDS; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        double cr = mlod_criterion(tree, 0, views + v);
        if (!(cv.count == 1 && cv.nodes[0] == 0 && cv.status[0] == (cr == 0 ? MLOD_STATUS_CULLED : MLOD_STATUS_DRAWN)))
            bad_inf++;
    }
    CHECK(bad_inf == 0, "eps=inf: %u of %d views do not have the root alone", bad_inf, 2 * KINDS);
    memset(&t, 0, sizeof t);
    check_against_reference(tree, &L, views, 0, 2 * KINDS, INFINITY, cut, &w, &t);
    tally_report(&t, "eps=inf");
    p.epsilon = 1e-30f;
    for (k = 0; k < KINDS; k++) views[k] = tu_random_view(&rng, (mlod_view_kind)k, c, 1.0);
    CHECK(mlod_cut_update(cut, tree, views, &p, NULL) == MLOD_OK, "eps=1e-30: update");
    for (v = 0; v < 2 * KINDS; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        for (k = 0; k < cv.count; k++)
            if (!(tu_is_leaf(&L, cv.nodes[k]) || cv.status[k] == MLOD_STATUS_CULLED)) bad_tiny++;
    }
    CHECK(bad_tiny == 0, "eps=1e-30: %u cut nodes are neither leaves nor culled", bad_tiny);
    memset(&t, 0, sizeof t);
    check_against_reference(tree, &L, views, 0, 2 * KINDS, 1e-30f, cut, &w, &t);
    tally_report(&t, "eps=1e-30");
    /* the inside views, moderate eps */
    p.epsilon = 2.0f;
    CHECK(mlod_cut_update(cut, tree, views, &p, NULL) == MLOD_OK, "inside views: update");
    memset(&t, 0, sizeof t);
    check_against_reference(tree, &L, views, 0, 2 * KINDS, 2.0f, cut, &w, &t);
    tally_report(&t, "eyes inside the root, eps 2");
    mlod_cut_destroy(cut);
    ws_free(&w);
    tu_layout_free(&L);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* ------------------------------------------------ independent criterion */

typedef struct frame {
    long double e[3], u[3], v[3], w[3];
} frame;

static void ld_normalize(long double *a)
{
    long double n = sqrtl(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    a[0] /= n;
    a[1] /= n;
    a[2] /= n;
}

static long double ld_dot(const long double *a, const long double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void ld_cross(long double *r, const long double *a, const long double *b)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* w = forward / |forward|, u = forward x up normalised, v = u x w. */
static void view_frame(const mlod_view *view, frame *F)
{
    long double f[3], up[3];
    int k;
    for (k = 0; k < 3; k++) {
        F->e[k] = view->position[k];
        f[k] = view->forward[k];
        up[k] = view->up[k];
    }
    for (k = 0; k < 3; k++) F->w[k] = f[k];
    ld_normalize(F->w);
    ld_cross(F->u, f, up);
    ld_normalize(F->u);
    ld_cross(F->v, F->u, F->w);
}

/* A cube map's face i (Vulkan's order +X, -X, +Y, -Y, +Z, -Z over X = u,
   Y = v, Z = -w): its axis a and two unit vectors p, q across it.  The
   criterion only needs the axis (a diameter does not depend on how the
   face's image is turned), so p and q are simply the other two axes. */
static void cube_face_axes(const frame *F, int face, long double *a, long double *p, long double *q)
{
    const long double *X = F->u, *Y = F->v, *W = F->w;
    long double sign = face % 2 ? -1.0L : 1.0L, zsign = face / 2 == 2 ? -1.0L : 1.0L; /* Z = -w */
    const long double *axis = face / 2 == 0 ? X : face / 2 == 1 ? Y : W, *o1 = face / 2 == 0 ? Y : X,
                      *o2 = face / 2 == 2 ? Y : W;
    int k;
    for (k = 0; k < 3; k++) {
        a[k] = sign * zsign * axis[k];
        p[k] = o1[k];
        q[k] = o2[k];
    }
}

/* Pixel coordinates of point p in view (dual: half 0 front, 1 back; cube:
   half is the face, and only points inside that face's frustum, between
   its near and far planes, have an image there: the face then surely
   reaches the sphere).  Returns 0 when p has no image there. */
static int project(const mlod_view *view, const frame *F, const long double *p, int half, long double *px)
{
    long double y[3] = {p[0] - F->e[0], p[1] - F->e[1], p[2] - F->e[2]};
    long double yu = ld_dot(y, F->u), yv = ld_dot(y, F->v), yw = ld_dot(y, F->w), len, s, den;
    switch (view->kind) {
    case MLOD_VIEW_CUBE: {
        long double a[3], pa[3], qa[3], ya, yp, yq;
        cube_face_axes(F, half, a, pa, qa);
        ya = ld_dot(y, a);
        yp = ld_dot(y, pa);
        yq = ld_dot(y, qa);
        if (!(ya > 0) || fabsl(yp) > ya || fabsl(yq) > ya || ya < view->near_plane || ya > (long double)view->far_plane)
            return 0;
        s = view->height / 4.0L; /* f = side / 2 for 90 degrees */
        px[0] = s * yp / ya;
        px[1] = s * yq / ya;
        return 1;
    }
    case MLOD_VIEW_PERSPECTIVE:
        if (yw <= 0) return 0;
        s = (view->height / 2.0L) / tanl(view->fov_y / 2.0L);
        px[0] = s * yu / yw;
        px[1] = s * yv / yw;
        return 1;
    case MLOD_VIEW_PARABOLOID:
        len = sqrtl(yu * yu + yv * yv + yw * yw);
        den = 1 + yw / len;
        if (den <= 1e-12L) return 0;
        s = (view->width > view->height ? view->width : view->height) / 2.0L;
        px[0] = s * yu / len / den;
        px[1] = s * yv / len / den;
        return 1;
    case MLOD_VIEW_DUAL_PARABOLOID:
        len = sqrtl(yu * yu + yv * yv + yw * yw);
        s = (view->width / 2.0L > view->height ? view->width / 2.0L : view->height) / 2.0L;
        if (half == 0) {
            if (yw < 0) return 0;
            den = 1 + yw / len;
            px[0] = s * yu / len / den;
        } else {
            if (yw > 0) return 0;
            den = 1 - yw / len;
            px[0] = -s * yu / len / den;
        }
        px[1] = s * yv / len / den;
        return 1;
    default:
        px[0] = yu * view->width / (2.0L * view->half_width);
        px[1] = yv * view->height / (2.0L * view->half_height);
        return 1;
    }
}

/* Is p inside the view volume, by a margin m (world units)? */
static int inside_volume(const mlod_view *view, const frame *F, const long double *p, long double m)
{
    long double y[3] = {p[0] - F->e[0], p[1] - F->e[1], p[2] - F->e[2]};
    long double yu = ld_dot(y, F->u), yv = ld_dot(y, F->v), yw = ld_dot(y, F->w), ty, tx;
    switch (view->kind) {
    case MLOD_VIEW_PERSPECTIVE:
        ty = tanl(view->fov_y / 2.0L);
        tx = ty * view->width / view->height;
        return yw > view->near_plane + m && yw < (long double)view->far_plane - m &&
               (fabsl(yu) - tx * yw) / sqrtl(1 + tx * tx) < -m && (fabsl(yv) - ty * yw) / sqrtl(1 + ty * ty) < -m;
    case MLOD_VIEW_PARABOLOID: return yw > m;
    case MLOD_VIEW_DUAL_PARABOLOID: return 1;
    case MLOD_VIEW_CUBE: {
        /* the six faces tile every direction: inside means between the
           near and the far cube, by the largest of |X|, |Y|, |Z| */
        long double big = fmaxl(fabsl(yu), fmaxl(fabsl(yv), fabsl(yw)));
        return big > view->near_plane + m && big < (long double)view->far_plane - m;
    }
    default:
        return fabsl(yu) < view->half_width - m && fabsl(yv) < view->half_height - m && yw > view->near_plane + m &&
               yw < (long double)view->far_plane - m;
    }
}

/* What the documentation says about a sphere (and cone) in a view:
   cull = +1 surely culled, -1 surely not, 0 too close to tell;
   value = the documented diameter (may be +inf), value_ok = well
   conditioned enough to compare at 1e-5 relative. */
typedef struct expectation {
    int cull, value_ok;
    long double value;
} expectation;

/* How far a sphere (x = centre - eye, radius r) lies outside a cube face's
   frustum, by its worst culling plane (> 0: that face does not reach it):
   the near and far planes along the face's axis, and its four side planes
   at 45 degrees, |x.p| = x.a and |x.q| = x.a. */
static long double cube_face_outside(const mlod_view *view, const frame *F, const long double *x, long double r,
                                     int face)
{
    long double a[3], p[3], q[3], xa, g;
    cube_face_axes(F, face, a, p, q);
    xa = ld_dot(x, a);
    g = fmaxl(view->near_plane - (xa + r), (xa - r) - (long double)view->far_plane);
    g = fmaxl(g, (fabsl(ld_dot(x, p)) - xa) / sqrtl(2.0L) - r);
    return fmaxl(g, (fabsl(ld_dot(x, q)) - xa) / sqrtl(2.0L) - r);
}

static expectation expect(const mlod_view *view, const frame *F, const float *sphere, const float *cone)
{
    expectation ex;
    long double x[3], r = sphere[3], d, xu, xv, xw, g = -INFINITY, m, gb = -INFINITY, W = view->width, H = view->height;
    long double ty = tanl(view->fov_y / 2.0L), tx = ty * W / H;
    int k, backface = cone && (view->flags & MLOD_VIEW_CULL_BACKFACES) && cone[3] < EXACT_PI;
    for (k = 0; k < 3; k++) x[k] = (long double)sphere[k] - F->e[k];
    d = sqrtl(ld_dot(x, x));
    xu = ld_dot(x, F->u);
    xv = ld_dot(x, F->v);
    xw = ld_dot(x, F->w);
    m = 1e-7L * (d + r);
    switch (view->kind) {
    case MLOD_VIEW_PERSPECTIVE:
        m += 1e-7L * (view->near_plane + (isfinite(view->far_plane) ? view->far_plane : 0));
        g = fmaxl(view->near_plane - (xw + r), (xw - r) - (long double)view->far_plane);
        g = fmaxl(g, (fabsl(xu) - tx * xw) / sqrtl(1 + tx * tx) - r);
        g = fmaxl(g, (fabsl(xv) - ty * xw) / sqrtl(1 + ty * ty) - r);
        break;
    case MLOD_VIEW_PARABOLOID: g = -(xw + r); break;
    case MLOD_VIEW_DUAL_PARABOLOID: break;
    case MLOD_VIEW_CUBE:
        /* culled when every face culls it: g is the least of the faces' */
        m += 1e-7L * (view->near_plane + (isfinite(view->far_plane) ? view->far_plane : 0));
        g = INFINITY;
        for (k = 0; k < 6; k++) g = fminl(g, cube_face_outside(view, F, x, r, k));
        break;
    default:
        m += 1e-7L * (fabsl(view->near_plane) + (isfinite(view->far_plane) ? fabsl(view->far_plane) : 0) +
                      view->half_width + view->half_height);
        g = fmaxl(fabsl(xu) - r - view->half_width, fabsl(xv) - r - view->half_height);
        g = fmaxl(g, fmaxl(view->near_plane - (xw + r), (xw - r) - (long double)view->far_plane));
        break;
    }
    if (backface) {
        long double axis_to_eye;
        float to_eye[3];
        if (view->kind == MLOD_VIEW_ORTHOGRAPHIC) {
            for (k = 0; k < 3; k++) to_eye[k] = (float)-F->w[k];
            axis_to_eye = exact_angle(cone, to_eye);
            gb = axis_to_eye - (EXACT_PI / 2 + cone[3]);
        } else if (d > r * (1 + 1e-6L)) {
            long double a0 = -x[0], a1 = -x[1], a2 = -x[2];
            long double c0 = cone[1] * a2 - cone[2] * a1, c1 = cone[2] * a0 - cone[0] * a2, c2 = cone[0] * a1 - cone[1] * a0;
            axis_to_eye = atan2l(sqrtl(c0 * c0 + c1 * c1 + c2 * c2), cone[0] * a0 + cone[1] * a1 + cone[2] * a2);
            gb = axis_to_eye - (EXACT_PI / 2 + cone[3] + asinl(r / d));
        }
        (void)to_eye;
    }
    ex.cull = (g > m || gb > 1e-7L) ? 1 : (g < -m && (gb < -1e-7L || !backface || gb == -INFINITY)) ? -1 : 0;
    if (backface && gb == -INFINITY && view->kind != MLOD_VIEW_ORTHOGRAPHIC && fabsl(d - r) <= 1e-6L * r && ex.cull == -1)
        ex.cull = 0;
    ex.value_ok = 1;
    ex.value = 0;
    if (d <= r * (1 - 1e-7L) && view->kind != MLOD_VIEW_ORTHOGRAPHIC) {
        ex.value = INFINITY;
        return ex;
    }
    if (fabsl(d - r) <= 1e-7L * r && view->kind != MLOD_VIEW_ORTHOGRAPHIC) {
        ex.value_ok = 0;
        return ex;
    }
    switch (view->kind) {
    case MLOD_VIEW_PERSPECTIVE: {
        long double f = (H / 2) / ty, den = xw * xw - r * r;
        if (xw <= r * (1 - 1e-9L)) ex.value = INFINITY;
        else if (xw > r && den > 1e-3L * xw * xw) ex.value = f * 2 * r * sqrtl(d * d - r * r) / den;
        else ex.value_ok = 0;
        break;
    }
    case MLOD_VIEW_PARABOLOID: {
        long double s = (W > H ? W : H) / 2, den = xw + sqrtl(d * d - r * r);
        if (den < -1e-9L * d) ex.value = INFINITY;
        else if (den > 1e-3L * d) ex.value = s * 2 * r / den;
        else ex.value_ok = 0;
        break;
    }
    case MLOD_VIEW_DUAL_PARABOLOID: {
        long double s = (W / 2 > H ? W / 2 : H) / 2, q = sqrtl(d * d - r * r), best = 0;
        int half;
        if (fabsl(fabsl(xw) - r) <= 1e-7L * d) {
            ex.value_ok = 0;
            break;
        }
        for (half = 0; half < 2; half++) {
            long double sw = half ? -xw : xw, den = sw + q;
            if (!(sw + r > 0)) continue; /* the sphere does not reach this half */
            if (den < -1e-9L * d) best = INFINITY;
            else if (den > 1e-3L * d) best = fmaxl(best, s * 2 * r / den);
            else ex.value_ok = 0;
        }
        ex.value = best;
        break;
    }
    case MLOD_VIEW_CUBE: {
        /* the largest over the faces that reach the sphere of the face's
           perspective diameter, f = s/2 (90 degrees); a face too close to
           its culling boundary to tell leaves the value unknown unless it
           cannot change the maximum */
        long double best = 0, unsure = 0;
        int face;
        for (face = 0; face < 6; face++) {
            long double a[3], p[3], q[3], xa, den, diam, gf = cube_face_outside(view, F, x, r, face);
            int ok = 1;
            if (gf > m) continue;
            cube_face_axes(F, face, a, p, q);
            xa = ld_dot(x, a);
            den = xa * xa - r * r;
            if (xa <= r * (1 - 1e-9L)) diam = INFINITY;
            else if (xa > r && den > 1e-3L * xa * xa) diam = (H / 4) * 2 * r * sqrtl(d * d - r * r) / den;
            else ok = 0, diam = INFINITY;
            if (gf < -m && ok) best = fmaxl(best, diam);
            else unsure = fmaxl(unsure, diam);
        }
        if (unsure > best * (1 - 1e-6L)) ex.value_ok = 0;
        ex.value = best;
        break;
    }
    default: ex.value = 2 * r * fmaxl(W / (2.0L * view->half_width), H / (2.0L * view->half_height)); break;
    }
    return ex;
}

/* A random view of random kind near a sphere, a third of them culled-ish. */
static mlod_view view_near_sphere(uint64_t *rng, const float *sphere, int kind)
{
    mlod_view v = tu_view((mlod_view_kind)kind);
    double dir[3], eye[3], target[3], r = sphere[3], dist = r * (scene_rng_double(rng) < 0.05 ? 0.5 : 1.05 * pow(60.0, scene_rng_double(rng))), perp[3], a;
    int k;
    tu_random_unit(rng, dir);
    for (k = 0; k < 3; k++) eye[k] = sphere[k] + dist * dir[k];
    tu_random_perp(rng, dir, perp);
    a = scene_rng_double(rng) * (scene_rng_double(rng) < 0.6 ? 0.8 : 3.0);
    for (k = 0; k < 3; k++) target[k] = eye[k] - cos(a) * dir[k] + sin(a) * perp[k];
    tu_look(rng, &v, eye, target);
    v.width = 1 + (uint32_t)(scene_rng_double(rng) * 256);
    v.height = 1 + (uint32_t)(scene_rng_double(rng) * 256);
    v.fov_y = (float)(0.2 + 2.7 * scene_rng_double(rng));
    v.near_plane = (float)(dist * (0.01 + 0.8 * scene_rng_double(rng)));
    v.far_plane = scene_rng_double(rng) < 0.5 ? INFINITY : (float)(dist * (0.5 + 2 * scene_rng_double(rng)));
    if (v.far_plane <= v.near_plane) v.far_plane = v.near_plane * 2;
    if (kind == MLOD_VIEW_CUBE) { /* 3s x 2s, s = 1 .. 128, from the width drawn */
        v.height = 2 * (1 + (v.width - 1) / 2);
        v.width = v.height / 2 * 3;
    }
    if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
        double w[3] = {v.forward[0], v.forward[1], v.forward[2]}, z = (scene_rng_double(rng) - 0.3) * 3 * r;
        v.half_width = (float)(r * (0.3 + 3 * scene_rng_double(rng)));
        v.half_height = (float)(r * (0.3 + 3 * scene_rng_double(rng)));
        tu_normalize3(w);
        for (k = 0; k < 3; k++)
            v.position[k] = (float)(sphere[k] - z * w[k] + (scene_rng_double(rng) - 0.5) * 3 * (v.half_width + r) * perp[k]);
        v.near_plane = (float)(-r * 2 * scene_rng_double(rng));
        v.far_plane = scene_rng_double(rng) < 0.3 ? INFINITY : (float)(v.near_plane + r * 4 * scene_rng_double(rng) + 1e-3 * r);
    }
    if (scene_rng_double(rng) < 0.5) v.flags = MLOD_VIEW_CULL_BACKFACES;
    return v;
}

#define NSIL 256
#define NSURF 128

/* Sampled points of a sphere: NSIL on the silhouette the view sees, NSURF
   uniform on the surface. */
static void sample_sphere(uint64_t *rng, const mlod_view *view, const frame *F, const float *sphere, long double (*pts)[3])
{
    long double C[3] = {sphere[0], sphere[1], sphere[2]}, r = sphere[3], x[3], d, a[3], b[3], centre[3], rho;
    int i, k;
    for (k = 0; k < 3; k++) x[k] = C[k] - F->e[k];
    d = sqrtl(ld_dot(x, x));
    if (view->kind == MLOD_VIEW_ORTHOGRAPHIC || d <= r) {
        for (k = 0; k < 3; k++) {
            a[k] = F->u[k];
            b[k] = F->v[k];
            centre[k] = C[k];
        }
        rho = r;
    } else {
        double xd[3] = {(double)(x[0] / d), (double)(x[1] / d), (double)(x[2] / d)}, p[3], q[3];
        tu_random_perp(rng, xd, p);
        tu_cross3(q, xd, p);
        for (k = 0; k < 3; k++) {
            a[k] = p[k];
            b[k] = q[k];
            centre[k] = C[k] - (r * r / d) * (x[k] / d);
        }
        rho = r * sqrtl(1 - (r / d) * (r / d));
    }
    for (i = 0; i < NSIL; i++) {
        long double phi = 2 * EXACT_PI * i / NSIL;
        for (k = 0; k < 3; k++) pts[i][k] = centre[k] + rho * (cosl(phi) * a[k] + sinl(phi) * b[k]);
    }
    for (i = 0; i < NSURF; i++) {
        double u[3];
        tu_random_unit(rng, u);
        for (k = 0; k < 3; k++) pts[NSIL + i][k] = C[k] + r * u[k];
    }
}

/* Largest distance between two of the n points (double is plenty here). */
static long double max_pairwise(long double (*px)[2], int n)
{
    static double x[1024], y[1024];
    double best = 0;
    int i, j;
    for (i = 0; i < n; i++) {
        x[i] = (double)px[i][0];
        y[i] = (double)px[i][1];
    }
    for (i = 0; i < n; i++)
        for (j = i + 1; j < n; j++) {
            double dx = x[i] - x[j], dy = y[i] - y[j], q = dx * dx + dy * dy;
            if (q > best) best = q;
        }
    return sqrtl(best);
}

static void test_criterion_reference(void)
{
    mlod_tree *trees[2];
    scene_mesh s;
    uint64_t rng = 99;
    uint32_t cases = 0, bad_lower = 0, bad_upper = 0, bad_cull_sample = 0, tight = 0, culled = 0, ti, i;
    uint32_t formula_cases = 0, bad_value = 0, bad_cull = 0, bad_nocull = 0, bad_nan = 0, compared = 0;
    uint32_t cube_tight = 0, cube_culled = 0, cube_compared = 0, cube_compared_multi = 0;
    char first_lower[256] = "", first_upper[256] = "", first_cull[256] = "", first_value[300] = "", first_cull2[256] = "",
         first_nocull[256] = "";
    static long double pts[NSIL + NSURF][3], px[6][NSIL + NSURF][2];
    scene_uv_sphere(&s, 1.0f, 10, 20);
    trees[0] = random_points_tree(600, 3, 1e-3, 0.4);
    trees[1] = tu_build(&s, 2000, 4, MLOD_ATTR_CONE);
    CHECK(trees[0] && trees[1], "criterion reference: builds");
    if (!trees[0] || !trees[1]) return;
    for (ti = 0; ti < 2; ti++) {
        const mlod_tree *t = trees[ti];
        for (i = 0; i < 750; i++) {
            uint32_t node = (uint32_t)(scene_rng_double(&rng) * t->node_count);
            const float *sp = t->spheres + 4 * node, *cone = t->cones + 4 * node;
            int kind = (int)(i % 5), half, halves, n[6] = {0, 0, 0, 0, 0, 0}, j, cube_inside = 0;
            mlod_view v = view_near_sphere(&rng, sp, kind);
            frame F;
            double c = mlod_criterion(t, node, &v);
            long double maxd = 0, xw, d, x[3];
            char desc[160];
            if (mlod_view_check(&v, NULL) != MLOD_OK) continue;
            view_frame(&v, &F);
            for (j = 0; j < 3; j++) x[j] = sp[j] - F.e[j];
            d = sqrtl(ld_dot(x, x));
            xw = ld_dot(x, F.w);
            snprintf(desc, sizeof desc, "tree %u node %u kind %d flags %u: r %.6g d %.6g x.w %.6g, c %.9g", ti, node, kind,
                     v.flags, sp[3], (double)d, (double)xw, c);
            cases++;
            sample_sphere(&rng, &v, &F, sp, pts);
            halves = kind == MLOD_VIEW_DUAL_PARABOLOID ? 2 : kind == MLOD_VIEW_CUBE ? 6 : 1;
            if (kind == MLOD_VIEW_CUBE) {
                /* the sphere well inside one face's frustum: c is that face's
                   diameter, which the silhouette's samples there span */
                long double a[3], p[3], q[3], xa;
                int face;
                for (face = 0; face < 6; face++) {
                    cube_face_axes(&F, face, a, p, q);
                    xa = ld_dot(x, a);
                    if ((xa - fabsl(ld_dot(x, p))) / sqrtl(2.0L) > 1.01L * sp[3] &&
                        (xa - fabsl(ld_dot(x, q))) / sqrtl(2.0L) > 1.01L * sp[3] && xa > 1.5L * sp[3] &&
                        xa - sp[3] > 1.01L * v.near_plane && xa + sp[3] < 0.99L * v.far_plane)
                        cube_inside = 1;
                }
            }
            for (half = 0; half < halves; half++) {
                n[half] = 0;
                for (j = 0; j < NSIL + NSURF; j++)
                    if (project(&v, &F, pts[j], half, px[half][n[half]])) n[half]++;
                maxd = fmaxl(maxd, max_pairwise(px[half], n[half]));
            }
            if (c == 0) {
                /* culled: no sampled point is inside the volume, unless every
                   normal of the cone at it faces away */
                culled++;
                cube_culled += kind == MLOD_VIEW_CUBE;
                for (j = 0; j < NSIL + NSURF; j++) {
                    long double m = 1e-6L * (d + sp[3]);
                    int inside = inside_volume(&v, &F, pts[j], m), faces = 0, q;
                    if (!inside) continue;
                    if (!(v.flags & MLOD_VIEW_CULL_BACKFACES) || cone[3] >= EXACT_PI) faces = 1;
                    for (q = 0; q < 16 && !faces; q++) {
                        double nn[3], to_eye[3], perp[3], ax[3] = {cone[0], cone[1], cone[2]}, ang = cone[3] * (q ? scene_rng_double(&rng) : 0);
                        int k;
                        tu_normalize3(ax);
                        tu_random_perp(&rng, ax, perp);
                        for (k = 0; k < 3; k++) {
                            nn[k] = cos(ang) * ax[k] + sin(ang) * perp[k];
                            to_eye[k] = v.kind == MLOD_VIEW_ORTHOGRAPHIC ? -(double)F.w[k] : (double)(F.e[k] - pts[j][k]);
                        }
                        if (tu_dot3(nn, to_eye) > 1e-6 * (double)(d + sp[3])) faces = 1;
                    }
                    if (faces) {
                        if (!bad_cull_sample++) snprintf(first_cull, sizeof first_cull, "%s: point %d inside", desc, j);
                        break;
                    }
                }
            } else if (isfinite(c)) {
                if (!(c >= maxd * (1 - 1e-4L))) {
                    if (!bad_lower++)
                        snprintf(first_lower, sizeof first_lower, "%s < sampled diameter %.9Lg", desc, maxd);
                }
                if (sp[3] < 0.5 * d && ((kind == MLOD_VIEW_PERSPECTIVE && xw > 1.5L * sp[3]) ||
                                        (kind == MLOD_VIEW_PARABOLOID && xw > sp[3] * 1.01L) ||
                                        (kind == MLOD_VIEW_DUAL_PARABOLOID && fabsl(xw) > sp[3] * 1.01L) ||
                                        kind == MLOD_VIEW_ORTHOGRAPHIC || cube_inside)) {
                    tight++;
                    cube_tight += kind == MLOD_VIEW_CUBE;
                    if (!(c <= 1.02L * maxd) && !bad_upper++)
                        snprintf(first_upper, sizeof first_upper, "%s > 1.02 x sampled diameter %.9Lg", desc, maxd);
                }
            }
        }
        /* the documented formulas and culling rules, many more cases */
        for (i = 0; i < 37500; i++) {
            uint32_t node = (uint32_t)(scene_rng_double(&rng) * t->node_count);
            const float *sp = t->spheres + 4 * node, *cone = t->cones + 4 * node;
            mlod_view v = view_near_sphere(&rng, sp, (int)(i % 5));
            frame F;
            expectation ex;
            double c;
            if (mlod_view_check(&v, NULL) != MLOD_OK) continue;
            view_frame(&v, &F);
            ex = expect(&v, &F, sp, cone);
            c = mlod_criterion(t, node, &v);
            formula_cases++;
            if (isnan(c)) {
                bad_nan++;
                continue;
            }
            if (ex.cull == 1 && c != 0) {
                if (!bad_cull++)
                    snprintf(first_cull2, sizeof first_cull2, "tree %u node %u kind %d flags %u: wholly outside, c %.9g", ti,
                             node, (int)v.kind, v.flags, c);
            } else if (ex.cull == -1) {
                if (c == 0) {
                    if (!bad_nocull++)
                        snprintf(first_nocull, sizeof first_nocull, "tree %u node %u kind %d flags %u: visible, c = 0", ti,
                                 node, (int)v.kind, v.flags);
                } else if (ex.value_ok) {
                    int ok = isinf(ex.value) ? isinf(c) : fabsl(c - ex.value) <= 1e-5L * ex.value;
                    compared++;
                    if (v.kind == MLOD_VIEW_CUBE) {
                        long double xc[3];
                        int face, reached = 0;
                        for (face = 0; face < 3; face++) xc[face] = (long double)sp[face] - F.e[face];
                        for (face = 0; face < 6; face++) reached += cube_face_outside(&v, &F, xc, sp[3], face) < 0;
                        cube_compared++;
                        cube_compared_multi += reached > 1;
                    }
                    if (!ok && !bad_value++)
                        snprintf(first_value, sizeof first_value,
                                 "tree %u node %u kind %d (W %u H %u fov %.6g hw %.6g hh %.6g): c %.12g, documented %.12Lg", ti,
                                 node, (int)v.kind, v.width, v.height, v.fov_y, v.half_width, v.half_height, c, ex.value);
                }
            }
        }
    }
    CHECK(bad_lower == 0, "criterion: %u of %u cases below the diameter of the sampled image; first: %s", bad_lower, cases,
          first_lower);
    CHECK(bad_upper == 0, "criterion: %u of %u small spheres in front above 1.02 x the sampled image; first: %s", bad_upper,
          tight, first_upper);
    CHECK(bad_cull_sample == 0, "criterion: %u of %u culled spheres have a sampled point inside the view; first: %s",
          bad_cull_sample, culled, first_cull);
    CHECK(tight > 300 && culled > 100, "criterion: only %u tight and %u culled cases", tight, culled);
    CHECK(cube_tight > 40 && cube_culled > 20 && cube_compared > 5000 && cube_compared_multi > 1000,
          "criterion: only %u tight and %u culled sampled cube map cases, %u formula values compared (%u over several "
          "faces)",
          cube_tight, cube_culled, cube_compared, cube_compared_multi);
    CHECK(bad_nan == 0, "criterion: %u NaN for valid views", bad_nan);
    CHECK(bad_cull == 0, "criterion: %u of %u spheres wholly outside (or back-facing) not culled; first: %s", bad_cull,
          formula_cases, first_cull2);
    CHECK(bad_nocull == 0, "criterion: %u of %u visible spheres culled; first: %s", bad_nocull, formula_cases, first_nocull);
    CHECK(bad_value == 0, "criterion: %u of %u values differ from the documented formula by > 1e-5; first: %s", bad_value,
          compared, first_value);
    printf("  criterion: %u sampled cases (%u tight, %u culled), %u formula cases (%u values compared; cube maps: %u "
           "tight, %u culled, %u compared, %u over several faces)\n",
           cases, tight, culled, formula_cases, compared, cube_tight, cube_culled, cube_compared, cube_compared_multi);
    mlod_tree_destroy(trees[0]);
    mlod_tree_destroy(trees[1]);
    scene_free(&s);
}

/* ------------------------------------------------------- float filter */

/* The float filter against the definition for one node-view at epsilon:
   the scalar filter (mlod__fast_status), where it decides, and the vector
   path (mlod__classify_children, on the node's parent), always, must give
   the exact path's status; so must the vector path told that the parent
   lies inside every plane, where the vector path proves it (the plane
   tests left out below it; fast_known counts those).  0 when they do (or
   the view has no filter), 1 scalar, 2 vector, 3 vector below a parent
   inside otherwise; *decided counts the scalar decisions. */
static uint32_t fast_known;
static int fast_disagrees(const mlod_tree *t, uint32_t node, const mlod_view *v, double eps, uint32_t *decided)
{
    mlod__pview pv;
    /* mlod__classify_children's buffers: a vector's lanes of room past the batch */
    uint8_t exact, fast, kids[2 * (MLOD__BATCH + MLOD__BATCH_PAD)], inside[2 * (MLOD__BATCH + MLOD__BATCH_PAD)];
    uint8_t known[5 + MLOD__BATCH_PAD] = {1, 1, 1, 1, 1}, parent_status;
    if (mlod__view_prepare(v, &pv, NULL) != MLOD_OK) return 0;
    mlod__fast_prepare(&pv, eps);
    if (!pv.fast.ok) return 0;
    exact = mlod__classify_exact(&pv, t, node, eps);
    fast = mlod__fast_status(&pv.fast, t->spheres + 4 * (size_t)node, mlod__cone_of(t, node));
    if (fast != MLOD__UNSURE) {
        ++*decided;
        if ((fast == MLOD_STATUS_COARSE ? mlod__invalid_status(t, node) : fast) != exact) return 1;
    }
    if (node > 0) {
        /* the parent alone (a partial vector), and five times over (a
           whole vector of pairs where the build has them, then a partial
           one): every copy as the exact path */
        uint32_t parents[5 + MLOD__BATCH_PAD], i, side = (node - 1) & 1u;
        for (i = 0; i < 5; i++) parents[i] = (node - 1) / 2;
        mlod__classify_children(&pv, t, parents, 1, eps, kids, NULL, NULL);
        if (kids[side] != exact) return 2;
        mlod__classify_children(&pv, t, parents, 5, eps, kids, NULL, NULL);
        for (i = 0; i < 5; i++)
            if (kids[2 * i + side] != exact) return 2;
        mlod__classify_known(&pv, t, parents, 1, eps, &parent_status, NULL, inside);
        if (inside[0]) {
            fast_known++;
            mlod__classify_children(&pv, t, parents, 1, eps, kids, known, inside);
            if (kids[side] != exact || !inside[side]) return 3;
            mlod__classify_children(&pv, t, parents, 5, eps, kids, known, inside);
            for (i = 0; i < 5; i++)
                if (kids[2 * i + side] != exact || !inside[2 * i + side]) return 3;
        }
    }
    return 0;
}

/* fast_disagrees at epsilon on the node-view's own criterion c and one
   double either side (where a filter without its margins errs), when c
   is finite and positive; the number of disagreements. */
static uint32_t fast_disagrees_at(const mlod_tree *t, uint32_t node, const mlod_view *v, double c, uint32_t *decided)
{
    uint32_t bad = 0;
    if (!(c > 0.0 && c < INFINITY)) return 0;
    bad += fast_disagrees(t, node, v, c, decided) != 0;
    bad += fast_disagrees(t, node, v, nextafter(c, 0.0), decided) != 0;
    bad += fast_disagrees(t, node, v, nextafter(c, INFINITY), decided) != 0;
    return bad;
}

/* The filter decides almost every node-view of ordinary views (else it
   buys nothing) and agrees with the exact path on every one it decides,
   at random epsilons and at epsilons on the criterion itself, for every
   view kind, with and without back-face culling, on trees with and
   without cones; the vector path (MLOD__VLANES lanes here, the scalar
   filter where the build has none) agrees on all. */
static void test_fast_filter(void)
{
    mlod_tree *trees[2];
    scene_mesh s;
    uint64_t rng = 0xf10a7f17e5ull;
    double c[3], R;
    uint32_t ti, kind, i, n, tried = 0, decided = 0, bad_random = 0, bad_on = 0, on_tried = 0, on_decided = 0;
    memset(&s, 0, sizeof s);
    scene_torus(&s, 1.0f, 0.35f, 48, 24);
    tu_bounds(&s, c, &R);
    trees[0] = tu_build(&s, 6000, 5, MLOD_ATTR_CONE);
    trees[1] = tu_build(&s, 6000, 6, 0);
    CHECK(trees[0] && trees[1], "float filter: builds");
    if (!trees[0] || !trees[1]) return;
    for (ti = 0; ti < 2; ti++)
        for (kind = 0; kind < 5; kind++)
            for (i = 0; i < 16; i++) {
                const mlod_tree *t = trees[ti];
                mlod_view v = tu_random_view(&rng, (mlod_view_kind)kind, c, R);
                double eps = 0.25 * pow(64.0, scene_rng_double(&rng));
                v.flags = i % 2 ? MLOD_VIEW_CULL_BACKFACES : 0;
                if (mlod_view_check(&v, NULL) != MLOD_OK) continue;
                for (n = i % 3; n < t->node_count; n += 3) {
                    tried++;
                    bad_random += fast_disagrees(t, n, &v, eps, &decided) != 0;
                    if (n % 29 == 0) {
                        on_tried += 3;
                        bad_on += fast_disagrees_at(t, n, &v, mlod_criterion(t, n, &v), &on_decided);
                    }
                }
            }
    CHECK(bad_random == 0, "float filter: %u of %u node-views at random epsilons differ from the exact path", bad_random,
          tried);
    CHECK(bad_on == 0, "float filter: %u of %u node-views at epsilon on their criterion differ from the exact path",
          bad_on, on_tried);
    CHECK(decided >= tried - tried / 200, "float filter: decides only %u of %u node-views of random views", decided,
          tried);
    CHECK(on_tried > 10000 && on_decided < on_tried / 100,
          "float filter: decided %u of %u node-views at epsilon on their criterion (within its margin: expected none)",
          on_decided, on_tried);
#ifdef MLOD__VLANES
    CHECK(fast_known > 1000, "float filter: only %u node-views below a parent proved inside every plane", fast_known);
#endif
    printf("  float filter: %u node-views, %.3f %% left to the exact path; %u at epsilon on their criterion, %u "
           "decided; %u below a parent proved inside every plane\n", tried, 100.0 * (tried - decided) / tried,
           on_tried, on_decided, fast_known);
    mlod_tree_destroy(trees[0]);
    mlod_tree_destroy(trees[1]);
    scene_free(&s);
}

/* Where the float filter's bounds are weakest: a paraboloid's x.w + t and
   a perspective view's x.w - r down to 1e-7 of |x| (an eye beside a large
   sphere, the sphere's silhouette grazing the paraboloid's rim or the
   eye's plane), at epsilon on the criterion, one double either side and
   1/16 to 1/2048 of it either side:
   the filter must leave these to the exact path or decide them as it
   would (its guards keep these denominators above |x| / 16). */
static void test_fast_conditioning(void)
{
    static const double deltas[] = {0.3, 0.1, 0.06, 0.03, 1e-2, 1e-3, 1e-4, 1e-5, 1e-7};
    float positions[6] = {0, 0, 0, 1, 0, 0}, radii[2] = {1, 1};
    uint64_t rng = 0xc0d1710edull;
    mlod_points pts;
    mlod_build_desc desc;
    mlod_tree *t = NULL;
    uint32_t i, cases = 0, bad = 0, decided = 0, guarded = 0;
    memset(&pts, 0, sizeof pts);
    pts.positions = positions;
    pts.radii = radii;
    pts.count = 2;
    memset(&desc, 0, sizeof desc);
    CHECK(mlod_build_points(&pts, &desc, &t, NULL) == MLOD_OK && t && t->node_count == 3, "conditioning: a 3-node tree");
    if (!t || t->node_count != 3) return;
    for (i = 0; i < 20000; i++) {
        int persp = i % 2, k;
        double D = pow(10.0, 4.0 * scene_rng_double(&rng) - 2.0), delta = deltas[(i / 2) % 9], w[3], u[3], x[3];
        double r = persp ? D * (0.05 + 0.9 * scene_rng_double(&rng)) : D * (0.71 + 0.15 * scene_rng_double(&rng));
        double xw = persp ? r + delta * D : -sqrt(D * D - r * r) + delta * D, side;
        mlod_view v = tu_view(persp ? MLOD_VIEW_PERSPECTIVE : MLOD_VIEW_PARABOLOID);
        if (!(fabs(xw) < D)) continue;
        side = sqrt(D * D - xw * xw);
        tu_random_unit(&rng, w);
        tu_random_perp(&rng, w, u);
        for (k = 0; k < 3; k++) {
            x[k] = xw * w[k] + side * u[k];
            v.position[k] = (float)(10.0 * scene_rng_double(&rng) - 5.0);
            v.forward[k] = (float)w[k];
            v.up[k] = (float)u[k];
        }
        v.width = v.height = 8 + (uint32_t)(scene_rng_double(&rng) * 120);
        v.fov_y = 3.0f;
        v.near_plane = (float)(1e-6 * D);
        v.far_plane = INFINITY;
        for (k = 0; k < 3; k++) t->spheres[4 + k] = t->spheres[8 + k] = (float)(v.position[k] + x[k]);
        t->spheres[7] = t->spheres[11] = (float)r;
        cases++;
        if (mlod_view_check(&v, NULL) != MLOD_OK) continue;
        {
            mlod__pview pv;
            float fx[3], d2;
            static const double factors[] = {1 - 1.0 / 16, 1 - 1.0 / 256, 1 - 1.0 / 2048, 1 + 1.0 / 2048, 1 + 1.0 / 256,
                                             1 + 1.0 / 16};
            double c = mlod_criterion(t, 1, &v);
            int f;
            bad += fast_disagrees_at(t, 1, &v, c, &decided);
            for (f = 0; f < 6 && c > 0.0 && c < INFINITY; f++) bad += fast_disagrees(t, 1, &v, c * factors[f], &decided) != 0;
            /* how many fail the guard: those the bounds could not cover */
            mlod__view_prepare(&v, &pv, NULL);
            for (k = 0; k < 3; k++) fx[k] = (float)((double)t->spheres[4 + k] - pv.f.eye[k]);
            d2 = fx[0] * fx[0] + fx[1] * fx[1] + fx[2] * fx[2];
            guarded += 256.0 * (persp ? delta * delta : delta * delta) * D * D < d2;
        }
    }
    CHECK(bad == 0, "conditioning: %u of %u node-views near a vanishing denominator differ from the exact path", bad,
          9 * cases);
    CHECK(decided > cases && guarded > cases / 4, "conditioning: too few decided (%u) or guarded (%u) of %u", decided,
          guarded, 9 * cases);
    printf("  float filter near vanishing denominators: %u node-views, %u decided\n", 9 * cases, decided);
    mlod_tree_destroy(t);
}

/* ----------------------------------------------- back faces, up close */

/* Back-face culling a hair either side of its boundary, for paraboloid
   and orthographic views (the criterion's two forms of the test): where
   long double arithmetic on the very inputs the library sees (the float
   sphere and cone, the eye and forward of mlod_view_frame_of) is clear
   of the boundary by 1e-13 of the scale, the criterion decides the same.
   The offsets straddle the margin (2^-30 of the scale) inside which the
   criterion stops trusting its polynomial bounds on sin and cos and sums
   their series. */
static void test_backface_boundary(void)
{
    static const double offsets[] = {1e-3, 1e-5, 1e-7, 1e-8, 3e-9, 1.5e-9, 6e-10, 2e-10, 1e-11};
    static const double angles[] = {0.0, 1e-6, 1e-4, 1e-2, 0.1, 0.5, 1.0, 1.4, 1.5706};
    static const double radii[] = {1e-7, 1e-5, 1e-3, 0.05, 0.4}; /* > 0: c = 0 means culled */
    uint64_t rng = 0xbac0face5eedull;
    float position[3] = {0, 0, 0}, normal[3] = {0, 0, 1}, radius = 1;
    mlod_points pts;
    mlod_build_desc desc;
    mlod_tree *t = NULL;
    uint32_t i, cases = 0, decided[2] = {0, 0}, near[2] = {0, 0}, wrong = 0, fast_bad = 0, fast_decided = 0;
    char first[256] = "";
    memset(&pts, 0, sizeof pts);
    pts.positions = position;
    pts.normals = normal;
    pts.radii = &radius;
    pts.count = 1;
    memset(&desc, 0, sizeof desc);
    desc.attributes = MLOD_ATTR_CONE;
    CHECK(mlod_build_points(&pts, &desc, &t, NULL) == MLOD_OK && t && t->cones, "back-face boundary: a one-node tree");
    if (!t || !t->cones) return;
    for (i = 0; i < 20000; i++) {
        int ortho = i % 3 == 0, k, lib_culled, exact_culled;
        double ax[3], perp[3], dir[3], centre[3], d = 1.0 + 2.0 * scene_rng_double(&rng), beta, delta, c;
        double r = d * radii[(i / 3) % 5], a = angles[(i / 15) % 9] * (1.0 + 0.01 * scene_rng_double(&rng));
        long double x[3], lr, la, len, away, tt, ss, m1, m2, scale, tol;
        mlod_view v;
        mlod_view_frame f;
        delta = offsets[(i / 135) % 9] * (i % 2 ? 1.0 : -1.0) * (1.0 + 0.1 * scene_rng_double(&rng));
        tu_random_unit(&rng, ax);
        tu_random_perp(&rng, ax, perp);
        for (k = 0; k < 3; k++) {
            centre[k] = 2.0 * scene_rng_double(&rng) - 1.0;
            t->spheres[k] = (float)centre[k];
            t->cones[k] = (float)ax[k];
        }
        t->spheres[3] = (float)r;
        t->cones[3] = (float)a;
        beta = TU_PI / 2 + a + (ortho ? 0.0 : asin(r / d)) + delta;
        for (k = 0; k < 3; k++) dir[k] = cos(beta) * ax[k] + sin(beta) * perp[k]; /* centre to eye */
        v = tu_view(ortho ? MLOD_VIEW_ORTHOGRAPHIC : MLOD_VIEW_PARABOLOID);
        v.flags = MLOD_VIEW_CULL_BACKFACES;
        tu_random_perp(&rng, dir, perp);
        for (k = 0; k < 3; k++) {
            v.position[k] = (float)(centre[k] + (ortho ? 2.0 * r + 1.0 : d) * dir[k]);
            v.forward[k] = (float)-dir[k];
            v.up[k] = (float)perp[k];
        }
        if (ortho) {
            v.half_width = v.half_height = (float)(2.0 * r + 1.0);
            v.near_plane = 0.0f;
            v.far_plane = (float)(4.0 * r + 4.0);
        }
        if (mlod_view_frame_of(&v, &f, NULL) != MLOD_OK) continue;
        /* exactly: culled when cos a t - sin a s > 0 and axis.(eye - centre) / |axis| < -(sin a t + cos a s) */
        for (k = 0; k < 3; k++) x[k] = (long double)t->spheres[k] - (long double)f.eye[k];
        lr = t->spheres[3];
        la = t->cones[3];
        len = sqrtl((long double)t->cones[0] * t->cones[0] + (long double)t->cones[1] * t->cones[1] +
                    (long double)t->cones[2] * t->cones[2]);
        if (ortho) {
            away = 0;
            for (k = 0; k < 3; k++) away -= (long double)t->cones[k] * (long double)f.subs[0].forward[k];
            tt = 1;
            ss = 0;
        } else {
            long double d2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
            if (!(d2 > lr * lr * (1 + 1e-9L))) continue;
            away = 0;
            for (k = 0; k < 3; k++) away -= (long double)t->cones[k] * x[k];
            tt = sqrtl(d2 - lr * lr);
            ss = lr;
        }
        m1 = cosl(la) * tt - sinl(la) * ss;
        m2 = -(sinl(la) * tt + cosl(la) * ss) - away / len;
        scale = tt + ss;
        tol = 1e-13L * scale;
        cases++;
        if (fabsl(m1) <= tol || fabsl(m2) <= tol || fabsl(away) <= tol) continue;
        exact_culled = la < EXACT_PI / 2 && away < 0 && m1 > 0 && m2 > 0;
        c = mlod_criterion(t, 0, &v);
        lib_culled = c == 0.0;
        fast_bad += fast_disagrees(t, 0, &v, 1.0, &fast_decided) != 0;
        decided[exact_culled]++;
        if (fabsl(m2) < 1e-8L * scale) near[exact_culled]++;
        if (lib_culled != exact_culled && !wrong++)
            snprintf(first, sizeof first, "%s, half-angle %.9g, r %.3g, d %.3g, offset %.3g: criterion %g, exactly %s",
                     ortho ? "orthographic" : "paraboloid", (double)la, (double)lr, d, delta, c,
                     exact_culled ? "culled" : "visible");
    }
    CHECK(wrong == 0, "back-face boundary: %u of %u decided cases differ from exact arithmetic; first: %s", wrong,
          decided[0] + decided[1], first);
    CHECK(decided[0] > 2000 && decided[1] > 2000 && near[0] > 200 && near[1] > 200,
          "back-face boundary: too few cases (%u visible, %u culled; %u and %u within 1e-8)", decided[0], decided[1],
          near[0], near[1]);
    CHECK(fast_bad == 0 && fast_decided > cases / 10 && fast_decided < cases - cases / 10,
          "back-face boundary: the float filter differs from the exact path %u times (it decided %u of %u)", fast_bad,
          fast_decided, cases);
    printf("  back-face boundary: %u cases, %u visible and %u culled decided (%u and %u within 1e-8 of the scale); "
           "the float filter decided %u\n",
           cases, decided[0], decided[1], near[0], near[1], fast_decided);
    mlod_tree_destroy(t);
}

/* ------------------------------------------------------- monotonicity */

static const double deltas[] = {-1e-3, -1e-6, -1e-7, 0.0, 1e-7, 1e-6, 1e-3};

static double pick_delta(uint64_t *rng) { return deltas[(int)(scene_rng_double(rng) * 7)]; }

/* A view adversarial to sphere s (and cone): type 1 eye near the sphere,
   2 perspective side plane tangent, 3 near/far plane tangent (perspective,
   orthographic or a cube map's face), 4 paraboloid plane tangent, 5
   orthographic box side tangent, 6 back-face boundary, 7 a cube map's
   edge between two faces tangent. */
static mlod_view adversarial_view(uint64_t *rng, int type, const float *s, const float *cone)
{
    double C[3] = {s[0], s[1], s[2]}, r = s[3], xh[3], p[3], q[3], e[3], w[3], up[3], d, b, a, delta = pick_delta(rng);
    int kind = (int)(scene_rng_double(rng) * 5), k, side = scene_rng_double(rng) < 0.5;
    mlod_view v = tu_view(MLOD_VIEW_PERSPECTIVE);
    tu_random_unit(rng, xh);
    tu_random_perp(rng, xh, p);
    tu_cross3(q, xh, p);
    d = r * (1.2 + 30 * scene_rng_double(rng));
    v.width = 1 + (uint32_t)(scene_rng_double(rng) * 200);
    v.height = 1 + (uint32_t)(scene_rng_double(rng) * 200);
    v.fov_y = (float)(0.2 + 2.7 * scene_rng_double(rng));
    v.near_plane = (float)(1e-3 * r);
    v.far_plane = INFINITY;
    for (k = 0; k < 3; k++) e[k] = C[k] - d * xh[k];
    switch (type) {
    case 1:
        v.kind = (mlod_view_kind)kind;
        for (k = 0; k < 3; k++) e[k] = C[k] - r * (1 + delta) * xh[k];
        tu_random_unit(rng, w);
        tu_random_perp(rng, w, up);
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            v.half_width = v.half_height = (float)(r * 2);
            v.near_plane = (float)(-3 * r);
            v.far_plane = (float)(3 * r);
        }
        break;
    case 2:
        b = asin(r / d);
        if (side) { /* top or bottom */
            a = v.fov_y / 2.0 + b * (1 + delta);
            for (k = 0; k < 3; k++) {
                w[k] = cos(a) * xh[k] + sin(a) * p[k];
                up[k] = -sin(a) * xh[k] + cos(a) * p[k];
            }
        } else { /* left or right */
            a = atan(tan(v.fov_y / 2.0) * v.width / v.height) + b * (1 + delta);
            for (k = 0; k < 3; k++) {
                w[k] = cos(a) * xh[k] + sin(a) * p[k];
                up[k] = q[k];
            }
        }
        break;
    case 3:
        for (k = 0; k < 3; k++) {
            w[k] = xh[k];
            up[k] = p[k];
        }
        a = scene_rng_double(rng);
        v.kind = a < 0.4 ? MLOD_VIEW_PERSPECTIVE : a < 0.8 ? MLOD_VIEW_ORTHOGRAPHIC : MLOD_VIEW_CUBE;
        if (v.kind == MLOD_VIEW_ORTHOGRAPHIC) {
            v.half_width = v.half_height = (float)(r * 2);
            v.near_plane = (float)(-10 * d);
        }
        if (side) v.near_plane = (float)(d + r * (1 + delta));
        else v.far_plane = (float)(d - r * (1 + delta));
        if (!(v.far_plane > v.near_plane)) v.near_plane = v.far_plane * 0.5f;
        break;
    case 4:
        v.kind = scene_rng_double(rng) < 0.5 ? MLOD_VIEW_PARABOLOID : MLOD_VIEW_DUAL_PARABOLOID;
        a = acos(fmax(-1.0, fmin(1.0, (side ? -1 : 1) * r * (1 + delta) / d)));
        for (k = 0; k < 3; k++) {
            w[k] = cos(a) * xh[k] + sin(a) * p[k];
            up[k] = -sin(a) * xh[k] + cos(a) * p[k];
        }
        break;
    case 5: {
        double hw = r * (0.5 + 2 * scene_rng_double(rng)), z = r * 3;
        v.kind = MLOD_VIEW_ORTHOGRAPHIC;
        v.half_width = (float)hw;
        v.half_height = (float)(r * (0.5 + 2 * scene_rng_double(rng)));
        v.near_plane = 0;
        v.far_plane = (float)(6 * r);
        for (k = 0; k < 3; k++) {
            w[k] = xh[k];
            up[k] = q[k];
        }
        /* right = w x up = xh x (xh x p) = -p: put the sphere just past +-hw along p */
        for (k = 0; k < 3; k++) e[k] = C[k] - z * w[k] + (side ? 1 : -1) * (hw + r * (1 + delta)) * p[k];
        break;
    }
    case 7: { /* the sphere r (1 + delta) from the plane between two cube faces, on either side */
        double x_axis[3], y_axis[3];
        v.kind = MLOD_VIEW_CUBE;
        b = asin(r / d);
        a = TU_PI / 4 + (side ? 1 : -1) * b * (1 + delta) + TU_PI / 2 * (int)(scene_rng_double(rng) * 4);
        for (k = 0; k < 3; k++) { /* xh = cos(a) X + sin(a) Y */
            x_axis[k] = cos(a) * xh[k] - sin(a) * p[k];
            y_axis[k] = sin(a) * xh[k] + cos(a) * p[k];
        }
        tu_cross3(w, y_axis, x_axis); /* forward = -Z = Y x X, so that right = forward x up = X */
        for (k = 0; k < 3; k++) up[k] = y_axis[k];
        break;
    }
    default: { /* back-face boundary */
        double ax[3] = {cone[0], cone[1], cone[2]}, beta, perp[3];
        v.kind = (mlod_view_kind)kind;
        v.flags = MLOD_VIEW_CULL_BACKFACES;
        tu_normalize3(ax);
        tu_random_perp(rng, ax, perp);
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            beta = TU_PI / 2 + cone[3] + delta;
            for (k = 0; k < 3; k++) w[k] = -(cos(beta) * ax[k] + sin(beta) * perp[k]);
            tu_random_perp(rng, w, up);
            for (k = 0; k < 3; k++) e[k] = C[k] - 2 * r * w[k];
            v.half_width = v.half_height = (float)(r * 2);
            v.near_plane = 0;
            v.far_plane = (float)(4 * r);
        } else {
            beta = TU_PI / 2 + cone[3] + asin(r / d) + delta;
            for (k = 0; k < 3; k++) {
                double dir = cos(beta) * ax[k] + sin(beta) * perp[k];
                e[k] = C[k] + d * dir;
                w[k] = -dir;
            }
            tu_random_perp(rng, w, up);
        }
        if (cone[3] >= TU_PI / 2) v.flags = 0;
        break;
    }
    }
    tu_set3f(v.position, e);
    tu_set3f(v.forward, w);
    tu_set3f(v.up, up);
    if (v.kind == MLOD_VIEW_CUBE) { /* 3s x 2s from the width drawn */
        v.height = 2 * (1 + (v.width - 1) / 2);
        v.width = v.height / 2 * 3;
    }
    if (scene_rng_double(rng) < 0.5) v.flags |= MLOD_VIEW_CULL_BACKFACES;
    return v;
}

static uint32_t monotone_pairs; /* (child, parent, view) triples checked, all trees */

static void check_monotone(const mlod_tree *t, const char *what, uint64_t seed, uint32_t pairs, const double *centre, double R)
{
    uint32_t bad[8] = {0}, count[8] = {0}, kinds[5] = {0}, nan_count = 0, skipped = 0, i, type;
    uint32_t fast_bad[8] = {0}, fast_decided = 0;
    char first[8][640];
    uint64_t rng = seed;
    if (t->node_count < 2) return;
    memset(first, 0, sizeof first);
    for (i = 0; i < pairs; i++) {
        uint32_t child = 1 + (uint32_t)(scene_rng_double(&rng) * (t->node_count - 1)), parent = (child - 1) / 2;
        int on_parent = scene_rng_double(&rng) < 0.3;
        const uint32_t target = on_parent ? parent : child;
        mlod_view v;
        double cc, cp;
        type = i % 8;
        if (type == 0) v = tu_random_view(&rng, (mlod_view_kind)(scene_rng_double(&rng) * 5), centre, R);
        else v = adversarial_view(&rng, (int)type, t->spheres + 4 * target, t->cones ? t->cones + 4 * target : NULL);
        if (type == 6 && !t->cones) v = tu_random_view(&rng, (mlod_view_kind)(scene_rng_double(&rng) * 5), centre, R);
        if (mlod_view_check(&v, NULL) != MLOD_OK) {
            skipped++;
            continue;
        }
        cc = mlod_criterion(t, child, &v);
        cp = mlod_criterion(t, parent, &v);
        fast_bad[type] += fast_disagrees_at(t, child, &v, cc, &fast_decided) + fast_disagrees_at(t, parent, &v, cp, &fast_decided);
        fast_bad[type] += fast_disagrees(t, child, &v, 0.5 + scene_rng_double(&rng), &fast_decided) != 0;
        count[type]++;
        kinds[v.kind]++;
        monotone_pairs++;
        if (isnan(cc) || isnan(cp)) {
            nan_count++;
            continue;
        }
        if (!(cc <= cp) && !bad[type]++)
            snprintf(first[type], sizeof first[type],
                     "node %u c %.17g > parent %u c %.17g; view kind %d flags %u pos %.9g %.9g %.9g fwd %.9g %.9g %.9g up %.9g %.9g %.9g W %u H %u fov %.9g near %.9g far %.9g hw %.9g hh %.9g",
                     child, cc, parent, cp, (int)v.kind, v.flags, v.position[0], v.position[1], v.position[2], v.forward[0],
                     v.forward[1], v.forward[2], v.up[0], v.up[1], v.up[2], v.width, v.height, v.fov_y, v.near_plane,
                     v.far_plane, v.half_width, v.half_height);
    }
    for (type = 0; type < 8; type++)
        CHECK(bad[type] == 0, "monotonicity %s, view type %u: %u of %u pairs with c(child) > c(parent); first: %s", what, type,
              bad[type], count[type], first[type]);
    for (type = 0; type < 8; type++)
        CHECK(fast_bad[type] == 0, "float filter on adversarial views, %s, type %u: %u of its decisions differ from the exact path",
              what, type, fast_bad[type]);
    CHECK(nan_count == 0, "monotonicity %s: %u NaN criteria for valid views", what, nan_count);
    CHECK(skipped < pairs / 20, "monotonicity %s: %u of %u generated views invalid", what, skipped, pairs);
    CHECK(kinds[MLOD_VIEW_CUBE] > pairs / 6, "monotonicity %s: only %u of %u views are cube maps", what,
          kinds[MLOD_VIEW_CUBE], pairs);
}

static void test_monotonicity(void)
{
    scene_mesh s;
    mlod_tree *t;
    double c[3] = {0, 0, 0}, R;
    uint32_t i;
    scene_uv_sphere(&s, 1.0f, 10, 20);
    t = tu_build(&s, 3000, 1, MLOD_ATTR_CONE);
    if (t) check_monotone(t, "sphere", 1, 40000, c, 1.0);
    mlod_tree_destroy(t);
    for (i = 0; i < 3 * s.vertex_count; i++) s.positions[i] *= 1e-15f;
    t = tu_build(&s, 1000, 2, MLOD_ATTR_CONE);
    if (t) check_monotone(t, "sphere of radius 1e-15", 2, 30000, c, 1e-15);
    mlod_tree_destroy(t);
    for (i = 0; i < 3 * s.vertex_count; i++) s.positions[i] *= 1e30f;
    t = tu_build(&s, 1000, 3, MLOD_ATTR_CONE);
    if (t) check_monotone(t, "sphere of radius 1e15", 3, 30000, c, 1e15);
    mlod_tree_destroy(t);
    scene_free(&s);
    scene_soup(&s, 500, 8);
    tu_bounds(&s, c, &R);
    t = tu_build(&s, 2000, 4, MLOD_ATTR_CONE);
    if (t) check_monotone(t, "soup", 4, 35000, c, R);
    mlod_tree_destroy(t);
    scene_free(&s);
    scene_room(&s);
    tu_bounds(&s, c, &R);
    t = tu_build(&s, 2000, 5, MLOD_ATTR_CONE);
    if (t) check_monotone(t, "room", 5, 35000, c, R);
    mlod_tree_destroy(t);
    scene_free(&s);
    t = random_points_tree(1500, 6, 1e-4, 0.3);
    c[0] = c[1] = c[2] = 0;
    if (t) check_monotone(t, "points", 6, 40000, c, 1.7);
    mlod_tree_destroy(t);
    CHECK(monotone_pairs >= 200000, "monotonicity: only %u (node, view) pairs checked", monotone_pairs);
    printf("  monotonicity: %u (node, view) pairs\n", monotone_pairs);
}

/* --------------------------------------------- incremental, lazy, motion */

static void rotate(double *v, const double *axis, double angle)
{
    double c = cos(angle), s = sin(angle), k[3], kxv[3], kv = tu_dot3(axis, v);
    int i;
    memcpy(k, axis, sizeof k);
    tu_cross3(kxv, k, v);
    for (i = 0; i < 3; i++) v[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1 - c);
}

typedef struct moving_views {
    uint32_t count;
    mlod_view base[16];
    double axis[16][3], orbit[16][3];
} moving_views;

static void moving_init(moving_views *m, uint64_t *rng, uint32_t count)
{
    double c[3] = {0, 0, 0};
    uint32_t i;
    m->count = count;
    for (i = 0; i < count; i++) {
        m->base[i] = tu_random_view(rng, (mlod_view_kind)(i % 5), c, 1.4);
        tu_random_unit(rng, m->axis[i]);
        tu_random_unit(rng, m->orbit[i]);
    }
}

/* Frame f: forward and up turned by 10 degrees per frame, eye orbiting the
   origin by 4 degrees per frame. */
static void moving_at(const moving_views *m, int f, mlod_view *out)
{
    uint32_t i;
    for (i = 0; i < m->count; i++) {
        double fw[3] = {m->base[i].forward[0], m->base[i].forward[1], m->base[i].forward[2]},
               up[3] = {m->base[i].up[0], m->base[i].up[1], m->base[i].up[2]},
               e[3] = {m->base[i].position[0], m->base[i].position[1], m->base[i].position[2]};
        out[i] = m->base[i];
        rotate(fw, m->axis[i], f * 10.0 * TU_PI / 180);
        rotate(up, m->axis[i], f * 10.0 * TU_PI / 180);
        rotate(e, m->orbit[i], f * 4.0 * TU_PI / 180);
        tu_set3f(out[i].forward, fw);
        tu_set3f(out[i].up, up);
        tu_set3f(out[i].position, e);
    }
}

typedef struct saved_cut {
    uint32_t count[16];
    uint32_t *nodes[16];
} saved_cut;

static void save_cut(saved_cut *s, const mlod_cut *cut, uint32_t views)
{
    uint32_t v;
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        s->count[v] = cv.count;
        s->nodes[v] = (uint32_t *)realloc(s->nodes[v], sizeof(uint32_t) * (cv.count + 1));
        if (cv.count) memcpy(s->nodes[v], cv.nodes, sizeof(uint32_t) * cv.count);
    }
}

/* Every node of the new cut lies within q edges of the previous cut's
   nodes it overlaps (q splits down, or q merges up). */
static uint32_t lazy_move_errors(const tu_layout *L, const uint32_t *prev, uint32_t prev_count, const mlod_cut_view *cv,
                                 uint32_t q, uint32_t *owner)
{
    uint32_t i, j, bad = 0;
    for (i = 0; i < prev_count; i++)
        for (j = 0; j < L->count[prev[i]]; j++) owner[L->first[prev[i]] + j] = prev[i];
    for (i = 0; i < cv->count; i++) {
        uint32_t n = cv->nodes[i], pos = L->first[n], end = L->first[n] + L->count[n];
        while (pos < end) {
            uint32_t o = owner[pos], dn = tu_depth(n), dof = tu_depth(o);
            if (tu_is_ancestor(o, n)) {
                if (dn - dof > q) bad++;
                break;
            }
            if (!tu_is_ancestor(n, o) || dof - dn > q) bad++;
            pos = L->first[o] + L->count[o];
        }
    }
    return bad;
}

/* A torus twisting frame by frame (scene_torus, scene_deform) and its tree
   of 4000 leaves with cones, refitted to each pose; its layout and a
   workspace.  twisting_init returns 0 (nothing held) when the build fails. */
typedef struct twisting {
    scene_mesh rest;
    float *pos, *nrm;
    mlod_mesh mesh;
    mlod_tree *tree;
    tu_layout L;
    workspace w;
} twisting;

static int twisting_init(twisting *tw, uint64_t seed)
{
    scene_torus(&tw->rest, 1.0f, 0.35f, 32, 16);
    tw->tree = tu_build(&tw->rest, 4000, seed, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
    if (!tw->tree) {
        scene_free(&tw->rest);
        return 0;
    }
    tw->pos = (float *)malloc(sizeof(float) * 3 * tw->rest.vertex_count);
    tw->nrm = (float *)malloc(sizeof(float) * 3 * tw->rest.vertex_count);
    tw->mesh = tu_mesh(&tw->rest);
    tw->mesh.positions = tw->pos;
    tw->mesh.normals = tw->nrm;
    tu_layout_init(&tw->L, tw->tree->leaf_count);
    ws_init(&tw->w, tw->tree->node_count);
    return 1;
}

/* The torus at time t, the tree refitted to it; 0 when the refit fails. */
static int twisting_pose(twisting *tw, float t)
{
    scene_deform(&tw->rest, t, tw->pos, tw->nrm);
    return mlod_refit_mesh(tw->tree, &tw->mesh, NULL, NULL) == MLOD_OK;
}

static void twisting_free(twisting *tw)
{
    ws_free(&tw->w);
    tu_layout_free(&tw->L);
    mlod_tree_destroy(tw->tree);
    free(tw->pos);
    free(tw->nrm);
    scene_free(&tw->rest);
}

static void run_motion(float eps, uint64_t seed)
{
    twisting tw;
    mlod_tree *tree;
    mlod_cut *cb = NULL, *ci = NULL, *cl[2] = {NULL, NULL};
    moving_views mv;
    mlod_view views[16];
    tally t;
    saved_cut prev[2];
    const uint32_t nv = 12, frames = 24;
    uint32_t f, v, q, inc_bad = 0, lazy_partition[2] = {0, 0}, lazy_status[2] = {0, 0}, lazy_moves[2] = {0, 0},
                      lazy_counts[2] = {0, 0}, converged[2] = {0, 0}, bound, k;
    uint64_t rng = seed;
    char what[64], first_inc[160] = "";
    snprintf(what, sizeof what, "motion eps %g", eps);
    memset(prev, 0, sizeof prev);
    memset(&t, 0, sizeof t);
    CHECK(twisting_init(&tw, seed), "%s: build", what);
    if (!tw.tree) return;
    tree = tw.tree;
    mlod_cut_create(nv, NULL, &cb, NULL);
    mlod_cut_create(nv, NULL, &ci, NULL);
    mlod_cut_create(nv, NULL, &cl[0], NULL);
    mlod_cut_create(nv, NULL, &cl[1], NULL);
    moving_init(&mv, &rng, nv);
    for (f = 0; f < frames; f++) {
        mlod_cut_params pb = params(MLOD_CUT_BASIC, eps, 1, NULL), pi = params(MLOD_CUT_INCREMENTAL, eps, 1, NULL);
        CHECK(twisting_pose(&tw, 0.15f * f), "%s frame %u: refit", what, f);
        moving_at(&mv, (int)f, views);
        CHECK(mlod_cut_update(cb, tree, views, &pb, NULL) == MLOD_OK && mlod_cut_update(ci, tree, views, &pi, NULL) == MLOD_OK,
              "%s frame %u: updates", what, f);
        for (v = 0; v < nv; v++) {
            mlod_cut_view a = mlod_cut_get(cb, v), b = mlod_cut_get(ci, v);
            if (!tu_same_cut(&a, &b) && !inc_bad++)
                snprintf(first_inc, sizeof first_inc, "frame %u view %u: basic %u nodes, incremental %u", f, v, a.count, b.count);
        }
        if (f % 4 == 0) check_against_reference(tree, &tw.L, views, 0, nv, eps, cb, &tw.w, &t);
        for (q = 0; q < 2; q++) {
            mlod_cut_params pl = params(MLOD_CUT_LAZY, eps, q + 1, NULL);
            CHECK(mlod_cut_update(cl[q], tree, views, &pl, NULL) == MLOD_OK, "%s frame %u: lazy update", what, f);
            for (v = 0; v < nv; v++) {
                mlod_cut_view cv = mlod_cut_get(cl[q], v);
                lazy_partition[q] += tu_partition_errors(&tw.L, cv.nodes, cv.count, tw.w.hits) != 0;
                lazy_counts[q] += !tu_counts_ok(&cv);
                for (k = 0; k < cv.count; k++) {
                    double c = mlod_criterion(tree, cv.nodes[k], views + v);
                    if (cv.status[k] != tu_status(c, eps, tu_is_leaf(&tw.L, cv.nodes[k]))) lazy_status[q]++;
                }
                if (f > 0 && prev[q].nodes[v] && tu_partition_errors(&tw.L, prev[q].nodes[v], prev[q].count[v], tw.w.hits) == 0)
                    lazy_moves[q] += lazy_move_errors(&tw.L, prev[q].nodes[v], prev[q].count[v], &cv, q + 1, tw.w.hits) != 0;
            }
            save_cut(&prev[q], cl[q], nv);
        }
    }
    CHECK(inc_bad == 0, "%s: incremental differs from basic in %u view-frames; first: %s", what, inc_bad, first_inc);
    tally_report(&t, what);
    for (q = 0; q < 2; q++) {
        CHECK(lazy_partition[q] == 0, "%s lazy q=%u: %u view-frames not a partition", what, q + 1, lazy_partition[q]);
        CHECK(lazy_counts[q] == 0, "%s lazy q=%u: %u view-frames with wrong counts", what, q + 1, lazy_counts[q]);
        CHECK(lazy_status[q] == 0, "%s lazy q=%u: %u cut nodes whose status disagrees with their criterion", what, q + 1,
              lazy_status[q]);
        CHECK(lazy_moves[q] == 0, "%s lazy q=%u: %u view-frames with a node more than q edges from the previous cut", what,
              q + 1, lazy_moves[q]);
    }
    /* views and mesh stop: lazy converges to basic within 2 depth + 2 calls */
    bound = 2 * tw.L.max_depth + 2;
    for (q = 0; q < 2; q++) {
        mlod_cut_params pl = params(MLOD_CUT_LAZY, eps, q + 1, NULL);
        for (k = 1; k <= bound && !converged[q]; k++) {
            uint32_t same = 0;
            mlod_cut_update(cl[q], tree, views, &pl, NULL);
            for (v = 0; v < nv; v++) {
                mlod_cut_view a = mlod_cut_get(cb, v), b = mlod_cut_get(cl[q], v);
                same += tu_same_cut(&a, &b);
            }
            if (same == nv) converged[q] = k;
        }
        CHECK(converged[q] != 0, "%s lazy q=%u: not equal to basic after %u calls with still views", what, q + 1, bound);
        printf("  %s lazy q=%u: converged after %u calls (bound %u)\n", what, q + 1, converged[q], bound);
    }
    {
        /* lazy_steps as large as it goes: one call from the root reaches the
           basic cut and stops when no move is left (it used to run all
           2^32 - 1 rounds) */
        mlod_cut_params pl = params(MLOD_CUT_LAZY, eps, UINT32_MAX, NULL);
        mlod_cut *cu = NULL;
        uint32_t same = 0;
        CHECK(mlod_cut_create(nv, NULL, &cu, NULL) == MLOD_OK && mlod_cut_update(cu, tree, views, &pl, NULL) == MLOD_OK,
              "%s lazy q=2^32-1: update", what);
        for (v = 0; cu && v < nv; v++) {
            mlod_cut_view a = mlod_cut_get(cb, v), b = mlod_cut_get(cu, v);
            same += tu_same_cut(&a, &b);
        }
        CHECK(same == nv, "%s lazy q=2^32-1: %u of %u views equal basic after one call", what, same, nv);
        mlod_cut_destroy(cu);
    }
    for (q = 0; q < 2; q++)
        for (v = 0; v < nv; v++) free(prev[q].nodes[v]);
    mlod_cut_destroy(cb);
    mlod_cut_destroy(ci);
    mlod_cut_destroy(cl[0]);
    mlod_cut_destroy(cl[1]);
    twisting_free(&tw);
}

static void test_motion(void)
{
    run_motion(2.0f, 31);
    run_motion(0.6f, 32);
}

/* ------------------------------------------------ a lazy update's budget */

typedef struct budget_copy {
    uint32_t count;
    uint32_t *nodes;
    uint8_t *status;
    uint64_t version;
} budget_copy;

static void budget_take(budget_copy *c, const mlod_cut_view *cv)
{
    c->count = cv->count;
    c->nodes = (uint32_t *)realloc(c->nodes, sizeof(uint32_t) * (cv->count + 1));
    c->status = (uint8_t *)realloc(c->status, cv->count + 1);
    if (cv->count) {
        memcpy(c->nodes, cv->nodes, sizeof(uint32_t) * cv->count);
        memcpy(c->status, cv->status, cv->count);
    }
    c->version = cv->version;
}

static int budget_same(const budget_copy *c, const mlod_cut_view *cv)
{
    return c->count == cv->count &&
           (!cv->count || (memcmp(c->nodes, cv->nodes, sizeof(uint32_t) * cv->count) == 0 &&
                           memcmp(c->status, cv->status, cv->count) == 0));
}

/* Lazy updates with a budget of node-views (mlod_cut_params.budget), the
   views turning and the torus twisting every frame, checked view by view
   against a model of the documented rule and against the definitions:
   - no update evaluates more node-views than its budget;
   - the views evaluated are those the rule picks: in passes, oldest
     evaluation first (equal ones in view order), each while the
     documented bound 3 n (2^q - 1) of its list's n entries fits in what
     the views taken before left of the budget; the others keep their
     list entry for entry, and their version moves exactly when their
     view bytes did;
   - every list is a partition with the right counts, and an evaluated
     view's statuses are its criterion's, its nodes within q edges of its
     list before;
   - once views and mesh stop, the budgeted updates reach the basic cut
     of every view, and then evaluate nothing;
   - a budget in another mode is refused, the cut unchanged; a budget
     below every bound evaluates nothing. */
static void run_budget(uint32_t q, float eps, uint64_t seed)
{
    enum { NV = 24 };
    twisting tw;
    mlod_tree *tree;
    mlod_cut *cut = NULL, *cb = NULL;
    mlod_view base[NV], views[NV], before[NV];
    double axis[NV][3];
    budget_copy copy[NV];
    uint32_t last[NV], order[NV];
    uint8_t picked[NV];
    uint64_t used;
    const uint32_t frames = 16;
    uint32_t f, v, k, over = 0, wrong_pick = 0, kept_bad = 0, version_bad = 0, partition = 0, counts = 0, status = 0,
                      moves = 0, partial = 0, converged = 0, after = 0, calls;
    uint64_t rng = seed, spent_total = 0, budget_total = 0;
    double c[3] = {0, 0, 0};
    char what[48];
    snprintf(what, sizeof what, "budget q=%u eps %g", q, eps);
    memset(copy, 0, sizeof copy);
    CHECK(twisting_init(&tw, seed), "%s: build", what);
    if (!tw.tree) return;
    tree = tw.tree;
    mlod_cut_create(NV, NULL, &cut, NULL);
    mlod_cut_create(NV, NULL, &cb, NULL);
    for (v = 0; v < NV; v++) {
        base[v] = tu_random_view(&rng, (mlod_view_kind)(v % 5), c, 1.4);
        tu_random_unit(&rng, axis[v]);
    }
    for (f = 0; f <= frames; f++) {
        mlod_cut_params pl = params(MLOD_CUT_LAZY, eps, q, NULL);
        uint64_t budget = 0, left, spent = 0;
        memcpy(before, views, sizeof views);
        for (v = 0; v < NV; v++) { /* turned by 3 degrees per frame, the eye with them */
            double fw[3] = {base[v].forward[0], base[v].forward[1], base[v].forward[2]},
                   up[3] = {base[v].up[0], base[v].up[1], base[v].up[2]},
                   e[3] = {base[v].position[0], base[v].position[1], base[v].position[2]};
            views[v] = base[v];
            rotate(fw, axis[v], f * 3.0 * TU_PI / 180);
            rotate(up, axis[v], f * 3.0 * TU_PI / 180);
            rotate(e, axis[v], f * 3.0 * TU_PI / 180);
            tu_set3f(views[v].forward, fw);
            tu_set3f(views[v].up, up);
            tu_set3f(views[v].position, e);
        }
        CHECK(twisting_pose(&tw, 0.1f * f), "%s frame %u: refit", what, f);
        if (f > 0) {
            /* about a third of the views' bounds; odd frames a budget that
               holds none (at most the smallest bound less one) */
            uint64_t sum = 0, least = UINT64_MAX;
            for (v = 0; v < NV; v++) {
                uint64_t b = tu_lazy_bound(copy[v].count, q);
                sum += b;
                if (b < least) least = b;
            }
            budget = f % 4 == 3 ? least - 1 : sum / 3;
            if (budget == 0) budget = 1;
        }
        pl.budget = budget;
        if (f == 1) { /* refused in the other modes, before any change */
            mlod_cut_params pi = params(MLOD_CUT_INCREMENTAL, eps, 1, NULL);
            mlod_error e;
            pi.budget = budget;
            CHECK(mlod_cut_update(cut, tree, views, &pi, &e) == MLOD_ERROR_INVALID_ARGUMENT,
                  "%s: a budget in incremental mode is not refused", what);
            for (v = 0; v < NV; v++) {
                mlod_cut_view cv = mlod_cut_get(cut, v);
                kept_bad += !budget_same(&copy[v], &cv) || cv.version != copy[v].version;
            }
        }
        CHECK(mlod_cut_update(cut, tree, views, &pl, NULL) == MLOD_OK, "%s frame %u: update", what, f);
        /* the model: every view changed (the mesh moves all over) */
        for (v = 0; v < NV; v++) order[v] = v;
        for (v = 1; v < NV; v++) /* oldest first, then view order (insertion: stable) */
            for (k = v; k > 0 && last[order[k - 1]] > last[order[k]]; k--) {
                uint32_t t = order[k];
                order[k] = order[k - 1];
                order[k - 1] = t;
            }
        /* passes (at most 4): each takes, oldest first, the views not yet
           taken while their bounds fit in what the views taken so far left
           of the budget (their actual counts), until a pass takes none */
        memset(picked, f == 0, sizeof picked);
        for (used = 0, k = 0; f > 0 && k < 4; k++) { /* at most 4 passes */
            uint32_t chosen = 0, j;
            uint8_t now[NV];
            memset(now, 0, sizeof now);
            left = budget - used;
            for (j = 0; j < NV; j++) {
                v = order[j];
                if (picked[v] || tu_lazy_bound(copy[v].count, q) > left) continue;
                left -= tu_lazy_bound(copy[v].count, q);
                picked[v] = now[v] = 1;
                chosen++;
            }
            for (v = 0; v < NV; v++)
                if (now[v]) used += mlod_cut_get(cut, v).evaluated;
            if (!chosen || used > budget) break;
        }
        for (v = 0; v < NV; v++) {
            mlod_cut_view cv = mlod_cut_get(cut, v);
            spent += cv.evaluated;
            wrong_pick += picked[v] != (cv.evaluated > 0) || picked[v] == cv.deferred;
            if (!picked[v]) {
                kept_bad += !budget_same(&copy[v], &cv) || cv.steps != 0;
                version_bad += (cv.version != copy[v].version) != (memcmp(&views[v], &before[v], sizeof(mlod_view)) != 0);
            }
        }
        if (f > 0) {
            over += spent > budget;
            spent_total += spent;
            budget_total += budget;
        }
        for (v = 0; v < NV; v++) {
            mlod_cut_view cv = mlod_cut_get(cut, v);
            partition += tu_partition_errors(&tw.L, cv.nodes, cv.count, tw.w.hits) != 0;
            counts += !tu_counts_ok(&cv);
            if (cv.evaluated > 0) {
                for (k = 0; k < cv.count; k++) {
                    double cr = mlod_criterion(tree, cv.nodes[k], views + v);
                    status += cv.status[k] != tu_status(cr, eps, tu_is_leaf(&tw.L, cv.nodes[k]));
                }
                if (f > 0) moves += lazy_move_errors(&tw.L, copy[v].nodes, copy[v].count, &cv, q, tw.w.hits) != 0;
                last[v] = f;
            }
            budget_take(&copy[v], &cv);
        }
    }
    CHECK(over == 0, "%s: %u updates over their budget", what, over);
    CHECK(wrong_pick == 0, "%s: %u view-updates evaluated against the rule (oldest first, while the bound fits)", what,
          wrong_pick);
    CHECK(kept_bad == 0, "%s: %u deferred views whose list changed", what, kept_bad);
    CHECK(version_bad == 0, "%s: %u deferred views whose version did not follow their view", what, version_bad);
    CHECK(partition == 0 && counts == 0, "%s: %u view-frames not a partition, %u with wrong counts", what, partition, counts);
    CHECK(status == 0, "%s: %u entries of evaluated views whose status disagrees with the criterion", what, status);
    CHECK(moves == 0, "%s: %u view-frames with a node more than q edges from the list before", what, moves);
    CHECK(spent_total * 4 >= budget_total / 4, "%s: the budget went unused: %llu of %llu node-views", what,
          (unsigned long long)spent_total, (unsigned long long)budget_total);
    /* views and mesh stop: the budgeted updates converge to the basic cut */
    {
        mlod_cut_params pb = params(MLOD_CUT_BASIC, eps, 1, NULL), pl = params(MLOD_CUT_LAZY, eps, q, NULL);
        uint64_t most = 0;
        CHECK(mlod_cut_update(cb, tree, views, &pb, NULL) == MLOD_OK, "%s: basic update", what);
        for (v = 0; v < NV; v++) {
            uint64_t b = tu_lazy_bound(mlod_cut_get(cb, v).count, q) * 2 + 16;
            if (b > most) most = b;
        }
        pl.budget = most; /* more than any view needs as it converges */
        for (calls = 1; calls <= NV * (2 * tw.L.max_depth + 2) && !converged; calls++) {
            uint32_t same = 0;
            uint64_t spent = 0;
            CHECK(mlod_cut_update(cut, tree, views, &pl, NULL) == MLOD_OK, "%s: update with still views", what);
            for (v = 0; v < NV; v++) {
                mlod_cut_view a = mlod_cut_get(cb, v), b = mlod_cut_get(cut, v);
                same += tu_same_cut(&a, &b);
                spent += b.evaluated;
                partial += tu_partition_errors(&tw.L, b.nodes, b.count, tw.w.hits) != 0;
            }
            over += spent > pl.budget;
            if (same == NV) converged = calls;
        }
        CHECK(converged != 0, "%s: not equal to the basic cut after %u calls with still views", what, calls - 1);
        CHECK(partial == 0 && over == 0, "%s: while converging, %u lists not a partition, %u updates over budget", what,
              partial, over);
        /* a lazy list is known to be the basic cut after a call that
           made no move on it: each view once more, then nothing is
           evaluated, and the lists stay the basic cuts */
        for (k = 0; k <= NV && converged; k++) {
            uint32_t evaluated = 0, same = 0;
            mlod_cut_update(cut, tree, views, &pl, NULL);
            for (v = 0; v < NV; v++) {
                mlod_cut_view a = mlod_cut_get(cb, v), b = mlod_cut_get(cut, v);
                evaluated += b.evaluated != 0;
                same += tu_same_cut(&a, &b);
            }
            after += same != NV;
            if (!evaluated) break;
        }
        CHECK(after == 0 && k <= NV, "%s: after convergence, %u updates moved a list; %u updates still evaluated", what,
              after, k);
        /* after a reset, an update starts every view from the root,
           whatever the budget (none is deferred) */
        pl.budget = 1;
        mlod_cut_update(cut, tree, views, &pl, NULL); /* all deferred but those skipped */
        mlod_cut_reset(cut);
        for (v = 0, k = 0; v < NV; v++) k += mlod_cut_get(cut, v).deferred;
        CHECK(mlod_cut_update(cut, tree, views, &pl, NULL) == MLOD_OK, "%s: update after a reset", what);
        for (v = 0; v < NV; v++) k += mlod_cut_get(cut, v).deferred || !mlod_cut_get(cut, v).evaluated;
        CHECK(k == 0, "%s: after a reset, %u views deferred or not evaluated", what, k);
        printf("  %s: %llu of %llu budgeted node-views spent while moving; converged after %u calls\n", what,
               (unsigned long long)spent_total, (unsigned long long)budget_total, converged);
    }
    for (v = 0; v < NV; v++) {
        free(copy[v].nodes);
        free(copy[v].status);
    }
    mlod_cut_destroy(cut);
    mlod_cut_destroy(cb);
    twisting_free(&tw);
}

static void test_budget(void)
{
    run_budget(1, 0.4f, 41);
    run_budget(2, 0.7f, 42);
}

/* Incremental starts from the root after a tree of another node count, or
   after mlod_cut_reset. */
static void test_restart(void)
{
    scene_mesh s;
    mlod_tree *a, *b;
    mlod_cut *ci = NULL, *cb = NULL;
    mlod_view views[5];
    uint64_t rng = 3;
    double c[3] = {0, 0, 0};
    uint32_t v, same = 0, k;
    mlod_cut_params pi = params(MLOD_CUT_INCREMENTAL, 2.0f, 1, NULL), pb = params(MLOD_CUT_BASIC, 2.0f, 1, NULL);
    scene_torus(&s, 1.0f, 0.3f, 16, 8);
    a = tu_build(&s, 1000, 1, 0);
    b = tu_build(&s, 1500, 1, 0);
    mlod_cut_create(5, NULL, &ci, NULL);
    mlod_cut_create(5, NULL, &cb, NULL);
    CHECK(mlod_cut_view_count(ci) == 5, "cut: view count %u", mlod_cut_view_count(ci));
    for (v = 0; v < 5; v++) CHECK(mlod_cut_get(ci, v).count == 0, "cut: view %u not empty before any update", v);
    for (v = 0; v < 5; v++) views[v] = tu_random_view(&rng, (mlod_view_kind)v, c, 1.3);
    for (k = 0; k < 3; k++) {
        mlod_tree *t = k == 1 ? b : a;
        if (k == 2) mlod_cut_reset(ci);
        CHECK(mlod_cut_update(ci, t, views, &pi, NULL) == MLOD_OK && mlod_cut_update(cb, t, views, &pb, NULL) == MLOD_OK,
              "restart %u: updates", k);
        for (v = 0, same = 0; v < 5; v++) {
            mlod_cut_view x = mlod_cut_get(ci, v), y = mlod_cut_get(cb, v);
            same += tu_same_cut(&x, &y);
        }
        CHECK(same == 5, "restart %u (%s): incremental equals basic in %u of 5 views", k,
              k == 1 ? "another node count" : k == 2 ? "after reset" : "first update", same);
    }
    CHECK(mlod_cut_bytes(ci) > 0, "cut: mlod_cut_bytes is 0 after an update");
    mlod_cut_destroy(ci);
    mlod_cut_destroy(cb);
    mlod_tree_destroy(a);
    mlod_tree_destroy(b);
    scene_free(&s);
}

/* ----------------------------------------------- cuts that shrink */

/* Chunks of a cut whose cuts shrank join (mlod__merge_chunks): after the
   update that shrinks them and one more that goes through the windows
   (the views moved a little), every chunk but the last holds at
   least a quarter of a window's entries, or could not take the next one
   in (a window's entries or views); the chunks cover the views in order,
   hold their lists, and the cuts equal a basic cut of the same views
   throughout.  With the default window every cut here fits one chunk; the
   compile matrix runs this with windows of 2^10 entries, where the cuts
   at epsilon 0.5 take dozens. */
static void test_shrinking(void)
{
    scene_mesh s;
    mlod_tree *t;
    mlod_cut *ci = NULL, *cb = NULL;
    enum { NV = 96 };
    mlod_view views[NV];
    uint64_t rng = 11;
    double c[3] = {0, 0, 0};
    static const float eps[4] = {0.5f, 8.0f, 8.0f, 0.5f};
    uint32_t v, k, i;
    scene_torus(&s, 1.0f, 0.3f, 32, 16);
    t = tu_build(&s, 20000, 2, MLOD_ATTR_CONE);
    mlod_cut_create(NV, NULL, &ci, NULL);
    mlod_cut_create(NV, NULL, &cb, NULL);
    for (v = 0; v < NV; v++) views[v] = tu_random_view(&rng, v % 2 ? MLOD_VIEW_PARABOLOID : MLOD_VIEW_PERSPECTIVE, c, 1.3);
    for (k = 0; k < 4 && t && ci && cb; k++) {
        mlod_cut_params pi = params(MLOD_CUT_INCREMENTAL, eps[k], 1, NULL), pb = params(MLOD_CUT_BASIC, eps[k], 1, NULL);
        uint32_t same = 0, covered = 0, small = 0;
        size_t held = 0;
        if (k == 2) /* the views a little further: an update that goes through every window (none skipped) */
            for (v = 0; v < NV; v++) views[v].position[0] += 1e-3f;
        CHECK(mlod_cut_update(ci, t, views, &pi, NULL) == MLOD_OK && mlod_cut_update(cb, t, views, &pb, NULL) == MLOD_OK,
              "shrinking, step %u: updates", k);
        for (v = 0; v < NV; v++) {
            mlod_cut_view x = mlod_cut_get(ci, v), y = mlod_cut_get(cb, v);
            same += tu_same_cut(&x, &y);
        }
        CHECK(same == NV, "shrinking, step %u (epsilon %g): the incremental cut equals the basic cut in %u of %u views", k,
              eps[k], same, NV);
        for (i = 0; i < ci->chunk_count; i++) {
            const mlod__chunk *ch = &ci->chunks[i];
            size_t entries = mlod__chunk_entries(ci, ch);
            CHECK(ch->first == covered && entries <= ch->capacity, "shrinking, step %u: chunk %u covers views %u.. "
                  "(expected %u) and holds its %zu entries (capacity %zu)", k, i, ch->first, covered, entries, ch->capacity);
            covered += ch->views;
            held += entries;
            if (k == 2 && i + 1 < ci->chunk_count) {
                const mlod__chunk *next = &ci->chunks[i + 1];
                small += entries < MLOD__WINDOW / 4 && entries + mlod__chunk_entries(ci, next) <= MLOD__WINDOW &&
                         ch->views + next->views <= MLOD__WINDOW_VIEWS;
            }
        }
        CHECK(covered == NV, "shrinking, step %u: the chunks cover %u of %u views", k, covered, NV);
        if (k == 2)
            CHECK(small == 0, "shrinking: %u of %u chunks hold under a quarter of a window and could have joined the next",
                  small, ci->chunk_count);
        if (getenv("SHRINK_VERBOSE")) printf("step %u: %u chunks, %zu entries\n", k, ci->chunk_count, held);
    }
    mlod_cut_destroy(ci);
    mlod_cut_destroy(cb);
    mlod_tree_destroy(t);
    scene_free(&s);
}

/* ------------------------------------------ unchanged views are skipped */

/* An update skips a view whose view (every byte), tree (the same object,
   not refitted since) and epsilon are those of the previous update, when
   that update left its cut exact; everything else is computed as before.
   The results are checked against the brute-force reference, so a skip
   that kept a stale list fails the reference as well as the counts. */
#define SKIP_NV 10

typedef struct skip_copy {
    mlod_cut_view cv[SKIP_NV];
    uint32_t *nodes[SKIP_NV];
    uint8_t *status[SKIP_NV];
} skip_copy;

static void skip_copy_take(skip_copy *c, const mlod_cut *cut)
{
    uint32_t v;
    for (v = 0; v < SKIP_NV; v++) {
        c->cv[v] = mlod_cut_get(cut, v);
        c->nodes[v] = (uint32_t *)realloc(c->nodes[v], sizeof(uint32_t) * (c->cv[v].count + 1));
        c->status[v] = (uint8_t *)realloc(c->status[v], c->cv[v].count + 1);
        if (c->cv[v].count) {
            memcpy(c->nodes[v], c->cv[v].nodes, sizeof(uint32_t) * c->cv[v].count);
            memcpy(c->status[v], c->cv[v].status, c->cv[v].count);
        }
        c->cv[v].nodes = c->nodes[v];
        c->cv[v].status = c->status[v];
    }
}

static void skip_copy_free(skip_copy *c)
{
    uint32_t v;
    for (v = 0; v < SKIP_NV; v++) {
        free(c->nodes[v]);
        free(c->status[v]);
    }
}

/* Views whose lists (or counts by status) differ from the copy's. */
static uint32_t skip_copy_differs(const skip_copy *c, const mlod_cut *cut)
{
    uint32_t v, n = 0;
    for (v = 0; v < SKIP_NV; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        n += !tu_same_cut(&cv, &c->cv[v]);
    }
    return n;
}

/* Bit v set: view v was evaluated (evaluated > 0) in the last update. */
static uint32_t skip_evaluated(const mlod_cut *cut)
{
    uint32_t v, mask = 0;
    for (v = 0; v < SKIP_NV; v++)
        if (mlod_cut_get(cut, v).evaluated > 0) mask |= 1u << v;
    return mask;
}

/* An update, then skip_evaluated; all bits set when the update fails. */
static uint32_t skip_update(mlod_cut *cut, const mlod_tree *tree, const mlod_view *views, const mlod_cut_params *p)
{
    return mlod_cut_update(cut, tree, views, p, NULL) == MLOD_OK ? skip_evaluated(cut) : ~0u;
}

static uint64_t skip_steps(const mlod_cut *cut)
{
    uint32_t v;
    uint64_t steps = 0;
    for (v = 0; v < SKIP_NV; v++) steps += mlod_cut_get(cut, v).steps;
    return steps;
}

typedef struct skip_env {
    mlod_tree *tree;
    tu_layout L, L_other; /* of tree, and of a tree of other leaves */
    workspace w;
    uint32_t bound; /* lazy calls that suffice to converge */
} skip_env;

/* Update; in lazy mode go on until a call makes no move (at most
   env->bound calls).  Returns the calls made, 0 on failure. */
static uint32_t skip_settle(const skip_env *env, mlod_cut *cut, const mlod_tree *tree, const mlod_view *views,
                            mlod_cut_params p)
{
    uint32_t calls = 0;
    do {
        if (mlod_cut_update(cut, tree, views, &p, NULL) != MLOD_OK) return 0;
        calls++;
    } while (p.mode == MLOD_CUT_LAZY && skip_steps(cut) != 0 && calls < env->bound);
    return calls;
}

/* Every view of the cut against the reference (basic cut of views at eps). */
static void skip_reference(skip_env *env, const mlod_tree *tree, const mlod_view *views, float eps, const mlod_cut *cut,
                           const char *what)
{
    tally t;
    memset(&t, 0, sizeof t);
    check_against_reference(tree, tree->leaf_count == env->L.leaves ? &env->L : &env->L_other, views, 0, SKIP_NV, eps,
                            cut, &env->w, &t);
    tally_report(&t, what);
}

/* An update after a change every view sees (what): every view evaluated,
   then, settled, every view's cut the reference's. */
static void skip_all_changed(skip_env *env, mlod_cut *cut, const mlod_view *views, mlod_cut_params p, const char *m,
                             const char *what)
{
    const uint32_t all = (1u << SKIP_NV) - 1;
    char line[160];
    uint32_t mask;
    CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip %s: update", m);
    mask = skip_evaluated(cut);
    CHECK(mask == all, "skip %s, %s: views 0x%x evaluated, expected all", m, what, mask);
    CHECK(skip_settle(env, cut, env->tree, views, p) > 0, "skip %s: update", m);
    snprintf(line, sizeof line, "skip %s, %s", m, what);
    skip_reference(env, env->tree, views, p.epsilon, cut, line);
}

static void skip_mode(skip_env *env, mlod_tree *twin, mlod_tree *other, const mlod_mesh *rest, const mlod_view *base,
                      mlod_cut_mode mode, uint32_t lazy_steps)
{
    static const char *names[4] = {"basic", "incremental", "lazy q=1", "lazy q=3"};
    const uint32_t all = (1u << SKIP_NV) - 1;
    mlod_cut_params p = params(mode, 1.5f, lazy_steps, NULL);
    mlod_view views[SKIP_NV], bad[SKIP_NV];
    mlod_cut *cut = NULL;
    skip_copy before;
    uint64_t revision;
    uint32_t v, mask;
    char what[160];
    const char *m = names[mode + (lazy_steps > 1)];
    memset(&before, 0, sizeof before);
    memcpy(views, base, sizeof views); /* the same bytes at another address */
    CHECK(mlod_cut_create(SKIP_NV, NULL, &cut, NULL) == MLOD_OK, "skip %s: create", m);
    if (!cut) return;
    CHECK(skip_settle(env, cut, env->tree, base, p) > 0, "skip %s: first update", m);
    skip_copy_take(&before, cut);

    /* 1. the same views (a copy), tree and epsilon: nothing evaluated, the same lists */
    CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip %s: second update", m);
    CHECK(skip_evaluated(cut) == 0 && skip_steps(cut) == 0,
          "skip %s: an update of unchanged views evaluated views 0x%x (%llu steps)", m, skip_evaluated(cut),
          (unsigned long long)skip_steps(cut));
    CHECK(skip_copy_differs(&before, cut) == 0, "skip %s: %u unchanged views' lists changed", m,
          skip_copy_differs(&before, cut));
    snprintf(what, sizeof what, "skip %s, unchanged views", m);
    skip_reference(env, env->tree, views, p.epsilon, cut, what);

    /* 2. one byte of one view, in a field its kind does not read: that view
       alone is evaluated, and its cut is the same */
    views[1].fov_y += 1.0f; /* view 1 is a paraboloid */
    CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip %s: update", m);
    mask = skip_evaluated(cut);
    CHECK(mask == 1u << 1, "skip %s, one unread byte of view 1 changed: views 0x%x evaluated, expected 0x2", m, mask);
    CHECK(skip_copy_differs(&before, cut) == 0, "skip %s, an unread byte changed: %u lists changed", m,
          skip_copy_differs(&before, cut));

    /* 3. one view moves: that view alone is evaluated; in lazy mode it
       keeps converging while the others stay skipped */
    views[2].position[0] += 0.05f;
    views[2].position[2] -= 0.04f;
    CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip %s: update", m);
    mask = skip_evaluated(cut);
    CHECK(mask == 1u << 2, "skip %s, view 2 moved: views 0x%x evaluated, expected 0x4", m, mask);
    if (mode == MLOD_CUT_LAZY) {
        uint32_t calls = 1, others = 0;
        while (mlod_cut_get(cut, 2).steps != 0 && calls < env->bound) {
            CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip lazy: update");
            calls++;
            mask = skip_evaluated(cut);
            others |= mask & ~(1u << 2);
            CHECK(mask & (1u << 2), "skip lazy: view 2 moved in the call before but was not evaluated (call %u)",
                  calls);
        }
        CHECK(others == 0, "skip lazy, view 2 converging: views 0x%x evaluated, which did not change", others);
        mask = skip_update(cut, env->tree, views, &p);
        CHECK(mask == 0, "skip lazy: after view 2 converged (%u calls), views 0x%x still evaluated", calls, mask);
    }
    snprintf(what, sizeof what, "skip %s, view 2 moved", m);
    skip_reference(env, env->tree, views, p.epsilon, cut, what);
    for (v = 0; v < SKIP_NV; v++)
        if (v != 2) {
            mlod_cut_view cv = mlod_cut_get(cut, v);
            CHECK(tu_same_cut(&cv, &before.cv[v]), "skip %s: view %u's list changed when only view 2 moved", m, v);
        }
    skip_copy_take(&before, cut);

    /* 4. a refit to the same positions: a new revision.  A basic update
       evaluates every view; an incremental or lazy one only the entries
       whose nodes the refit changed (the first refit after the build may
       round some leaves otherwise than the build did), and after a second
       such refit nothing at all.  A write the tree did not record (its
       revision counted up by hand) makes the next update, and the update
       after the next refit, evaluate every view again. */
    revision = env->tree->revision;
    CHECK(mlod_refit_mesh(env->tree, rest, NULL, NULL) == MLOD_OK, "skip %s: refit", m);
    CHECK(env->tree->revision == revision + 1, "skip %s: a refit took the revision from %llu to %llu", m,
          (unsigned long long)revision, (unsigned long long)env->tree->revision);
    if (mode == MLOD_CUT_BASIC) {
        skip_all_changed(env, cut, views, p, m, "after a refit to the same positions");
    } else {
        CHECK(skip_settle(env, cut, env->tree, views, p) > 0, "skip %s: update", m);
        snprintf(what, sizeof what, "skip %s, after a refit to the same positions", m);
        skip_reference(env, env->tree, views, p.epsilon, cut, what);
        skip_copy_take(&before, cut);
        CHECK(mlod_refit_mesh(env->tree, rest, NULL, NULL) == MLOD_OK, "skip %s: refit", m);
        mask = skip_update(cut, env->tree, views, &p);
        CHECK(mask == 0, "skip %s, a second refit to the same positions: views 0x%x evaluated, expected none", m,
              mask);
        CHECK(skip_copy_differs(&before, cut) == 0, "skip %s, a second refit to the same positions: %u lists changed",
              m, skip_copy_differs(&before, cut));
        env->tree->revision++;
        skip_all_changed(env, cut, views, p, m, "after a write the tree did not record");
        CHECK(mlod_refit_mesh(env->tree, rest, NULL, NULL) == MLOD_OK, "skip %s: refit", m);
        skip_all_changed(env, cut, views, p, m, "after the refit that follows a write the tree did not record");
    }

    /* 5. another epsilon, then the same again */
    p.epsilon = 2.5f;
    skip_all_changed(env, cut, views, p, m, "epsilon 1.5 -> 2.5");
    mask = skip_update(cut, env->tree, views, &p);
    CHECK(mask == 0, "skip %s, epsilon 2.5 twice: views 0x%x evaluated", m, mask);

    /* 6. a failed update (a bad view) leaves what the cut knows as it was */
    memcpy(bad, views, sizeof bad);
    bad[4].up[0] = bad[4].forward[0], bad[4].up[1] = bad[4].forward[1], bad[4].up[2] = bad[4].forward[2];
    CHECK(mlod_cut_update(cut, env->tree, bad, &p, NULL) == MLOD_ERROR_BAD_VIEW, "skip %s: a bad view is refused", m);
    mask = skip_update(cut, env->tree, views, &p);
    CHECK(mask == 0, "skip %s, after a failed update: views 0x%x evaluated", m, mask);

    /* 7. mlod_cut_reset */
    mlod_cut_reset(cut);
    CHECK(mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK, "skip %s: update", m);
    mask = skip_evaluated(cut);
    CHECK(mask == all, "skip %s, after mlod_cut_reset: views 0x%x evaluated, expected all", m, mask);
    CHECK(skip_settle(env, cut, env->tree, views, p) > 0, "skip %s: update", m);

    /* 8. another tree: the same content and revision in another object,
       another node count, and back */
    mlod_refit_mesh(twin, rest, NULL, NULL);
    twin->revision = env->tree->revision; /* as if a user wrote it: only the address tells them apart */
    {
        mlod_tree *trees[3];
        const char *tree_names[3] = {"an identical tree", "a tree of another node count", "the first tree again"};
        int k;
        trees[0] = twin;
        trees[1] = other;
        trees[2] = env->tree;
        for (k = 0; k < 3; k++) {
            CHECK(mlod_cut_update(cut, trees[k], views, &p, NULL) == MLOD_OK, "skip %s: update", m);
            mask = skip_evaluated(cut);
            CHECK(mask == all, "skip %s, %s: views 0x%x evaluated, expected all", m, tree_names[k], mask);
            CHECK(skip_settle(env, cut, trees[k], views, p) > 0, "skip %s: update", m);
            snprintf(what, sizeof what, "skip %s, %s", m, tree_names[k]);
            skip_reference(env, trees[k], views, p.epsilon, cut, what);
        }
    }
    skip_copy_free(&before);
    mlod_cut_destroy(cut);
}

/* Rest positions, and those of the vertices within `radius` of `centre`
   moved by `offset`, into out. */
static void skip_move_region(const scene_mesh *s, const float *centre, float radius, const float *offset, float *out)
{
    uint32_t i;
    int k;
    for (i = 0; i < s->vertex_count; i++) {
        const float *q = s->positions + 3 * (size_t)i;
        float d2 = 0.0f;
        for (k = 0; k < 3; k++) d2 += (q[k] - centre[k]) * (q[k] - centre[k]);
        for (k = 0; k < 3; k++) out[3 * (size_t)i + k] = q[k] + (d2 <= radius * radius ? offset[k] : 0.0f);
    }
}

/* Skipping unchanged nodes: with the views unchanged and the tree
   refitted, an incremental or lazy update evaluates only the entries
   whose node or parent a refit changed.  The torus with one region of it
   moved at a time (from a single vertex to a third of it), frame after
   frame: every update's lists equal, entry for entry, those of the same
   update of a twin tree that lost its record of changes (its revision
   counted up by hand: every entry evaluated), each view evaluates no more
   nodes than the twin's, fewer in all, and the cuts are the reference's.
   With and without a pool of threads. */
static void skip_nodes(skip_env *env, mlod_tree *twin, const scene_mesh *s, const mlod_view *views)
{
    static const float radii[4] = {0.0f, 0.25f, 0.6f, 1.0f};
    float *moved = (float *)malloc(sizeof(float) * 3 * s->vertex_count);
    mlod_pool *pool = NULL;
    mlod_parallel hook;
    mlod_mesh mesh = tu_mesh(s);
    uint64_t rng = 77;
    int mode, threaded;
    memset(&hook, 0, sizeof hook);
#ifdef MANYLODS_PTHREADS
    pool = mlod_pool_create(2);
    if (pool) hook = mlod_pool_parallel(pool);
#endif
    for (threaded = 0; threaded < 2; threaded++)
        for (mode = 0; mode < 3; mode++) {
            mlod_cut_params p = params(mode ? MLOD_CUT_LAZY : MLOD_CUT_INCREMENTAL, 1.5f, mode == 2 ? 2u : 1u,
                                       threaded && pool ? &hook : NULL);
            const char *m = mode == 0 ? "incremental" : mode == 1 ? "lazy q=1" : "lazy q=2";
            mlod_cut *a = NULL, *b = NULL;
            uint64_t evaluated[2] = {0, 0};
            uint32_t frame, v, differ = 0, more = 0;
            char what[160], first[160] = "";
            if (threaded && !pool) continue;
            CHECK(mlod_cut_create(SKIP_NV, NULL, &a, NULL) == MLOD_OK &&
                      mlod_cut_create(SKIP_NV, NULL, &b, NULL) == MLOD_OK,
                  "skip nodes: create");
            mesh.positions = s->positions;
            CHECK(mlod_refit_mesh(env->tree, &mesh, NULL, NULL) == MLOD_OK &&
                      mlod_refit_mesh(twin, &mesh, NULL, NULL) == MLOD_OK,
                  "skip nodes: refit");
            CHECK(skip_settle(env, a, env->tree, views, p) > 0 && skip_settle(env, b, twin, views, p) > 0,
                  "skip nodes: first updates");
            for (frame = 0; frame < 12; frame++) {
                const float *centre = s->positions + 3 * (size_t)(scene_rng_next(&rng) % s->vertex_count);
                float offset[3];
                int k;
                for (k = 0; k < 3; k++) offset[k] = (float)(0.15 * (scene_rng_double(&rng) - 0.5));
                skip_move_region(s, centre, radii[frame % 4], offset, moved);
                mesh.positions = moved;
                CHECK(mlod_refit_mesh(env->tree, &mesh, NULL, NULL) == MLOD_OK &&
                          mlod_refit_mesh(twin, &mesh, NULL, NULL) == MLOD_OK,
                      "skip nodes: refit");
                twin->revision++; /* as if written otherwise: the twin's record of changes is lost */
                CHECK(mlod_cut_update(a, env->tree, views, &p, NULL) == MLOD_OK &&
                          mlod_cut_update(b, twin, views, &p, NULL) == MLOD_OK,
                      "skip nodes: update");
                for (v = 0; v < SKIP_NV; v++) {
                    mlod_cut_view ca = mlod_cut_get(a, v), cb = mlod_cut_get(b, v);
                    evaluated[0] += ca.evaluated;
                    evaluated[1] += cb.evaluated;
                    more += ca.evaluated > cb.evaluated;
                    if (!tu_same_cut(&ca, &cb) && !differ++)
                        snprintf(first, sizeof first, "frame %u, view %u (kind %d): %u and %u entries", frame, v,
                                 (int)views[v].kind, ca.count, cb.count);
                }
                if (mode == 0) {
                    snprintf(what, sizeof what, "skip nodes, %s%s, frame %u", m, threaded ? ", 2 threads" : "",
                             frame);
                    skip_reference(env, env->tree, views, p.epsilon, a, what);
                }
            }
            CHECK(differ == 0, "skip nodes, %s%s: %u view-updates differ from the twin's; first: %s", m,
                  threaded ? ", 2 threads" : "", differ, first);
            CHECK(more == 0 && evaluated[0] < evaluated[1],
                  "skip nodes, %s%s: %llu nodes evaluated against the twin's %llu (%u view-updates evaluated more)",
                  m, threaded ? ", 2 threads" : "", (unsigned long long)evaluated[0],
                  (unsigned long long)evaluated[1], more);
            if (mode >= 1) {
                CHECK(skip_settle(env, a, env->tree, views, p) > 0, "skip nodes: settle");
                snprintf(what, sizeof what, "skip nodes, %s%s, settled", m, threaded ? ", 2 threads" : "");
                skip_reference(env, env->tree, views, p.epsilon, a, what);
            }
            if (!threaded)
                printf("  skip nodes, %s: %llu nodes evaluated in 12 frames, %llu without the record of changes\n", m,
                       (unsigned long long)evaluated[0], (unsigned long long)evaluated[1]);
            mlod_cut_destroy(a);
            mlod_cut_destroy(b);
        }
    mesh.positions = s->positions; /* back to rest for what follows */
    CHECK(mlod_refit_mesh(env->tree, &mesh, NULL, NULL) == MLOD_OK, "skip nodes: refit");
    if (pool) mlod_pool_destroy(pool);
    free(moved);
}

/* A lazy cut that has not converged is not skipped: from the root, call
   after call with the same views, a view is evaluated exactly when it
   moved in the call before. */
static void skip_lazy_converging(skip_env *env, const mlod_view *views)
{
    mlod_cut_params p = params(MLOD_CUT_LAZY, 1.5f, 1, NULL);
    mlod_cut *cut = NULL;
    uint64_t moved[SKIP_NV];
    uint32_t v, call, kept = 0, skipped = 0, wrong = 0, converged = 0;
    char first[160] = "";
    CHECK(mlod_cut_create(SKIP_NV, NULL, &cut, NULL) == MLOD_OK &&
              mlod_cut_update(cut, env->tree, views, &p, NULL) == MLOD_OK,
          "skip lazy from the root: update");
    if (!cut) return;
    for (call = 2; call <= env->bound && !converged; call++) {
        for (v = 0; v < SKIP_NV; v++) moved[v] = mlod_cut_get(cut, v).steps;
        mlod_cut_update(cut, env->tree, views, &p, NULL);
        for (v = 0; v < SKIP_NV; v++) {
            int evaluated = mlod_cut_get(cut, v).evaluated > 0;
            kept += moved[v] != 0;
            skipped += moved[v] == 0;
            if (evaluated != (moved[v] != 0) && !wrong++)
                snprintf(first, sizeof first, "call %u, view %u: %llu moves in the call before, evaluated %llu", call,
                         v, (unsigned long long)moved[v], (unsigned long long)mlod_cut_get(cut, v).evaluated);
        }
        if (skip_steps(cut) == 0) converged = call;
    }
    CHECK(wrong == 0,
          "skip lazy from the root: %u view-calls evaluated where they should not or the reverse; first: %s", wrong,
          first);
    CHECK(converged != 0 && kept > SKIP_NV && skipped > SKIP_NV,
          "skip lazy from the root: converged after %u calls, %u view-calls still moving, %u settled", converged, kept,
          skipped);
    skip_reference(env, env->tree, views, p.epsilon, cut, "skip lazy from the root, converged");
    printf("  skip: lazy from the root converged after %u calls (%u view-calls moving, %u skipped)\n", converged, kept,
           skipped);
    mlod_cut_destroy(cut);
}

/* Skipping does not depend on the thread count or task order: a sequence of
   updates in every mode, some views changing, gives the same lists and the
   same evaluated and steps counts under every hook. */
static void skip_threads(const skip_env *env, const mlod_view *base)
{
    mlod_pool *pools[3];
    mlod_parallel hooks[6];
    mlod_cut *cuts[6];
    mlod_view views[SKIP_NV];
    uint32_t h, k, v, mismatches[6] = {0, 0, 0, 0, 0, 0};
    memset(hooks, 0, sizeof hooks);
    tu_hooks(pools, hooks + 1);
    for (h = 0; h < 6; h++) mlod_cut_create(SKIP_NV, NULL, &cuts[h], NULL);
    memcpy(views, base, sizeof views);
    for (k = 0; k < 9; k++) {
        mlod_cut_mode mode = (mlod_cut_mode)(k / 3);
        if (k % 3 == 1) views[k % SKIP_NV].position[1] += 0.03f; /* one view moves, the others stay */
        for (h = 0; h < 6; h++) {
            mlod_cut_params p = params(mode, 1.5f, 1, h == 0 ? NULL : &hooks[h]);
            if (h > 0 && h < 4 && !pools[h - 1]) continue;
            CHECK(mlod_cut_update(cuts[h], env->tree, views, &p, NULL) == MLOD_OK, "skip threads: update");
            for (v = 0; h > 0 && v < SKIP_NV; v++) {
                mlod_cut_view a = mlod_cut_get(cuts[0], v), b = mlod_cut_get(cuts[h], v);
                mismatches[h] += !tu_same_cut(&a, &b) || a.evaluated != b.evaluated || a.steps != b.steps;
            }
        }
    }
    for (h = 1; h < 6; h++)
        CHECK(mismatches[h] == 0, "skip threads: hook %u differs from no hook in %u view-updates", h, mismatches[h]);
    for (h = 0; h < 6; h++) mlod_cut_destroy(cuts[h]);
    for (h = 0; h < 3; h++) mlod_pool_destroy(pools[h]);
}

/* A tree destroyed and built again (malloc often hands back the same
   address) is another tree to the cut: every view is evaluated. */
static void skip_rebuilt(const scene_mesh *s, const mlod_view *views)
{
    mlod_cut_params p;
    mlod_cut *cut = NULL;
    mlod_tree *tree = tu_build(s, 2500, 3, MLOD_ATTR_CONE);
    const void *first_address = tree;
    uint64_t first_revision = tree ? tree->revision : 0;
    int round;
    memset(&p, 0, sizeof p);
    p.mode = MLOD_CUT_INCREMENTAL;
    p.epsilon = 2.0f;
    CHECK(tree && mlod_cut_create(SKIP_NV, NULL, &cut, NULL) == MLOD_OK, "skip, rebuilt tree: set-up");
    if (!tree || !cut) {
        mlod_tree_destroy(tree);
        return;
    }
    for (round = 0; round < 3; round++) { /* the same tree twice, then rebuilt */
        uint32_t mask;
        CHECK(mlod_cut_update(cut, tree, views, &p, NULL) == MLOD_OK, "skip, rebuilt tree: update");
        mask = skip_evaluated(cut);
        CHECK(mask == (round == 1 ? 0u : (1u << SKIP_NV) - 1), "skip, rebuilt tree, round %d (%s address): views 0x%x evaluated",
              round, (const void *)tree == first_address ? "the same" : "another", mask);
        if (round == 1) {
            mlod_tree_destroy(tree);
            tree = tu_build(s, 2500, 3, MLOD_ATTR_CONE);
            if (!tree) break;
            CHECK(tree->revision != first_revision, "skip, rebuilt tree: the revision %llx came back",
                  (unsigned long long)first_revision);
        }
    }
    mlod_cut_destroy(cut);
    mlod_tree_destroy(tree);
}

static void test_skip(void)
{
    scene_mesh s;
    mlod_mesh rest;
    mlod_tree *twin, *other;
    mlod_view views[SKIP_NV];
    skip_env env;
    uint64_t rng = 404;
    double c[3] = {0, 0, 0};
    uint32_t v, mode;
    scene_torus(&s, 1.0f, 0.35f, 24, 12);
    rest = tu_mesh(&s);
    env.tree = tu_build(&s, 3000, 9, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
    twin = tu_build(&s, 3000, 9, MLOD_ATTR_CONE | MLOD_ATTR_REFIT);
    other = tu_build(&s, 2000, 9, MLOD_ATTR_CONE);
    CHECK(env.tree && twin && other, "skip: builds");
    if (!env.tree || !twin || !other) return;
    /* every tree starts from its own revision, a multiple of 2^32 */
    CHECK(env.tree->revision % 4294967296u == 0 && twin->revision % 4294967296u == 0 &&
              other->revision % 4294967296u == 0 && env.tree->revision != twin->revision &&
              twin->revision != other->revision && env.tree->revision != other->revision,
          "skip: new trees start from revisions %llx, %llx, %llx", (unsigned long long)env.tree->revision,
          (unsigned long long)twin->revision, (unsigned long long)other->revision);
    tu_layout_init(&env.L, env.tree->leaf_count);
    tu_layout_init(&env.L_other, other->leaf_count);
    ws_init(&env.w, env.tree->node_count);
    env.bound = 2 * env.L.max_depth + 2;
    for (v = 0; v < SKIP_NV; v++) {
        views[v] = tu_random_view(&rng, (mlod_view_kind)(v % 5), c, 1.4);
        views[v].width = views[v].kind == MLOD_VIEW_CUBE ? 48 : 32;
        views[v].height = views[v].kind == MLOD_VIEW_CUBE ? 32 : 24;
    }
    {
        /* a failed refit leaves the revision as it was */
        mlod_mesh wrong = rest;
        uint64_t revision = env.tree->revision;
        wrong.index_count -= 3; /* one triangle fewer than at build */
        CHECK(mlod_refit_mesh(env.tree, &wrong, NULL, NULL) == MLOD_ERROR_MISMATCH && env.tree->revision == revision,
              "skip: a refused refit changed the revision to %llu", (unsigned long long)env.tree->revision);
    }
    for (mode = 0; mode < 4; mode++) /* basic, incremental, lazy with 1 and 3 steps */
        skip_mode(&env, twin, other, &rest, views, (mlod_cut_mode)(mode < 3 ? mode : 2), mode < 3 ? 1 : 3);
    skip_nodes(&env, twin, &s, views);
    skip_lazy_converging(&env, views);
    skip_threads(&env, views);
    skip_rebuilt(&s, views);
    ws_free(&env.w);
    tu_layout_free(&env.L);
    tu_layout_free(&env.L_other);
    mlod_tree_destroy(env.tree);
    mlod_tree_destroy(twin);
    mlod_tree_destroy(other);
    scene_free(&s);
}

/* --------------------------------------------------------------- threads */

static pthread_t main_thread;
static unsigned long foreign_allocations;

static void *thread_checked_alloc(void *user, size_t bytes)
{
    if (!pthread_equal(pthread_self(), main_thread)) foreign_allocations++;
    return tu_counter_alloc(user, bytes);
}

static void thread_checked_free(void *user, void *p)
{
    if (!pthread_equal(pthread_self(), main_thread)) foreign_allocations++;
    tu_counter_free(user, p);
}

static void test_threads(void)
{
    enum { NV = 40, CONFIGS = 6, FRAMES = 4 };
    scene_mesh s;
    mlod_tree *tree;
    mlod_pool *pool1 = mlod_pool_create(1), *pool2 = mlod_pool_create(2), *pool4 = mlod_pool_create(4);
    mlod_parallel hooks[CONFIGS];
    mlod_view base[NV], views[NV];
    mlod_cut *cuts[CONFIGS];
    tu_counter counter;
    mlod_allocator alloc;
    uint64_t rng = 11;
    double c[3] = {0, 0, 0};
    uint32_t v, k, cfg, mode, f, median_count, big, sizes[NV];
    static const char *names[CONFIGS] = {"no hook", "pool of 1", "pool of 2", "pool of 4", "reverse order", "odd then even"};
    static const char *modes[3] = {"basic", "incremental", "lazy"};
    tu_layout L;
    workspace w;
    tally t;
    memset(&counter, 0, sizeof counter);
    main_thread = pthread_self();
    alloc.alloc = thread_checked_alloc;
    alloc.free = thread_checked_free;
    alloc.user = &counter;
    CHECK(pool1 && pool2 && pool4, "threads: pools");
    if (!pool1 || !pool2 || !pool4) return;
    memset(hooks, 0, sizeof hooks);
    hooks[1] = mlod_pool_parallel(pool1);
    hooks[2] = mlod_pool_parallel(pool2);
    hooks[3] = mlod_pool_parallel(pool4);
    hooks[4].run = tu_run_reverse;
    hooks[5].run = tu_run_odd_even;
    scene_uv_sphere(&s, 1.0f, 24, 48);
    tree = tu_build(&s, 20000, 1, MLOD_ATTR_CONE);
    CHECK(tree != NULL, "threads: build");
    if (!tree) return;
    for (v = 0; v + 1 < NV; v++) {
        double dir[3], eye[3];
        tu_random_unit(&rng, dir);
        for (k = 0; k < 3; k++) eye[k] = dir[k] * (3 + 5 * scene_rng_double(&rng));
        base[v] = tu_view((mlod_view_kind)(v % 5));
        tu_look(&rng, base + v, eye, c);
        base[v].half_width = base[v].half_height = 1.2f;
        base[v].near_plane = base[v].kind == MLOD_VIEW_ORTHOGRAPHIC ? -20.0f : 0.01f;
        base[v].width = base[v].kind == MLOD_VIEW_CUBE ? 12 : 8; /* a cube map: six 4 x 4 faces */
        base[v].height = 8;
        base[v].flags = v % 3 == 0 ? MLOD_VIEW_CULL_BACKFACES : 0;
    }
    {
        /* one eye 0.02 above the surface, a wide 512 x 512 tile */
        double eye[3] = {0, 0, 1.02}, target[3] = {0.3, 0, 0.9};
        base[NV - 1] = tu_view(MLOD_VIEW_PERSPECTIVE);
        tu_look(&rng, base + NV - 1, eye, target);
        base[NV - 1].width = base[NV - 1].height = 512;
        base[NV - 1].fov_y = 2.0f;
        base[NV - 1].near_plane = 1e-3f;
    }
    for (cfg = 0; cfg < CONFIGS; cfg++) mlod_cut_create(NV, &alloc, &cuts[cfg], NULL);
    for (mode = 0; mode < 3; mode++) {
        uint32_t mismatches[CONFIGS] = {0};
        for (cfg = 0; cfg < CONFIGS; cfg++) mlod_cut_reset(cuts[cfg]);
        for (f = 0; f < (mode == 0 ? 1u : (uint32_t)FRAMES); f++) {
            for (v = 0; v < NV; v++) {
                double fw[3] = {base[v].forward[0], base[v].forward[1], base[v].forward[2]}, ax[3] = {0.3, 0.8, 0.5};
                tu_normalize3(ax);
                views[v] = base[v];
                rotate(fw, ax, f * 3.0 * TU_PI / 180);
                if (v != NV - 1) tu_set3f(views[v].forward, fw);
                if (v != NV - 1) {
                    double up[3] = {base[v].up[0], base[v].up[1], base[v].up[2]};
                    rotate(up, ax, f * 3.0 * TU_PI / 180);
                    tu_set3f(views[v].up, up);
                }
            }
            for (cfg = 0; cfg < CONFIGS; cfg++) {
                mlod_cut_params p = params((mlod_cut_mode)mode, 1.0f, 1, cfg ? &hooks[cfg] : NULL);
                CHECK(mlod_cut_update(cuts[cfg], tree, views, &p, NULL) == MLOD_OK, "threads %s %s frame %u: update",
                      modes[mode], names[cfg], f);
                if (cfg == 0) continue;
                for (v = 0; v < NV; v++) {
                    mlod_cut_view a = mlod_cut_get(cuts[0], v), b = mlod_cut_get(cuts[cfg], v);
                    mismatches[cfg] += !tu_same_cut(&a, &b);
                }
            }
        }
        for (cfg = 1; cfg < CONFIGS; cfg++)
            CHECK(mismatches[cfg] == 0, "threads %s: %s differs from no hook in %u view-frames", modes[mode], names[cfg],
                  mismatches[cfg]);
    }
    /* the big view is >= 100x the median, and basic agrees with the reference */
    {
        mlod_cut_params p = params(MLOD_CUT_BASIC, 1.0f, 1, &hooks[2]);
        uint32_t sorted[NV - 1];
        mlod_cut_update(cuts[2], tree, base, &p, NULL);
        for (v = 0; v < NV; v++) sizes[v] = mlod_cut_get(cuts[2], v).count;
        memcpy(sorted, sizes, sizeof sorted);
        for (v = 0; v < NV - 1; v++)
            for (k = v + 1; k < NV - 1; k++)
                if (sorted[k] < sorted[v]) {
                    uint32_t tmp = sorted[k];
                    sorted[k] = sorted[v];
                    sorted[v] = tmp;
                }
        median_count = sorted[(NV - 1) / 2];
        big = sizes[NV - 1];
        CHECK(big >= 100 * median_count, "threads: the close view's cut has %u nodes, median of the others %u (< 100x)", big,
              median_count);
        printf("  threads: close view %u nodes, median view %u nodes\n", big, median_count);
        tu_layout_init(&L, tree->leaf_count);
        ws_init(&w, tree->node_count);
        memset(&t, 0, sizeof t);
        check_against_reference(tree, &L, base, NV - 4, 4, 1.0f, cuts[2], &w, &t);
        tally_report(&t, "threads: the last 4 views, basic with a pool of 2");
        ws_free(&w);
        tu_layout_free(&L);
    }
    CHECK(foreign_allocations == 0, "threads: the allocator was called %lu times from another thread", foreign_allocations);
    for (cfg = 0; cfg < CONFIGS; cfg++) mlod_cut_destroy(cuts[cfg]);
    CHECK(counter.live_blocks == 0, "threads: %lu blocks leaked by the cuts", counter.live_blocks);
    mlod_pool_destroy(pool1);
    mlod_pool_destroy(pool2);
    mlod_pool_destroy(pool4);
    mlod_tree_destroy(tree);
    scene_free(&s);
}

/* A parallel hook that runs the tasks in order on the calling thread and
   keeps the largest task count of one call. */
static void run_counting(void *user, uint32_t count, mlod_task_fn *task, void *context)
{
    uint32_t *most = (uint32_t *)user, i;
    if (count > *most) *most = count;
    for (i = 0; i < count; i++) task(context, i);
}

/* One large view alone, updated from frame to frame in basic mode: its
   first update from nothing, then from its previous cut as the eye
   glides, closes in (the previous cut too small below the entries it
   gets nearer to), backs off, and at a coarser epsilon.  Every cut equals the reference and
   those of a pool of 2 threads; a cut of tens of thousands of nodes is
   spread over many tasks in every update (the root's split alone was one
   task when its room came from the previous cut). */
static void test_one_view(void)
{
    enum { FRAMES = 10 };
    static const double distance[FRAMES] = {1.6, 1.6, 1.58, 1.2, 1.21, 2.5, 2.5, 2.5, 2.4, 1.9};
    static const float eps[FRAMES] = {1, 1, 1, 1, 1, 1, 1, 4, 4, 4}; /* coarse cuts: fewer nodes than leaves */
    mlod_tree *tree = sphere_points_tree(60000, 41, 0.003);
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel counting, pooled;
    mlod_cut *cut = NULL, *cut2 = NULL;
    uint32_t most = 0, f, smallest_spread = (uint32_t)-1, largest_cut = 0, previous = 0, spread = 0;
    uint64_t rng = 5;
    tu_layout L;
    workspace w;
    tally t;
    CHECK(tree && pool, "one view: tree and pool");
    if (!tree || !pool) {
        mlod_tree_destroy(tree);
        mlod_pool_destroy(pool);
        return;
    }
    counting.run = run_counting;
    counting.user = &most;
    pooled = mlod_pool_parallel(pool);
    tu_layout_init(&L, tree->leaf_count);
    ws_init(&w, tree->node_count);
    memset(&t, 0, sizeof t);
    CHECK(mlod_cut_create(1, NULL, &cut, NULL) == MLOD_OK && mlod_cut_create(1, NULL, &cut2, NULL) == MLOD_OK,
          "one view: create");
    for (f = 0; cut && cut2 && f < FRAMES; f++) {
        double eye[3] = {0.2 * f / FRAMES, 0.1, distance[f]}, target[3] = {0, 0, 0};
        mlod_view view = tu_view(MLOD_VIEW_PERSPECTIVE);
        mlod_cut_params p = params(MLOD_CUT_BASIC, eps[f], 1, &counting);
        mlod_cut_params p2 = params(MLOD_CUT_BASIC, eps[f], 1, &pooled);
        mlod_cut_view a, b;
        tu_look(&rng, &view, eye, target);
        view.width = view.height = 1024;
        view.near_plane = 0.05f;
        view.flags = f % 2 ? MLOD_VIEW_CULL_BACKFACES : 0;
        most = 0;
        CHECK(mlod_cut_update(cut, tree, &view, &p, NULL) == MLOD_OK &&
                  mlod_cut_update(cut2, tree, &view, &p2, NULL) == MLOD_OK,
              "one view, frame %u: update", f);
        a = mlod_cut_get(cut, 0);
        b = mlod_cut_get(cut2, 0);
        CHECK(tu_same_cut(&a, &b), "one view, frame %u: a pool of 2 gives another cut", f);
        check_against_reference(tree, &L, &view, 0, 1, eps[f], cut, &w, &t);
        if (a.count > largest_cut) largest_cut = a.count;
        /* a large cut is spread over tasks: from nothing (its first split
           stops at a frontier of MLOD__SEGMENT_GROWTH nodes alike in
           size), and from a previous cut whose room (a quarter more) is
           wide (see mlod__root_room) */
        if (a.count >= 4 * MLOD__SEGMENT_GROWTH &&
            (f == 0 || previous + previous / 4 + MLOD__MIN_SHARE > MLOD__SEGMENT_GROWTH)) {
            CHECK(most >= 4, "one view, frame %u: a cut of %u nodes (%u before), its update's largest parallel call %u "
                  "tasks", f, a.count, previous, most);
            if (most < smallest_spread) smallest_spread = most;
            spread++;
        }
        previous = a.count;
    }
    tally_report(&t, "one view");
    CHECK(spread >= 3, "one view: only %u updates of a large cut (largest %u nodes)", spread, largest_cut);
    printf("  one view: cuts up to %u nodes; %u updates of large cuts, each with a call of %u tasks or more\n",
           largest_cut, spread, smallest_spread);
    mlod_cut_destroy(cut);
    mlod_cut_destroy(cut2);
    ws_free(&w);
    tu_layout_free(&L);
    mlod_pool_destroy(pool);
    mlod_tree_destroy(tree);
}

/* test_cut [GROUP...]: every group, or those named (the compile matrix
   runs the cut and float filter groups under qemu, where the whole program
   takes minutes). */
/* mlod_view_filter_of, the float filter as manylods_vk.h uploads it: the
   same values as the cut's own (mlod__fast_prepare) for every kind of
   view, and refusals. */
static void test_filter_export(void)
{
    uint64_t rng = 91;
    double c[3] = {0, 0, 0};
    unsigned views = 0, wrong = 0, with_filter = 0;
    int i, s, j, k;
    float out[MLOD_FILTER_FLOATS];
    mlod_error e;
    mlod_view bad;
    for (i = 0; i < 200; i++) {
        mlod_view v = tu_random_view(&rng, (mlod_view_kind)(i % 5), c, 1.4);
        float eps = i % 7 == 0 ? INFINITY : (float)(0.25 + 4.0 * scene_rng_double(&rng));
        mlod__pview pv;
        const float *o;
        int bad_here = 0;
        if (i % 3 == 0) v.position[0] += 0.1f; /* eyes whose floats are not small */
        if (mlod_view_filter_of(&v, eps, out, &e) != MLOD_OK || mlod__view_prepare(&v, &pv, NULL) != MLOD_OK) {
            CHECK(0, "filter export: view %d refused: %s", i, e.message);
            continue;
        }
        mlod__fast_prepare(&pv, eps);
        views++;
        with_filter += (unsigned)pv.fast.ok;
        bad_here |= out[MLOD_FILTER_OK] != (float)pv.fast.ok;
        if (pv.fast.ok) {
            bad_here |= out[MLOD_FILTER_BACKFACES] != (float)pv.fast.backfaces ||
                        out[MLOD_FILTER_ORTHO] != (float)pv.fast.ortho ||
                        out[MLOD_FILTER_SUB_COUNT] != (float)pv.fast.sub_count ||
                        out[MLOD_FILTER_FLOAT_EYE] != (float)pv.fast.float_eye;
            for (k = 0; k < 3; k++) bad_here |= out[MLOD_FILTER_EYE + k] != pv.fast.eye_f[k];
            for (s = 0; s < pv.fast.sub_count; s++) {
                const mlod__fsub *fs = &pv.fast.subs[s];
                o = out + MLOD_FILTER_SUBS + s * MLOD_FILTER_SUB_STRIDE;
                bad_here |= o[MLOD_FILTER_S_KIND] != (float)fs->kind ||
                            o[MLOD_FILTER_S_PLANE_COUNT] != (float)fs->plane_count ||
                            o[MLOD_FILTER_S_VALID] != fs->valid || o[MLOD_FILTER_S_INVALID] != fs->invalid;
                for (k = 0; k < 3; k++) bad_here |= o[MLOD_FILTER_S_W + k] != fs->w[k];
                for (j = 0; j < fs->plane_count; j++) {
                    const float *plane = o + MLOD_FILTER_S_PLANES + j * MLOD_FILTER_PLANE_STRIDE;
                    for (k = 0; k < 5; k++) bad_here |= plane[MLOD_FILTER_P_N + k] != fs->planes[j][k];
                    bad_here |= plane[MLOD_FILTER_P_SLOPE] != fs->slope[j] || plane[MLOD_FILTER_P_ERR] != fs->err[j];
                }
            }
        }
        wrong += (unsigned)bad_here;
    }
    CHECK(wrong == 0 && views == 200 && with_filter > 100,
          "filter export: %u of %u views differ from the cut's filter (%u with one)", wrong, views, with_filter);
    bad = tu_random_view(&rng, MLOD_VIEW_PERSPECTIVE, c, 1.4);
    CHECK(mlod_view_filter_of(&bad, 1.0f, NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "filter export: NULL out refused");
    CHECK(mlod_view_filter_of(&bad, 0.0f, out, &e) == MLOD_ERROR_INVALID_ARGUMENT &&
              mlod_view_filter_of(&bad, NAN, out, &e) == MLOD_ERROR_INVALID_ARGUMENT,
          "filter export: epsilon 0 and NaN refused");
    bad.fov_y = 4.0f;
    CHECK(mlod_view_filter_of(&bad, 1.0f, out, &e) == MLOD_ERROR_BAD_VIEW, "filter export: a bad view refused (%s)",
          e.message);
}

/* The planning's shortcut over 8 statuses at a time against the plain
   byte-by-byte rule (mlod__to_split): the word test for every word of
   statuses with at most two bytes to split, at every position, and whole
   segments' lengths and split counts against a byte loop. */

/* Whether node a is node m or above it, by m's chain of parents. */
static int plain_at_or_above(uint32_t a, uint32_t m)
{
    while (m > a) m = (m - 1) / 2;
    return m == a;
}

static unsigned plain_rooms_below_leaves; /* rooms from a previous cut, below the leaves' bound */

/* A split's room by its definition: the previous cut's entries below
   the node (1 where one of them holds it), a quarter more and
   MLOD__MIN_SHARE, or the unit; at most the leaves below. */
static size_t plain_split_room(const uint32_t *prev, size_t prev_count, size_t unit, uint32_t node, uint32_t n)
{
    size_t room = unit, leaves = tu_leaves_below(node, n), held = 0, k;
    if (prev) {
        for (k = 0; k < prev_count; k++) held += (size_t)plain_at_or_above(node, prev[k]);
        if (held == 0) held = 1;
        room = held + held / 4 + MLOD__MIN_SHARE;
    }
    plain_rooms_below_leaves += (unsigned)(prev && room < leaves);
    return room < leaves ? room : leaves;
}

/* mlod__segment_length by a byte loop: entries to split by the rule, the
   segment closed at MLOD__SEGMENT_INPUT entries or once its rooms reach
   MLOD__SEGMENT_GROWTH. */
static uint32_t plain_segment_length(const uint32_t *nodes, const uint8_t *status, size_t at, size_t end, int lazy,
                                     int trust, const uint32_t *prev, size_t prev_count, size_t unit, uint32_t n,
                                     size_t *grow)
{
    uint32_t count = 0;
    size_t g = 0;
    while (at + count < end && count < MLOD__SEGMENT_INPUT && g < MLOD__SEGMENT_GROWTH) {
        if (mlod__to_split(status[at + count], lazy, trust))
            g += plain_split_room(prev, prev_count, unit, nodes[at + count], n);
        count++;
    }
    *grow = g;
    return count;
}

/* A random cut of the tree of n leaves below node, of at most `room`
   entries, in leaf order, appended to out. */
static void random_cut(uint64_t *rng, uint32_t node, uint32_t n, double split, uint32_t *out, size_t *count,
                       size_t room)
{
    if (node < n - 1 && room >= 2 && scene_rng_double(rng) < split) {
        random_cut(rng, 2 * node + 1, n, split, out, count, room / 2);
        random_cut(rng, 2 * node + 2, n, split, out, count, room - room / 2);
        return;
    }
    out[(*count)++] = node;
}

/* The runs of unchanged entries of a stamped view's list
   (mlod__unchanged_runs, mlod__all_unchanged) against the rule read entry
   by entry: an entry is unchanged when no refit of the last `age` changed
   its parent (the root entry: itself).  Random cuts of random trees, and
   records of changes in which each changed node marks every node above
   it, as a refit does: few, some or many nodes changed per revision. */
static void test_unchanged_runs(void)
{
    enum { LIST = 20000 };
    static uint32_t nodes[LIST], changes[LIST];
    static uint8_t flags[LIST];
    uint64_t rng = 91;
    unsigned i, windows = 0, wrong = 0, wrong_all = 0, runs_of_all = 0, mixed = 0;
    for (i = 0; i < 90; i++) {
        const double shares[3] = {0.0005, 0.01, 0.2};
        uint32_t n = 2u + (uint32_t)(scene_rng_double(&rng) * (LIST / 2 - 2)), x, r, now = 1000, age, w;
        size_t count = 0;
        mlod_tree tree;
        memset(&tree, 0, sizeof tree);
        tree.leaf_count = n;
        tree.node_count = 2 * n - 1;
        tree.changes = changes;
        tree.revision = now;
        for (x = 0; x < 2 * n - 1; x++) changes[x] = now - 10;
        for (r = now - 4; r <= now; r++) { /* five refits, each marking nodes and what lies above them */
            uint32_t seeds = 1u + (uint32_t)(shares[i % 3] * n), k;
            for (k = 0; k < seeds; k++) {
                x = (uint32_t)(scene_rng_double(&rng) * (2 * n - 1));
                for (;;) {
                    changes[x] = r;
                    if (x == 0) break;
                    x = (x - 1) / 2;
                }
            }
        }
        random_cut(&rng, 0, n, 0.8 + 0.2 * scene_rng_double(&rng), nodes, &count, LIST);
        age = 1u + i % 4;
        for (w = 0; w < 40; w++) { /* windows: the segments of a view's list */
            uint32_t at = (uint32_t)(scene_rng_double(&rng) * (double)count), len, k, all = 1;
            len = 1u + (uint32_t)(scene_rng_double(&rng) * (double)(count - at < 1500 ? count - at : 1500));
            if (at + len > count) len = (uint32_t)count - at;
            mlod__unchanged_runs(&tree, age, nodes + at, len, flags);
            for (k = 0; k < len; k++) {
                uint32_t e = nodes[at + k];
                uint8_t want = (uint8_t)(now - changes[e > 0 ? (e - 1) / 2 : 0] >= age);
                wrong += flags[k] != want;
                all &= want;
            }
            wrong_all += (unsigned)(mlod__all_unchanged(&tree, age, nodes + at, len) != (int)all);
            runs_of_all += all && len > 1;
            mixed += !all;
            windows++;
        }
    }
    CHECK(wrong == 0 && wrong_all == 0 && runs_of_all > 100 && mixed > 100,
          "unchanged runs: %u entries and %u of %u windows differ from the entry-by-entry rule (%u windows wholly "
          "unchanged, %u mixed)",
          wrong, wrong_all, windows, runs_of_all, mixed);
}

static void test_planning(void)
{
    static const uint8_t values[] = {MLOD__PENDING,
                                     MLOD_STATUS_DRAWN,
                                     MLOD_STATUS_CULLED,
                                     MLOD_STATUS_OVERSIZE,
                                     MLOD_STATUS_COARSE,
                                     MLOD_STATUS_DRAWN | MLOD__PARENT_INVALID,
                                     MLOD_STATUS_COARSE | MLOD__PARENT_INVALID,
                                     0xff};
    enum { LIST = 20000 };
    static uint8_t list[LIST + 8];
    static uint32_t cut_nodes[LIST], prev_nodes[LIST];
    uint64_t rng = 77;
    unsigned words = 0, wrong = 0, segments = 0, bad = 0;
    int trust, lazy, from_prev, i, j, k, a, b;
    for (trust = 0; trust < 2; trust++)
        for (i = 0; i < 8; i++)       /* the background value */
            for (j = 0; j < 8; j++)   /* one odd byte */
                for (k = 0; k < 8; k++) /* another */
                    for (a = 0; a < 8; a++)
                        for (b = 0; b < 8; b++) {
                            uint8_t w[8];
                            int want = 1, m;
                            memset(w, values[i], 8);
                            w[a] = values[j];
                            w[b] = values[k];
                            for (m = 0; m < 8; m++) want &= !mlod__to_split(w[m], 0, trust);
                            words++;
                            wrong += (unsigned)(mlod__none_to_split8(w, trust) != want);
                        }
    CHECK(wrong == 0, "planning: the 8-status test disagrees with the byte rule on %u of %u words", wrong, words);
    for (i = 0; i < 40; i++) {
        /* runs of statuses to split scattered thinly or thickly, over the
           entries of a random cut (its nodes give the rooms) and with rooms
           from another random cut of the same tree (a previous cut) */
        unsigned density = i % 2 ? 1u : 1u + (unsigned)(scene_rng_double(&rng) * 64);
        uint32_t n = 2u + (uint32_t)(scene_rng_double(&rng) * 60000);
        size_t at, end, cut_count = 0, prev_count = 0;
        size_t unit = 1u + (size_t)(scene_rng_double(&rng) * (i % 2 ? 100 : 9000));
        /* the cut: long (many segments), or coarse beside a fine previous
           cut (rooms below the leaves' bound) */
        size_t coarse = i % 2 ? 20u + (size_t)(scene_rng_double(&rng) * 2000) : LIST;
        random_cut(&rng, 0, n, 0.85 + 0.15 * scene_rng_double(&rng), cut_nodes, &cut_count, coarse);
        random_cut(&rng, 0, n, 0.8 + 0.2 * scene_rng_double(&rng), prev_nodes, &prev_count, LIST);
        end = cut_count - (size_t)(scene_rng_double(&rng) * (double)(cut_count < 100 ? cut_count : 100));
        for (at = 0; at < LIST + 8; at++)
            list[at] = (unsigned)(scene_rng_double(&rng) * density) == 0 ? values[(int)(scene_rng_double(&rng) * 8)]
                                                                 : values[1 + (int)(scene_rng_double(&rng) * 3)];
        for (lazy = 0; lazy < 2; lazy++)
            for (trust = 0; trust < 2; trust++)
                for (from_prev = 0; from_prev < 2; from_prev++) {
                    mlod__list in;
                    mlod__room_walk w;
                    memset(&in, 0, sizeof in);
                    in.status = list;
                    in.nodes = cut_nodes;
                    w.prev = from_prev ? prev_nodes : NULL;
                    w.prev_count = from_prev ? prev_count : 0;
                    w.cursor = 0;
                    w.unit = unit;
                    w.leaf_count = n;
                    w.deepest = mlod__depth_of(2 * (uint64_t)n - 2);
                    for (at = (size_t)(scene_rng_double(&rng) * 7); at < end;) {
                        size_t g1, g2;
                        uint32_t n1 = mlod__segment_length(&in, at, end, !lazy, trust, &w, &g1);
                        uint32_t n2 = plain_segment_length(cut_nodes, list, at, end, lazy, trust, w.prev, prev_count,
                                                           unit, n, &g2);
                        segments++;
                        bad += (unsigned)(n1 != n2 || g1 != g2);
                        if (n2 == 0) break;
                        at += n2;
                    }
                }
    }
    CHECK(bad == 0 && segments > 1000 && plain_rooms_below_leaves > 1000,
          "planning: %u of %u segments differ from the byte loop (%u rooms from a previous cut below the leaves' "
          "bound)", bad, segments, plain_rooms_below_leaves);
}

int main(int argc, char **argv)
{
    int rc;
    test_groups_begin(argc, argv);
    TEST_GROUP("random_trees", test_random_trees());
    TEST_GROUP("hand_made", test_hand_made());
    TEST_GROUP("zero_radius", test_zero_radius());
    TEST_GROUP("restart", test_restart());
    TEST_GROUP("shrinking", test_shrinking());
    TEST_GROUP("criterion_reference", test_criterion_reference());
    TEST_GROUP("backface_boundary", test_backface_boundary());
    TEST_GROUP("fast_filter", test_fast_filter());
    TEST_GROUP("fast_conditioning", test_fast_conditioning());
    TEST_GROUP("monotonicity", test_monotonicity());
    TEST_GROUP("motion", test_motion());
    TEST_GROUP("budget", test_budget());
    TEST_GROUP("threads", test_threads());
    TEST_GROUP("one_view", test_one_view());
    TEST_GROUP("skip", test_skip());
    TEST_GROUP("planning", test_planning());
    TEST_GROUP("unchanged runs", test_unchanged_runs());
    TEST_GROUP("filter_export", test_filter_export());
    test_groups_end();
    rc = test_finish();
    fflush(stdout); /* keep the result line even if a sanitizer reports at exit */
    return rc;
}
