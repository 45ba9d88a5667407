/* tests/test_memory.c - memory a caller can plan for.

   1. A failed mlod_cut_update: in every mode, with and without a
      parallel hook.  After an error found before any work (a bad view or
      epsilon) the cut holds the same cuts, reports the same bytes and
      holds the same live bytes of its allocator as before the call, and
      still skips the views its lists were computed for (an update with
      them allocates nothing and evaluates nothing).  After running out of
      memory (an allocator failing its k-th call, a live-bytes budget) the
      cut is reset: no entries, every version new, no more bytes than
      before, reported exactly; the same updates again give the same cuts
      in the same bytes; and the next update with room to spare gives the
      cut an undisturbed cut gives.
   2. The sizing functions: mlod_build_mesh_bound / mlod_build_points_bound
      against the allocator's high-water mark of live bytes (at or above
      it, at most 10 % above), mlod_cut_bound against a cut's bytes and
      its updates' peaks, mlod_atlas_bound against mlod_atlas_create. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

/* ---------------------------------------------------- budget allocator */

/* testutil.h's counting allocator, zeroed, failing every call from fail_at
   on once that is set (the budget of live bytes is budget_bytes). */
typedef tu_counter budget;

static mlod_allocator budget_allocator(budget *b)
{
    memset(b, 0, sizeof *b);
    b->fail_after = 1;
    return tu_allocator(b);
}

/* ------------------------------------------------------- cut snapshots */

/* Everything mlod_cut_get says about every view, copied. */
typedef struct snapshot {
    uint32_t views;
    mlod_cut_view *cv;
    uint32_t **nodes;
    uint8_t **status;
    size_t bytes;
} snapshot;

static void snapshot_take(snapshot *s, const mlod_cut *cut)
{
    uint32_t v;
    s->views = mlod_cut_view_count(cut);
    s->cv = (mlod_cut_view *)calloc(s->views, sizeof *s->cv);
    s->nodes = (uint32_t **)calloc(s->views, sizeof *s->nodes);
    s->status = (uint8_t **)calloc(s->views, sizeof *s->status);
    s->bytes = mlod_cut_bytes(cut);
    for (v = 0; v < s->views; v++) {
        s->cv[v] = mlod_cut_get(cut, v);
        s->nodes[v] = (uint32_t *)malloc(s->cv[v].count * sizeof(uint32_t) + 1);
        s->status[v] = (uint8_t *)malloc(s->cv[v].count + 1);
        if (s->cv[v].count) {
            memcpy(s->nodes[v], s->cv[v].nodes, s->cv[v].count * sizeof(uint32_t));
            memcpy(s->status[v], s->cv[v].status, s->cv[v].count);
        }
    }
}

static void snapshot_free(snapshot *s)
{
    uint32_t v;
    for (v = 0; v < s->views; v++) {
        free(s->nodes[v]);
        free(s->status[v]);
    }
    free(s->cv);
    free(s->nodes);
    free(s->status);
    memset(s, 0, sizeof *s);
}

/* The view whose cut differs from the snapshot's (its lists, counts and
   statistics), or -1 when every view's is the same. */
static long snapshot_differs(const snapshot *s, const mlod_cut *cut)
{
    uint32_t v;
    for (v = 0; v < s->views; v++) {
        mlod_cut_view now = mlod_cut_get(cut, v), was = s->cv[v];
        if (now.count != was.count || now.drawn != was.drawn || now.culled != was.culled ||
            now.oversize != was.oversize || now.coarse != was.coarse || now.evaluated != was.evaluated ||
            now.steps != was.steps)
            return (long)v;
        if (now.count && (memcmp(now.nodes, s->nodes[v], now.count * sizeof(uint32_t)) != 0 ||
                          memcmp(now.status, s->status[v], now.count) != 0))
            return (long)v;
    }
    return -1;
}

/* ----------------------------------------------- 1. memory after failure */

static scene_mesh room;
static mlod_tree *room_tree;
#define VIEWS 24
static mlod_view far_views[VIEWS], near_views[VIEWS];

static void make_views(void)
{
    uint64_t rng = 77;
    double c[3], R;
    uint32_t v;
    int k;
    tu_bounds(&room, c, &R);
    for (v = 0; v < VIEWS; v++) {
        mlod_view_kind kind = (mlod_view_kind)(v % 4);
        double eye[3], dir[3];
        far_views[v] = tu_random_view(&rng, kind, c, R);
        far_views[v].width = far_views[v].height = 16;
        near_views[v] = far_views[v];
        /* the same views, closer and finer: every cut grows */
        tu_random_unit(&rng, dir);
        for (k = 0; k < 3; k++) eye[k] = c[k] + 0.3 * R * dir[k];
        tu_set3f(near_views[v].position, eye);
        near_views[v].width = near_views[v].height = 48;
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) near_views[v].half_width = near_views[v].half_height = (float)(0.3 * R);
    }
}

/* A cut of `mode` with the far views' cut (lazy: after two calls) on an
   allocator of its own. */
