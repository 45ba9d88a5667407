/* bench/proof_calibration.c - how many cut entries could an incremental
   update prove unchanged, frame after frame, from bounds on how far nodes
   and views moved?  A measurement for issue 53's "proven skipping", not part
   of the build or of the library.

   Build by hand (from the repository root):
     gcc -O2 -std=c99 -D_POSIX_C_SOURCE=200809L bench/proof_calibration.c \
         -o /tmp/proof_cal -lm -lpthread
   Run:  /tmp/proof_cal [static|part|turning] [frames]   (defaults: static 8)

   The bench's object protocol (bench/bench.c): the bumpy torus knot, N =
   1.3 M samples with cones, twisting by scene_deform (t = 0.1 per frame);
   1024 paraboloid lights 32 x 32 with back-face culling (shape_object_rig),
   epsilon 1 px.  static: the rig at rest over the whole knot twisting;
   part: the rig at rest, only the highest eighth of the vertices (by y)
   twisting; turning: the rig turning 1 degree per frame over the whole knot
   twisting.  Each frame the basic cut is computed by the library; the
   entries of the frame before are then judged.

   The proof.  An entry (node x with status s, its parent p) keeps s and its
   parent stays invalid while, for x and for p, the centre moved at most T,
   the radius changed at most G, the cone's axis and half-angle turned at
   most A, the view's eye moved at most E and its axis turned at most R
   (accumulated since the entry was last evaluated).  Under those motions a
   paraboloid node-view (x = centre - eye, w = x . forward, d = |x|) has
       x . w in [w - m, w + m],   m = T + E + R (d + T + E),
       |x| in [d - T - E, d + T + E],  radius in [r - G, r + G],
   the direction to the eye turned at most asin((T + E) / (d - T - E)) and
   the cone at most A, so the diameter 2 scale r / (x.w + sqrt(d^2 - r^2))
   lies between its values at the corners of that box, and the plane test
   (x.w + r >= 0) and the back-face test (the library's mlod__backfacing,
   with the cone widened or narrowed) are decided at the corners likewise.
   An entry is proven when every corner gives s for x and "invalid, not
   culled" for p.  At evaluation, an entry's budgets are the largest of
   64, 32, .. 1 times this frame's motions that still prove it (none: it is
   evaluated next frame); a skipped entry's budgets shrink by each frame's
   motion.

   Two bookkeepings, each checked: every entry it skips must be in the new
   basic cut with the same status (a wrong one aborts):
     per node  the motions of x and p themselves, budgets as exact doubles:
               the most any bound of this kind can skip (a ceiling);
     stored    the motions as the largest over the depth-12 subtree holding
               p (8191 bounds, what a tree can keep cheaply), budgets rounded
               down to powers of two (what a few bits per entry can hold).
   Printed per frame: the share of entries equal in node and status to the
   frame before (what any scheme could skip at best), and the share each
   bookkeeping skips, of all entries and of the entries whose node or parent
   moved. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "shapes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAL_VIEWS 1024u
#define CAL_DEPTH 12u /* the stored bounds: one per node of depth <= 12 */

typedef struct motion {
    double t, g, a; /* centre moved, radius changed, cone turned */
} motion;

typedef struct budget {
    double t, g, a, e, r; /* node translation, growth, cone turn; eye translation, axis turn; t < 0: none */
} budget;

typedef struct view_motion {
    double e, r; /* eye moved, axis turned (radians) */
} view_motion;

static void fail(const char *what)
{
    fprintf(stderr, "proof_calibration: %s\n", what);
    exit(1);
}

/* The node of depth <= CAL_DEPTH holding node x (x itself when shallow). */
static uint32_t stored_slot(uint32_t x)
{
    uint32_t depth = mlod__depth_of(x);
    return depth <= CAL_DEPTH ? x : ((x + 1) >> (depth - CAL_DEPTH)) - 1;
}

/* The angle between two cones' axes (floats, not unit). */
static double axes_angle(const float *a, const float *b)
{
    double x[3] = {a[0], a[1], a[2]}, y[3] = {b[0], b[1], b[2]};
    return mlod__angle(x, y);
}