static mlod_cut *settled_cut(const mlod_allocator *a, mlod_cut_params p)
{
    mlod_cut *cut = NULL;
    int i;
    if (mlod_cut_create(VIEWS, a, &cut, NULL) != MLOD_OK) return NULL;
    p.epsilon = 3.0f;
    for (i = 0; i < 2; i++)
        if (mlod_cut_update(cut, room_tree, far_views, &p, NULL) != MLOD_OK) {
            mlod_cut_destroy(cut);
            return NULL;
        }
    return cut;
}

/* The near views' update of a settled cut, on an allocator with no
   limit: the bytes its peak takes above what the cut held, and the
   allocations it makes. */
static size_t growth_of_update(mlod_cut_params p, unsigned long *calls)
{
    budget b;
    mlod_allocator a = budget_allocator(&b);
    mlod_cut *cut = settled_cut(&a, p);
    size_t before;
    *calls = 0;
    if (!cut) return 0;
    before = b.live_bytes;
    b.peak_bytes = b.live_bytes;
    b.calls = 0;
    p.epsilon = 0.75f;
    CHECK(mlod_cut_update(cut, room_tree, near_views, &p, NULL) == MLOD_OK, "growth: the unlimited update failed");
    *calls = b.calls;
    mlod_cut_destroy(cut);
    return b.peak_bytes - before;
}

/* After a failed update, the cut is as it was: same cuts, bytes and
   allocator live bytes. */
static int check_unchanged(const snapshot *s, const mlod_cut *cut, const budget *b, size_t live, mlod_result got,
                           mlod_result expected, const char *what, unsigned long at)
{
    long view = snapshot_differs(s, cut);
    int ok = got == expected && view < 0 && mlod_cut_bytes(cut) == s->bytes && b->live_bytes == live;
    CHECK(got == expected, "%s %lu: returned %s, expected %s", what, at, mlod_result_name(got), mlod_result_name(expected));
    CHECK(view < 0, "%s %lu: view %ld's cut changed", what, at, view);
    CHECK(mlod_cut_bytes(cut) == s->bytes, "%s %lu: mlod_cut_bytes %zu, was %zu", what, at, mlod_cut_bytes(cut), s->bytes);
    CHECK(b->live_bytes == live, "%s %lu: the allocator holds %zu live bytes, held %zu", what, at, b->live_bytes, live);
    return ok;
}

/* After an update that ran out of memory: the cut is reset (no entries,
   every version new), holds no more than before (live bytes) and reports
   what it holds.  Then the settled cut's updates again give the settled
   cuts (the snapshot s) in the same bytes.  Returns 1 when all held. */
static int check_reset(const snapshot *s, mlod_cut *cut, const budget *b, size_t live, mlod_result got,
                       mlod_cut_params p, const char *what, unsigned long at)
{
    uint32_t v, kept = 0, old_versions = 0;
    int i, ok;
    long view;
    for (v = 0; v < s->views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        kept += cv.count != 0;
        old_versions += cv.version == s->cv[v].version;
    }
    CHECK(got == MLOD_ERROR_OUT_OF_MEMORY, "%s %lu: returned %s", what, at, mlod_result_name(got));
    CHECK(kept == 0 && old_versions == 0, "%s %lu: not reset: %u views hold entries, %u kept their version", what, at,
          kept, old_versions);
    CHECK(b->live_bytes <= live && mlod_cut_bytes(cut) == b->live_bytes,
          "%s %lu: the cut reports %zu bytes, holds %zu, held %zu before", what, at, mlod_cut_bytes(cut), b->live_bytes, live);
    ok = got == MLOD_ERROR_OUT_OF_MEMORY && kept == 0 && old_versions == 0 && b->live_bytes <= live;
    p.epsilon = 3.0f;
    for (i = 0; i < 2; i++) CHECK(mlod_cut_update(cut, room_tree, far_views, &p, NULL) == MLOD_OK, "%s %lu: settle again", what, at);
    view = snapshot_differs(s, cut);
    CHECK(view < 0 && mlod_cut_bytes(cut) == s->bytes && b->live_bytes == live,
          "%s %lu: settled again, view %ld differs; %zu bytes, %zu before", what, at, view, mlod_cut_bytes(cut), s->bytes);
    return ok && view < 0 && b->live_bytes == live;
}

/* After a failed update the cut still knows what its lists were computed
   for: when the settled cut's last update evaluated no view (its lists are
   exact for the far views), an update with those views again skips every
   view, so it succeeds with an allocator that refuses everything, asks it
   for nothing, evaluates nothing and leaves the cut as it was.  Returns 1
   when it checked. */
static unsigned check_still_known(const snapshot *s, mlod_cut *cut, budget *b, size_t live, mlod_cut_params p,
                                  const char *what, unsigned long at)
{
    unsigned long fail_at = b->fail_at, calls = b->calls;
    size_t budget_bytes = b->budget_bytes;
    mlod_result r;
    uint32_t v, evaluated = 0;
    for (v = 0; v < s->views; v++)
        if (s->cv[v].evaluated) return 0;
    p.epsilon = 3.0f;
    b->fail_at = b->calls + 1;
    b->budget_bytes = 0;
    r = mlod_cut_update(cut, room_tree, far_views, &p, NULL);
    for (v = 0; v < s->views; v++) evaluated += mlod_cut_get(cut, v).evaluated > 0;
    CHECK(r == MLOD_OK && evaluated == 0 && b->calls == calls,
          "%s %lu: then the settled views again: %s, %u views evaluated, %lu allocations", what, at,
          mlod_result_name(r), evaluated, b->calls - calls);
    CHECK(snapshot_differs(s, cut) < 0 && mlod_cut_bytes(cut) == s->bytes && b->live_bytes == live,
          "%s %lu: then the settled views again changed the cut", what, at);
    b->fail_at = fail_at;
    b->budget_bytes = budget_bytes;
    return 1;
}

/* After the update that succeeded: the cut an undisturbed cut of the same
   history computes for the near views. */
static void check_as_undisturbed(const mlod_cut *cut, const budget *b, mlod_cut_params p, const char *what)
{
    budget rb;
    mlod_allocator ra = budget_allocator(&rb);
    mlod_cut *ref = settled_cut(&ra, p);
    snapshot want;
    long view;
    p.epsilon = 0.75f;
    CHECK(ref && mlod_cut_update(ref, room_tree, near_views, &p, NULL) == MLOD_OK, "%s: reference update", what);
    if (!ref) return;
    snapshot_take(&want, ref);
    view = snapshot_differs(&want, cut);
    CHECK(view < 0, "%s: after the failures view %ld's cut differs from an undisturbed cut's", what, view);
    CHECK(mlod_cut_bytes(cut) == b->live_bytes, "%s: the cut reports %zu bytes, holds %zu", what, mlod_cut_bytes(cut), b->live_bytes);
    snapshot_free(&want);
    mlod_cut_destroy(ref);
}

static void test_failed_updates(void)
{
    static const char *mode_names[3] = {"basic", "incremental", "lazy"};
    mlod_pool *pool = mlod_pool_create(3);
    mlod_parallel hooks[2];
    const char *hook_names[2] = {"no hook", "3 threads"};
    uint32_t h, mode, fails = 0, budgets = 0, known = 0;
    hooks[1] = mlod_pool_parallel(pool);
    for (mode = 0; mode < 3; mode++)
        for (h = 0; h < 2; h++) {
            mlod_cut_params p;
            budget b;
            mlod_allocator a = budget_allocator(&b);
            mlod_cut *cut;
            snapshot s;
            unsigned long calls, k;
            size_t growth, live;
            char what[96];
            int f;
            if (h == 1 && !pool) continue;
            memset(&p, 0, sizeof p);
            p.mode = (mlod_cut_mode)mode;
            p.lazy_steps = 3;
            p.parallel = h ? &hooks[h] : NULL;
            growth = growth_of_update(p, &calls);
            CHECK(growth > 0 && calls > 0, "%s, %s: the near views' update grows the cut (%zu bytes, %lu allocations)",
                  mode_names[mode], hook_names[h], growth, calls);
            cut = settled_cut(&a, p);
            CHECK(cut != NULL, "%s, %s: settled cut", mode_names[mode], hook_names[h]);
            if (!cut) continue;
            snapshot_take(&s, cut);
            live = b.live_bytes;
            CHECK(s.bytes == live, "%s, %s: the cut reports %zu bytes, holds %zu", mode_names[mode], hook_names[h], s.bytes,
                  live);
            /* errors found before any work */
            {
                mlod_view bad[VIEWS];
                memcpy(bad, near_views, sizeof bad);
                bad[VIEWS - 1].width = 0;
                p.epsilon = -1.0f;
                snprintf(what, sizeof what, "%s, %s, bad epsilon", mode_names[mode], hook_names[h]);
                check_unchanged(&s, cut, &b, live, mlod_cut_update(cut, room_tree, near_views, &p, NULL),
                                MLOD_ERROR_BAD_EPSILON, what, 0);
                p.epsilon = 0.75f;
                snprintf(what, sizeof what, "%s, %s, bad view", mode_names[mode], hook_names[h]);
                check_unchanged(&s, cut, &b, live, mlod_cut_update(cut, room_tree, bad, &p, NULL), MLOD_ERROR_BAD_VIEW, what, 0);
                /* basic and incremental updates leave exact cuts: checked for them at least */
                CHECK(check_still_known(&s, cut, &b, live, p, what, 0) || mode == MLOD_CUT_LAZY,
                      "%s: the settled cut's last update evaluated views", what);
            }
            /* the allocator fails the update's k-th call and every later one, for every k */
            snprintf(what, sizeof what, "%s, %s, failing allocation", mode_names[mode], hook_names[h]);
            for (k = 1; k <= calls; k++) {
                mlod_error e;
                mlod_result r;
                b.fail_at = b.calls + k;
                r = mlod_cut_update(cut, room_tree, near_views, &p, &e);
                b.fail_at = 0;
                check_reset(&s, cut, &b, live, r, p, what, k);
                known += check_still_known(&s, cut, &b, live, p, what, k);
                fails++;
            }
            b.fail_at = 0;
            /* budgets from what the cut holds up to the peak the update takes
               with room to spare (near it, an update may succeed: its
               buffers' spare eighth is only asked for, not needed), then
               none: the first update that succeeds computes the cut an
               undisturbed cut computes */
            snprintf(what, sizeof what, "%s, %s, budget of live bytes (per mille of the growth)", mode_names[mode],
                     hook_names[h]);
            for (f = 0;; f += 71) {
                mlod_result r;
                b.budget_bytes = f < 1000 ? live + growth * (size_t)f / 1000 : 0;
                r = mlod_cut_update(cut, room_tree, near_views, &p, NULL);
                if (r == MLOD_OK) break;
                b.budget_bytes = 0;
                check_reset(&s, cut, &b, live, r, p, what, (unsigned long)f);
                known += check_still_known(&s, cut, &b, live, p, what, (unsigned long)f);
                budgets++;
            }
            CHECK(f >= 500, "%s: an update succeeded with %d per mille of the growth it takes", what, f);
            b.budget_bytes = 0;
            snprintf(what, sizeof what, "%s, %s", mode_names[mode], hook_names[h]);
            check_as_undisturbed(cut, &b, p, what);
            snapshot_free(&s);
            mlod_cut_destroy(cut);
            CHECK(b.live_blocks == 0 && b.live_bytes == 0, "%s: %lu blocks, %zu bytes left after destroy", what, b.live_blocks, b.live_bytes);
        }
    printf("  failed updates checked: %u with a failing allocation, %u under a budget; %u times the settled views "
           "were skipped after one\n", fails, budgets, known);
    mlod_pool_destroy(pool);
}