/* The statuses a paraboloid node-view can take under the budget
   (1 drawn, 2 culled, 4 invalid: a set), per the box in the header. */
static int possible_statuses(const mlod__pview *pv, const float *sphere, const float *cone, const budget *b,
                             double epsilon)
{
    const mlod_view_sub *sub = &pv->f.subs[0];
    double x[3], d, w, r = sphere[3], move = b->t + b->e, m, lo_r, hi_r;
    int k, set = 0, may_cull, may_show, may_back = 0, may_front = 1;
    for (k = 0; k < 3; k++) x[k] = (double)sphere[k] - pv->f.eye[k];
    d = sqrt(mlod__dot3(x, x));
    w = mlod__dot3(x, sub->forward);
    m = move + b->r * (d + move);
    lo_r = r - b->g > 0 ? r - b->g : 0;
    hi_r = r + b->g;
    may_cull = (w - m) + lo_r < 0;
    may_show = (w + m) + hi_r >= 0;
    if (pv->backfaces && cone) {
        if (d - move <= hi_r) {
            may_back = 1;
        } else {
            double turn = asin(move / (d - move) < 1.0 ? move / (d - move) : 1.0) + 1e-9;
            double near_x[3], far_x[3], near2, far2;
            float wide[4], narrow[4];
            /* nearer, the sphere's angle asin(r / d) is larger: harder to cull */
            for (k = 0; k < 3; k++) {
                near_x[k] = x[k] * (d - move) / d;
                far_x[k] = x[k] * (d + move) / d;
            }
            near2 = mlod__dot3(near_x, near_x);
            far2 = mlod__dot3(far_x, far_x);
            memcpy(wide, cone, sizeof wide);
            memcpy(narrow, cone, sizeof narrow);
            wide[3] = (float)((cone[3] + b->a + turn) * (1 + 1e-6));
            narrow[3] = (float)((cone[3] - b->a - turn) * (1 - 1e-6));
            /* the widened cone and the largest sphere culled: never shown */
            may_front = !mlod__backfacing(pv, near_x, near2, hi_r, sqrt(fmax(near2 - hi_r * hi_r, 0)), wide);
            /* the narrowed cone and the smallest sphere shown: never culled */
            may_back = narrow[3] < 0 || mlod__backfacing(pv, far_x, far2, lo_r, sqrt(fmax(far2 - lo_r * lo_r, 0)), narrow);
        }
    }
    if (may_cull || may_back) set |= 2;
    if (may_show && may_front) {
        /* the diameter grows with r and shrinks with x.w and |x| */
        double near_d = d - move, far_d = d + move;
        double most = near_d <= hi_r ? INFINITY
                                     : sub->scale * (1 + 1e-6) *
                                           mlod__paraboloid_diameter(hi_r, w - m, sqrt(near_d * near_d - hi_r * hi_r));
        double least = sub->scale * (1 - 1e-6) *
                       mlod__paraboloid_diameter(lo_r, w + m, sqrt(fmax(far_d * far_d - lo_r * lo_r, 0)));
        if (least <= epsilon) set |= 1;
        if (most > epsilon) set |= 4;
    }
    return set;
}

static int proves(const mlod__pview *pv, const mlod_tree *tree, uint32_t x, uint8_t status, const budget *b,
                  double epsilon)
{
    int want = status == MLOD_STATUS_DRAWN ? 1 : status == MLOD_STATUS_CULLED ? 2 : 4;
    if (possible_statuses(pv, tree->spheres + 4 * (size_t)x, tree->cones + 4 * (size_t)x, b, epsilon) != want)
        return 0;
    if (x == 0) return 1;
    x = (x - 1) / 2;
    return possible_statuses(pv, tree->spheres + 4 * (size_t)x, tree->cones + 4 * (size_t)x, b, epsilon) == 4;
}

static double floor_pow2(double v) { return v > 0 ? ldexp(1.0, (int)floor(log2(v))) : v; }