/* --------------------------------------------- 2. sizing: builds */

static mlod_pool *pool2;

/* One build on a counting allocator: its peak equals the bound, the tree
   reports what it holds.  Returns the peak. */
static size_t check_build(const mlod_mesh *m, const mlod_points *pts, uint32_t n, uint32_t attributes, int hook,
                          const char *what)
{
    budget b;
    mlod_allocator a = budget_allocator(&b);
    mlod_build_desc d = tu_desc(n, 9, attributes);
    mlod_parallel par = mlod_pool_parallel(pool2);
    mlod_tree *t = NULL;
    mlod_error e;
    mlod_result r;
    size_t bound;
    d.allocator = &a;
    if (hook && pool2) d.parallel = &par;
    if (m) {
        r = mlod_build_mesh(m, &d, &t, &e);
        bound = mlod_build_mesh_bound(n, m->index_count / 3, attributes);
    } else {
        r = mlod_build_points(pts, &d, &t, &e);
        bound = mlod_build_points_bound(pts->count, attributes);
        n = pts->count;
    }
    CHECK(r == MLOD_OK, "%s, N = %u, attributes %#x: build failed: %s", what, n, attributes, e.message);
    if (r != MLOD_OK) return 0;
    CHECK(b.peak_bytes <= bound && (double)bound <= 1.1 * (double)b.peak_bytes,
          "%s, N = %u, attributes %#x%s: bound %zu bytes against a peak of %zu (within 10 %% above)", what, n, attributes,
          hook ? ", 2 threads" : "", bound, b.peak_bytes);
    CHECK(bound == b.peak_bytes, "%s, N = %u, attributes %#x: bound %zu is not the peak %zu exactly", what, n, attributes, bound,
          b.peak_bytes);
    CHECK(t->bytes == b.live_bytes, "%s, N = %u: the tree reports %zu bytes, holds %zu", what, n, t->bytes, b.live_bytes);
    CHECK(t->bytes <= bound, "%s, N = %u: the tree's %zu bytes above the peak bound %zu", what, n, t->bytes, bound);
    mlod_tree_destroy(t);
    CHECK(b.live_bytes == 0 && b.live_blocks == 0, "%s, N = %u: %zu bytes left after destroy", what, n, b.live_bytes);
    return b.peak_bytes;
}

static void test_build_bounds(void)
{
    static const uint32_t attrs[5] = {0, MLOD_ATTR_CONE, MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR, MLOD_ATTR_REFIT,
                                      MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT};
    static const uint32_t ns[6] = {1, 2, 7, 100, 3000, 40000};
    scene_mesh soup, torus;
    mlod_mesh meshes[2];
    const char *names[2] = {"soup (5000 triangles)", "torus"};
    uint32_t i, k, a, h, builds = 0;
    size_t big;
    pool2 = mlod_pool_create(2);
    if (!scene_soup(&soup, 5000, 3) || !scene_torus(&torus, 1.0f, 0.3f, 24, 12)) return;
    meshes[0] = tu_mesh(&soup);
    meshes[1] = tu_mesh(&torus);
    /* meshes: N below and above the triangle count (refit data differs) */
    for (k = 0; k < 2; k++)
        for (i = 0; i < 6; i++)
            for (a = 0; a < 5; a++)
                for (h = 0; h < 2; h++) {
                    if (h && (i % 2 || a % 2)) continue;
                    check_build(&meshes[k], NULL, ns[i], attrs[a], (int)h, names[k]);
                    builds++;
                }
    /* points: with and without radii and normals */
    for (i = 0; i < 6; i++)
        for (a = 0; a < 5; a++) {
            uint32_t n = ns[i], j;
            uint64_t rng = 11;
            float *xyz = (float *)malloc(3 * sizeof(float) * n), *radii = (float *)malloc(sizeof(float) * n);
            mlod_points pts;
            memset(&pts, 0, sizeof pts);
            for (j = 0; j < 3 * n; j++) xyz[j] = scene_rng_range(&rng, -1.0f, 1.0f);
            for (j = 0; j < n; j++) radii[j] = scene_rng_range(&rng, 0.001f, 0.01f);
            pts.positions = xyz;
            pts.count = n;
            pts.colors = xyz; /* any floats */
            pts.normals = a % 2 ? xyz : NULL;
            pts.radii = a % 2 ? NULL : radii;
            check_build(NULL, &pts, n, attrs[a], (int)(i == 5), "points");
            builds++;
            free(xyz);
            free(radii);
        }
    /* what the issue met: N = 2^30 is accepted and needs far more than a
       small machine has: the sampling arrays (28 bytes a sample), the
       tree's spheres (32 a leaf) and the positions along three axes (36)
       are 96 GiB at once */
    big = mlod_build_mesh_bound(MANYLODS_MAX_LEAVES, 12, 0);
    CHECK(sizeof(size_t) < 8 ? big == (size_t)-1 : big > (size_t)96 << 30,
          "N = 2^30: bound %zu bytes, expected over 96 GiB (or (size_t)-1)", big);
    CHECK(mlod_build_mesh_bound(0, 12, 0) == 0 && mlod_build_mesh_bound(MANYLODS_MAX_LEAVES + 1u, 12, 0) == 0 &&
              mlod_build_points_bound(0, MLOD_ATTR_CONE) == 0 && mlod_build_points_bound(MANYLODS_MAX_LEAVES + 1u, 0) == 0,
          "bounds of builds refused before allocating are not 0");
    CHECK(mlod_build_mesh_bound(1000, 10, MLOD_ATTR_CONE) < mlod_build_mesh_bound(1001, 10, MLOD_ATTR_CONE) &&
              mlod_build_mesh_bound(1000, 10, 0) < mlod_build_mesh_bound(1000, 10, attrs[4]),
          "build bound not increasing with N and attributes");
    printf("  build bounds: %u builds, each bound equal to the allocator's peak; N = 2^30 needs %.0f GiB\n", builds,
           (double)big / 1073741824.0);
    scene_free(&soup);
    scene_free(&torus);
    mlod_pool_destroy(pool2);
}

/* ------------------------------------------------ 2. sizing: the cut */

/* mlod_cut_reserve's allocations: nodes and statuses of a window's two
   work lists and of the scratch, the segments, the tasks. */
#define MLOD_TEST_WORK_BUFFERS 8u

/* A cut reserved with mlod_cut_reserve for the largest mean cut the same
   sequence of updates reached (views[call % 2 * V], `calls` updates): it
   holds at most mlod_cut_bound, its updates peak at most there and give
   the cuts of an unreserved cut (compared by hash); then steady frames
   (the first views moved by a millionth of the scene, four times)
   allocate nothing after the first (basic and incremental: a lazy cut
   still converges). */