/* What one bookkeeping keeps per entry of the previous cuts. */
typedef struct book {
    uint32_t *nodes[CAL_VIEWS], count[CAL_VIEWS];
    uint8_t *status[CAL_VIEWS];
    budget *left[CAL_VIEWS];
    uint64_t skipped, moving, moving_skipped;
} book;

/* The motion bounding node x and its parent this frame: per node, or the
   stored bound of the parent's depth-12 subtree (which holds both). */
static motion entry_motion(const motion *per_node, const motion *stored, uint32_t x, int use_stored)
{
    uint32_t p = x ? (x - 1) / 2 : 0;
    motion m;
    if (use_stored) return stored[stored_slot(p)];
    m.t = fmax(per_node[x].t, per_node[p].t);
    m.g = fmax(per_node[x].g, per_node[p].g);
    m.a = fmax(per_node[x].a, per_node[p].a);
    return m;
}

/* One view's update of a bookkeeping: the old entries judged against this
   frame's motion and the new cut, the new cut's budgets set. */
static void judge_view(book *bk, uint32_t v, const mlod_cut_view *now, const mlod__pview *pv, const mlod_tree *tree,
                       const motion *per_node, const motion *stored, view_motion vm, int use_stored,
                       int32_t *where, double epsilon)
{
    static const double multiples[] = {64, 32, 16, 8, 4, 2, 1};
    budget *next = (budget *)malloc(sizeof(budget) * (now->count ? now->count : 1));
    uint8_t *kept = (uint8_t *)calloc(now->count ? now->count : 1, 1);
    uint32_t j, q;
    if (!next || !kept) fail("out of memory");
    for (j = 0; j < now->count; j++) where[now->nodes[j]] = (int32_t)j;
    for (j = 0; j < bk->count[v]; j++) {
        uint32_t x = bk->nodes[v][j];
        motion m = entry_motion(per_node, stored, x, use_stored);
        const budget *b = &bk->left[v][j];
        int32_t at = where[x];
        int moving = m.t > 0 || m.g > 0 || m.a > 0 || vm.e > 0 || vm.r > 0;
        int skip = b->t >= 0 && b->t >= m.t && b->g >= m.g && b->a >= m.a && b->e >= vm.e && b->r >= vm.r;
        bk->moving += moving;
        if (!skip) continue;
        if (at < 0 || now->status[at] != bk->status[v][j]) fail("an entry proven unchanged changed: the bound is wrong");
        kept[at] = 1;
        next[at].t = b->t - m.t;
        next[at].g = b->g - m.g;
        next[at].a = b->a - m.a;
        next[at].e = b->e - vm.e;
        next[at].r = b->r - vm.r;
        if (use_stored) {
            next[at].t = floor_pow2(next[at].t);
            next[at].g = floor_pow2(next[at].g);
            next[at].a = floor_pow2(next[at].a);
            next[at].e = floor_pow2(next[at].e);
            next[at].r = floor_pow2(next[at].r);
        }
        bk->skipped++;
        bk->moving_skipped += moving;
    }
    for (j = 0; j < now->count; j++) {
        uint32_t x = now->nodes[j];
        motion m = entry_motion(per_node, stored, x, use_stored);
        where[x] = -1;
        if (kept[j]) continue;
        next[j].t = -1;
        /* a little above zero: a node that did not move may move next */
        for (q = 0; q < sizeof multiples / sizeof multiples[0]; q++) {
            budget b;
            b.t = multiples[q] * fmax(m.t, 1e-7);
            b.g = multiples[q] * fmax(m.g, 1e-8);
            b.a = multiples[q] * fmax(m.a, 1e-7);
            b.e = multiples[q] * vm.e;
            b.r = multiples[q] * vm.r;
            if (use_stored) {
                b.t = floor_pow2(b.t);
                b.g = floor_pow2(b.g);
                b.a = floor_pow2(b.a);
                b.e = floor_pow2(b.e);
                b.r = floor_pow2(b.r);
            }
            if (proves(pv, tree, x, now->status[j], &b, epsilon)) {
                next[j] = b;
                break;
            }
        }
    }
    free(bk->nodes[v]);
    free(bk->status[v]);
    free(bk->left[v]);
    bk->nodes[v] = (uint32_t *)malloc(sizeof(uint32_t) * (now->count ? now->count : 1));
    bk->status[v] = (uint8_t *)malloc(now->count ? now->count : 1);
    if (!bk->nodes[v] || !bk->status[v]) fail("out of memory");
    memcpy(bk->nodes[v], now->nodes, sizeof(uint32_t) * now->count);
    memcpy(bk->status[v], now->status, now->count);
    bk->left[v] = next;
    bk->count[v] = now->count;
    free(kept);
}

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "static";
    int frames = argc > 2 ? atoi(argv[2]) : 8, f, part = !strcmp(mode, "part"), turning = !strcmp(mode, "turning");
    const double epsilon = 1.0;
    scene_mesh scene;
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel parallel = mlod_pool_parallel(pool);
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_tree *tree;
    mlod_cut *cut;
    mlod_error error;
    mlod_view *views = (mlod_view *)malloc(sizeof(mlod_view) * CAL_VIEWS), *before = (mlod_view *)malloc(sizeof(mlod_view) * CAL_VIEWS);
    float *positions, *moved, *spheres, *cones;
    double limit;
    motion *per_node, *stored;
    int32_t *where;
    static book books[2];
    uint32_t i, v, vertices, stored_count = (1u << (CAL_DEPTH + 1)) - 1;
    if (!part && !turning && strcmp(mode, "static")) fail("mode: static, part or turning");
    shape_torus_knot(&scene, 1536, 96);
    vertices = scene.vertex_count;
    positions = (float *)malloc(sizeof(float) * 3 * vertices);
    moved = (float *)malloc(sizeof(float) * 3 * vertices);
    if (!shape_top_eighth(&scene, &limit)) fail("out of memory");
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = scene.positions;
    mesh.vertex_count = vertices;
    mesh.indices = scene.indices;
    mesh.index_count = scene.index_count;
    memset(&desc, 0, sizeof desc);
    desc.sample_count = 1300000;
    desc.seed = 1;
    desc.radius_scale = 1;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_REFIT;
    desc.parallel = &parallel;
    if (mlod_build_mesh(&mesh, &desc, &tree, &error) != MLOD_OK) fail(error.message);
    if (mlod_cut_create(CAL_VIEWS, NULL, &cut, &error) != MLOD_OK) fail(error.message);
    spheres = (float *)malloc(16 * (size_t)tree->node_count);
    cones = (float *)malloc(16 * (size_t)tree->node_count);
    per_node = (motion *)malloc(sizeof(motion) * tree->node_count);
    stored = (motion *)malloc(sizeof(motion) * stored_count);
    where = (int32_t *)malloc(sizeof(int32_t) * tree->node_count);
    if (!views || !before || !positions || !moved || !spheres || !cones || !per_node || !stored || !where)
        fail("out of memory");
    for (i = 0; i < tree->node_count; i++) where[i] = -1;
    printf("proof_calibration %s: N = %u, %u views 32x32, epsilon 1; shares of the cut's entries\n", mode,
           tree->leaf_count, CAL_VIEWS);
    printf("frame  entries  equal-to-before  skipped(per node)  of-moving  skipped(stored)  of-moving\n");
    for (f = 0; f <= frames; f++) {
        mlod_cut_params params;
        uint64_t entries = 0, equal = 0;
        int b;
        memcpy(spheres, tree->spheres, 16 * (size_t)tree->node_count);
        memcpy(cones, tree->cones, 16 * (size_t)tree->node_count);
        scene_deform(&scene, (float)(0.1 * f), moved, NULL);
        shape_part_positions(&scene, moved, part ? limit : -INFINITY, positions);
        mesh.positions = positions;
        if (mlod_refit_mesh(tree, &mesh, &parallel, &error) != MLOD_OK) fail(error.message);
        memset(stored, 0, sizeof(motion) * stored_count);
        for (i = 0; i < tree->node_count; i++) {
            const float *a = spheres + 4 * (size_t)i, *c = tree->spheres + 4 * (size_t)i;
            const float *ca = cones + 4 * (size_t)i, *cb = tree->cones + 4 * (size_t)i;
            double dx = (double)c[0] - a[0], dy = (double)c[1] - a[1], dz = (double)c[2] - a[2];
            motion *m = &per_node[i], *s = &stored[stored_slot(i)];
            m->t = sqrt(dx * dx + dy * dy + dz * dz) * (1 + 1e-9);
            m->g = fabs((double)c[3] - a[3]) * (1 + 1e-9);
            m->a = ca[3] >= MLOD__PI && cb[3] >= MLOD__PI ? 0 : (axes_angle(ca, cb) + fabs((double)cb[3] - ca[3])) * (1 + 1e-9) + 1e-12;
            if (m->t == 0 && m->g == 0 && !memcmp(ca, cb, 16)) m->a = 0;
            s->t = fmax(s->t, m->t);
            s->g = fmax(s->g, m->g);
            s->a = fmax(s->a, m->a);
        }
        for (i = stored_count - 1; i > 0; i--) { /* a shallow node's bound covers its subtree */
            motion *p = &stored[(i - 1) / 2];
            p->t = fmax(p->t, stored[i].t);
            p->g = fmax(p->g, stored[i].g);
            p->a = fmax(p->a, stored[i].a);
        }
        memcpy(before, views, sizeof(mlod_view) * CAL_VIEWS);
        shape_object_rig(CAL_VIEWS, 32, turning ? 1.0 : 0.0, f, views);
        memset(&params, 0, sizeof params);
        params.mode = MLOD_CUT_BASIC;
        params.epsilon = (float)epsilon;
        params.parallel = &parallel;
        if (mlod_cut_update(cut, tree, views, &params, &error) != MLOD_OK) fail(error.message);
        for (b = 0; b < 2; b++) books[b].skipped = books[b].moving = books[b].moving_skipped = 0;
        for (v = 0; v < CAL_VIEWS; v++) {
            mlod_cut_view now = mlod_cut_get(cut, v);
            mlod__pview pv;
            view_motion vm = {0, 0};
            uint32_t j;
            if (mlod__view_prepare(&views[v], &pv, NULL) != MLOD_OK || pv.sub_count != 1 ||
                pv.kind[0] != MLOD_VIEW_PARABOLOID)
                fail("the rig's views are paraboloids");
            if (f > 0) {
                mlod__pview old;
                double de[3];
                mlod__view_prepare(&before[v], &old, NULL);
                for (i = 0; i < 3; i++) de[i] = pv.f.eye[i] - old.f.eye[i];
                vm.e = sqrt(mlod__dot3(de, de)) * (1 + 1e-9);
                /* the frame's turn: the larger angle its forward or right axis turned */
                vm.r = fmax(mlod__angle(old.f.subs[0].forward, pv.f.subs[0].forward),
                            mlod__angle(old.f.subs[0].right, pv.f.subs[0].right));
                vm.r = vm.r * 1.001 + (vm.r > 0 ? 1e-7 : 0);
            }
            entries += now.count;
            if (f > 0) {
                for (j = 0; j < books[0].count[v]; j++) where[books[0].nodes[v][j]] = (int32_t)j;
                for (j = 0; j < now.count; j++) {
                    int32_t at = where[now.nodes[j]];
                    equal += at >= 0 && books[0].status[v][at] == now.status[j];
                }
                for (j = 0; j < books[0].count[v]; j++) where[books[0].nodes[v][j]] = -1;
            }
            for (b = 0; b < 2; b++) judge_view(&books[b], v, &now, &pv, tree, per_node, stored, vm, b, where, epsilon);
        }
        printf("%5d  %7llu  %14.1f%%  %16.1f%%  %8.1f%%  %14.1f%%  %8.1f%%\n", f, (unsigned long long)entries,
               100.0 * equal / entries, 100.0 * books[0].skipped / entries,
               100.0 * books[0].moving_skipped / (books[0].moving ? books[0].moving : 1),
               100.0 * books[1].skipped / entries,
               100.0 * books[1].moving_skipped / (books[1].moving ? books[1].moving : 1));
        fflush(stdout);
    }
    return 0;
}