static void check_reserved(const mlod_view *views, uint32_t V, mlod_cut_params p, uint32_t calls, uint64_t most,
                           uint64_t hash, const char *what)
{
    budget b;
    mlod_allocator a = budget_allocator(&b);
    mlod_cut *cut = NULL;
    uint32_t mean = (uint32_t)((most + V - 1) / V), call, v;
    size_t bound = mlod_cut_bound(V, mean), reserved;
    unsigned long allocations;
    uint64_t h = TU_HASH_START;
    mlod_view *steady = (mlod_view *)malloc(V * sizeof(mlod_view));
    CHECK(mlod_cut_create(V, &a, &cut, NULL) == MLOD_OK && mlod_cut_reserve(cut, mean, NULL) == MLOD_OK,
          "%s: reserve", what);
    if (!cut || !steady) {
        free(steady);
        mlod_cut_destroy(cut);
        return;
    }
    reserved = b.live_bytes;
    CHECK(reserved <= bound && mlod_cut_bytes(cut) == reserved,
          "%s: reserved for %u nodes per view, holds %zu bytes (reports %zu), the bound is %zu", what, mean, b.live_bytes,
          mlod_cut_bytes(cut), bound);
    b.peak_bytes = b.live_bytes;
    for (call = 0; call < calls; call++) {
        CHECK(mlod_cut_update(cut, room_tree, views + (call % 2) * V, &p, NULL) == MLOD_OK, "%s: update", what);
        for (v = 0; v < V; v++) {
            mlod_cut_view c = mlod_cut_get(cut, v);
            h = tu_hash(h, c.nodes, c.count * sizeof *c.nodes);
        }
    }
    CHECK(b.peak_bytes <= bound, "%s: after reserving %zu bytes, the updates peak at %zu, above the bound %zu", what,
          reserved, b.peak_bytes, bound);
    CHECK(h == hash, "%s: the reserved cut's cuts differ from an unreserved cut's", what);
    for (call = 0; call < 4; call++) {
        double c[3], R;
        tu_bounds(&room, c, &R);
        memcpy(steady, views, V * sizeof(mlod_view));
        for (v = 0; v < V; v++) steady[v].position[0] += (float)(1e-6 * R * (call + 1));
        allocations = b.calls;
        CHECK(mlod_cut_update(cut, room_tree, steady, &p, NULL) == MLOD_OK, "%s: steady update", what);
        /* (a lazy cut still converges) */
        CHECK(call == 0 || p.mode == MLOD_CUT_LAZY || b.calls == allocations, "%s: steady frame %u: %lu allocations", what,
              call, b.calls - allocations);
    }
    free(steady);
    mlod_cut_destroy(cut);
    CHECK(b.live_bytes == 0, "%s: %zu bytes left after destroy", what, b.live_bytes);
    /* a reserve that runs out of memory leaves the cut as it was */
    if (V == 16 && p.mode == MLOD_CUT_BASIC) {
        unsigned long k;
        for (k = 1; k <= MLOD_TEST_WORK_BUFFERS + 1; k++) {
            size_t created;
            mlod_result r;
            mlod_error e;
            a = budget_allocator(&b);
            cut = NULL;
            if (mlod_cut_create(V, &a, &cut, NULL) != MLOD_OK) continue;
            created = b.live_bytes;
            b.fail_at = b.calls + k;
            r = mlod_cut_reserve(cut, mean, &e);
            CHECK(k > MLOD_TEST_WORK_BUFFERS ? r == MLOD_OK
                                              : r == MLOD_ERROR_OUT_OF_MEMORY && b.live_bytes == created &&
                                                    mlod_cut_bytes(cut) == created,
                  "%s: reserve failing at allocation %lu of the work buffers: %s, %zu bytes held, %zu before", what, k,
                  mlod_result_name(r), b.live_bytes, created);
            mlod_cut_destroy(cut);
        }
    }
}

static void test_cut_bounds(void)
{
    static const uint32_t counts[3] = {1, 16, 256};
    static const float eps[3] = {8.0f, 1.0f, 0.35f};
    mlod_pool *pool = mlod_pool_create(2);
    mlod_parallel par = mlod_pool_parallel(pool);
    double c[3], R, worst_large = 0.0, worst_peak = 0.0, worst_entry = 0.0;
    uint32_t ci, ei, mode, cases = 0;
    tu_bounds(&room, c, &R);
    for (ci = 0; ci < 3; ci++)
        for (ei = 0; ei < 3; ei++)
            for (mode = 0; mode < 3; mode++) {
                uint32_t V = counts[ci], v, call, calls = ci == 2 ? 3u : 5u;
                uint64_t hash = TU_HASH_START;
                char what[96];
                mlod_view *views = (mlod_view *)malloc(2 * V * sizeof(mlod_view));
                uint64_t rng = 3 + ci, most = 0;
                budget b;
                mlod_allocator a = budget_allocator(&b);
                mlod_cut *cut = NULL;
                mlod_cut_params p;
                size_t bound, created;
                if (ci == 2 && ei == 2) { /* 2.2 M nodes: too slow for the tests */
                    free(views);
                    continue;
                }
                for (v = 0; v < 2 * V; v++) {
                    views[v] = tu_random_view(&rng, (mlod_view_kind)(v % 4), c, R);
                    views[v].width = views[v].height = 32;
                }
                memset(&p, 0, sizeof p);
                p.mode = (mlod_cut_mode)mode;
                p.epsilon = eps[ei];
                p.lazy_steps = 2;
                p.parallel = ci == 2 && pool ? &par : NULL;
                if (mlod_cut_create(V, &a, &cut, NULL) != MLOD_OK) {
                    free(views);
                    continue;
                }
                created = b.live_bytes;
                /* the first update of a new cut: its peak */
                b.peak_bytes = b.live_bytes;
                CHECK(mlod_cut_update(cut, room_tree, views, &p, NULL) == MLOD_OK, "cut bound: update");
                for (v = 0; v < V; v++) most += mlod_cut_get(cut, v).count;
                bound = mlod_cut_bound(V, (uint32_t)((most + V - 1) / V));
                CHECK(b.peak_bytes <= bound, "cut bound, %u views, eps %g, mode %u: the first update peaks at %zu bytes, above the bound %zu",
                      V, eps[ei], mode, b.peak_bytes, bound);
                for (v = 0; v < V; v++) {
                    mlod_cut_view cv = mlod_cut_get(cut, v);
                    hash = tu_hash(hash, cv.nodes, cv.count * sizeof *cv.nodes);
                }
                /* later updates, the views moving between two sets: what the cut holds, and the updates'
                   peak */
                b.peak_bytes = b.live_bytes;
                for (call = 1; call < calls; call++) {
                    uint64_t total = 0;
                    CHECK(mlod_cut_update(cut, room_tree, views + (call % 2) * V, &p, NULL) == MLOD_OK, "cut bound: update");
                    for (v = 0; v < V; v++) {
                        mlod_cut_view cv = mlod_cut_get(cut, v);
                        total += cv.count;
                        hash = tu_hash(hash, cv.nodes, cv.count * sizeof *cv.nodes);
                    }
                    if (total > most) most = total;
                }
                snprintf(what, sizeof what, "reserved cut, %u views, eps %g, mode %u", V, eps[ei], mode);
                check_reserved(views, V, p, calls, most, hash, what);
                bound = mlod_cut_bound(V, (uint32_t)((most + V - 1) / V));
                CHECK(mlod_cut_bytes(cut) == b.live_bytes, "cut bound: the cut reports %zu bytes, holds %zu", mlod_cut_bytes(cut),
                      b.live_bytes);
                CHECK(mlod_cut_bytes(cut) <= bound, "cut bound, %u views, eps %g, mode %u, %llu nodes at most: holds %zu bytes, above the bound %zu",
                      V, eps[ei], mode, (unsigned long long)most, mlod_cut_bytes(cut), bound);
                CHECK(b.peak_bytes <= bound, "cut bound, %u views, eps %g, mode %u: later updates peak at %zu bytes, above the bound %zu",
                      V, eps[ei], mode, b.peak_bytes, bound);
                if ((double)b.peak_bytes / (double)bound > worst_peak) worst_peak = (double)b.peak_bytes / (double)bound;
                if (most >= ((uint64_t)1 << 20)) {
                    double ratio = (double)bound / (double)b.peak_bytes;
                    /* (it counts windows of twice MLOD__WINDOW entries, a third of it here) */
                    CHECK(ratio <= 1.6, "cut bound, %llu nodes: %zu bytes, %.2f times the updates' peak", (unsigned long long)most,
                          bound, ratio);
                    if (ratio > worst_large) worst_large = ratio;
                }
                /* between updates: the lists, compact (issue 53: at most 6 bytes per entry beyond the
                   per-view arrays a new cut holds) */
                if (most >= ((uint64_t)1 << 16)) {
                    uint64_t now = 0;
                    double per_entry;
                    for (v = 0; v < V; v++) now += mlod_cut_get(cut, v).count;
                    per_entry = (double)(mlod_cut_bytes(cut) - created) / (double)now;
                    CHECK(per_entry <= 6.0, "cut bound, %u views, eps %g, mode %u: %.2f bytes per entry between updates",
                          V, eps[ei], mode, per_entry);
                    if (per_entry > worst_entry) worst_entry = per_entry;
                }
                CHECK(created <= mlod_cut_bound(V, 0),
                      "cut bound: a new cut of %u views holds %zu bytes, above the bound for empty cuts %zu", V, created,
                      mlod_cut_bound(V, 0));
                cases++;
                mlod_cut_destroy(cut);
                free(views);
            }
    CHECK(mlod_cut_bound(0, 10) == 0 && mlod_cut_bound(1000, 100) < mlod_cut_bound(1000, 200), "cut bound: 0 views or not increasing");
    printf("  cut bounds: %u cases at or above what cuts held and first updates peaked at; later updates peaked at up to\n"
           "  %.2f times it (for cuts of a million nodes, it is %.2f times their peak at most); between updates, cuts of\n"
           "  64 k entries or more held %.2f bytes per entry at most\n",
           cases, worst_peak, worst_large, worst_entry);
    mlod_pool_destroy(pool);
}

/* ----------------------------------------------- 2. sizing: the atlas */

static void test_atlas_bounds(void)
{
    uint64_t rng = 5;
    uint32_t trial, exact = 0;
    for (trial = 0; trial < 60; trial++) {
        uint32_t V = 1 + (uint32_t)(scene_rng_double(&rng) * 40), v;
        mlod_view views[40];
        mlod_atlas_desc desc;
        mlod_atlas *atlas = NULL;
        budget b;
        mlod_allocator a = budget_allocator(&b);
        size_t bound, before;
        double pyramid = 0.0;
        uint32_t values;
        memset(&desc, 0, sizeof desc);
        desc.channels = trial % 4;
        desc.columns = trial % 3 ? 0 : 1 + trial % 7;
        for (v = 0; v < V; v++) {
            views[v] = tu_view(MLOD_VIEW_PERSPECTIVE);
            views[v].width = trial % 2 ? 64 : 1 + (uint32_t)(scene_rng_double(&rng) * 100);
            views[v].height = trial % 2 ? 32 : 1 + (uint32_t)(scene_rng_double(&rng) * 100);
        }
        bound = mlod_atlas_bound(views, V, &desc);
        CHECK(mlod_atlas_create(views, V, &desc, &a, &atlas, NULL) == MLOD_OK, "atlas bound: create");
        if (!atlas) continue;
        CHECK(bound == atlas->bytes && bound == b.live_bytes && bound == b.peak_bytes,
              "atlas bound %zu: the atlas reports %zu, allocated %zu (peak %zu)", bound, atlas->bytes, b.live_bytes, b.peak_bytes);
        exact += bound == b.peak_bytes;
        /* fill_holes' scratch, on power-of-two tiles: a third of the pixels
           times (values + 1) floats */
        values = 1 + (desc.channels & MLOD_ATLAS_NORMAL ? 3 : 0) + (desc.channels & MLOD_ATLAS_COLOR ? 3 : 0);
        for (v = 0; v < V; v++) pyramid += (double)views[v].width * views[v].height / 3.0 * (values + 1) * sizeof(float);
        before = b.live_bytes;
        b.peak_bytes = b.live_bytes;
        CHECK(mlod_atlas_fill_holes(atlas, NULL, NULL) == MLOD_OK, "atlas bound: fill holes");
        if (trial % 2)
            CHECK((double)(b.peak_bytes - before) <= 1.01 * pyramid + 8.0 * V && (double)(b.peak_bytes - before) >= 0.9 * pyramid,
                  "atlas: fill_holes took %zu bytes, the manual says about %.0f", b.peak_bytes - before, pyramid);
        mlod_atlas_destroy(atlas);
        CHECK(b.live_bytes == 0, "atlas: %zu bytes left after destroy", b.live_bytes);
    }
    /* what mlod_atlas_create refuses has no size */
    {
        mlod_view views[2];
        mlod_atlas_desc desc;
        memset(&desc, 0, sizeof desc);
        views[0] = views[1] = tu_view(MLOD_VIEW_PERSPECTIVE);
        views[1].width = 0;
        CHECK(mlod_atlas_bound(views, 2, &desc) == 0 && mlod_atlas_bound(views, 0, &desc) == 0 &&
                  mlod_atlas_bound(NULL, 1, &desc) == 0 && mlod_atlas_bound(views, 1, NULL) == 0,
              "atlas bound: not 0 for an empty tile, no views or no desc");
        desc.disc_scale = 1.5f;
        CHECK(mlod_atlas_bound(views, 1, &desc) == 0, "atlas bound: not 0 for disc_scale 1.5");
        desc.disc_scale = 0.0f;
        desc.channels = 4;
        CHECK(mlod_atlas_bound(views, 1, &desc) == 0, "atlas bound: not 0 for unknown channels");
        desc.channels = 0;
        views[0].width = views[0].height = 0xffffffffu;
        views[1] = views[0];
        CHECK(mlod_atlas_bound(views, 2, &desc) == 0, "atlas bound: not 0 for an atlas of 2^33 x 2^32 pixels");
    }
    printf("  atlas bounds: %u atlases, each bound what mlod_atlas_create allocated\n", exact);
}

/* Large buffers get transparent huge pages where the system leaves them
   to the program (madvise mode) or always has them: after
   mlod__alloc_array of 64 MiB, touched, /proc/self/smaps shows huge pages
   in its mapping.  Not checked (and not counted) where the system has no
   huge pages or no smaps, or the build turned the advice off. */
static void test_huge_pages(void)
{
#if defined(__linux__) && !defined(MANYLODS_NO_HUGE_PAGES)
    char mode[128] = "", line[256];
    FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    mlod_allocator a = mlod_default_allocator();
    size_t bytes = (size_t)64 << 20, total = 0, huge_kb = 0;
    unsigned char *p;
    uintptr_t at;
    int inside = 0;
    if (f) {
        if (!fgets(mode, sizeof mode, f)) mode[0] = '\0';
        fclose(f);
    }
    if (!strstr(mode, "[madvise]") && !strstr(mode, "[always]")) {
        printf("  huge pages: not checked (the system's mode: %s)\n", mode[0] ? mode : "unknown");
        return;
    }
    p = (unsigned char *)mlod__alloc_array(&a, bytes, 1, &total);
    CHECK(p != NULL && total == bytes, "huge pages: 64 MiB allocated");
    if (!p) return;
    memset(p, 1, bytes);
    at = (uintptr_t)p + bytes / 2;
    f = fopen("/proc/self/smaps", "r");
    while (f && fgets(line, sizeof line, f)) {
        unsigned long long lo, hi;
        size_t kb;
        if (sscanf(line, "%llx-%llx", &lo, &hi) == 2 && strchr(line, '-') && strchr(line, '-') < strchr(line, ' '))
            inside = lo <= at && at < hi;
        else if (inside && sscanf(line, "AnonHugePages: %zu kB", &kb) == 1)
            huge_kb = kb;
    }
    if (f) {
        fclose(f);
        CHECK(huge_kb >= 2048, "huge pages: the 64 MiB buffer has %zu kB of huge pages (system mode %s)", huge_kb, mode);
        printf("  huge pages: %zu kB of a 64 MiB buffer\n", huge_kb);
    } else {
        printf("  huge pages: not checked (no /proc/self/smaps)\n");
    }
    mlod__free(&a, p);
#endif
}

int main(void)
{
    if (!scene_room(&room)) return 1;
    room_tree = tu_build(&room, 20000, 5, MLOD_ATTR_CONE);
    if (!room_tree) return 1;
    make_views();
    test_failed_updates();
    test_build_bounds();
    test_cut_bounds();
    test_atlas_bounds();
    test_huge_pages();
    mlod_tree_destroy(room_tree);
    scene_free(&room);
    return test_finish();
}
