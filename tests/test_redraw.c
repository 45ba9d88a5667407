/* tests/test_redraw.c - the atlas follows the cut: mlod_splat keeps the
   tiles that show what it would draw and redraws the others.

   Each step changes something (nothing; a refit to the same mesh; part of
   the mesh moving; some views moving; colours alone; disc_scale; another
   writer of the pixels; a reset; another cut; another tree; arrays
   written by hand), updates the cuts and splats into the atlas kept from
   step to step.  Checked at every step, for incremental, basic and lazy
   cuts, and with an atlas that fills its holes (mlod_atlas_desc.fill_holes):
   - the kept atlas equals, bit for bit in depth, normals and colours, a
     new atlas splatted from scratch (a full redraw; for fill_holes, a
     full redraw without it, then mlod_atlas_fill_holes);
   - atlas->redrawn is the number of tiles this file expects redrawn, from
     its own record of the documented rule: a tile is kept when its view
     and its cut's entries (nodes, and which are culled) did not change in
     any update since it was drawn, and no drawn node changed (its sphere,
     cone or colour bits, or those of a leaf below it) in any refit since,
     found by comparing the tree's arrays before and after each refit;
   - atlas->patched is the number of the others this file expects patched
     rather than drawn whole: a tile of an atlas that does not fill holes,
     drawn from a basic cut (an incremental or basic update, or a lazy one
     that made no move) of the same cut object, view bytes and tree object
     as now, every update since giving a basic cut of that view, with a
     refit since and no arrays written by hand since the last refit,
     which changed at most half of the tree's internal nodes at depth 10;
   - mlod_cut_view.version moves exactly when the view or the entries
     change, and no two cuts share one.
   REDRAW_VERBOSE=1 in the environment prints each step's redrawn tiles. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

#define VIEWS 24u
#define LEAVES 6000u

/* What this file knows of the tree: the arrays as they were, and per node
   the step of the last refit that changed it or a leaf below it. */
typedef struct shadow_tree {
    float *spheres, *cones, *colors;
    int *changed_at;
    int refit_at; /* the last refit's step (-1: none) */
    int by_hand;  /* arrays written by hand, the revision counted up, since the last refit */
    double share; /* of the internal nodes at depth 10 (or the deepest there are), those the last refit changed */
} shadow_tree;

/* What this file knows of one cut: per view the entries of its last
   update, the view, and the last step whose update changed either. */
typedef struct shadow_cut {
    uint32_t *nodes[VIEWS];
    uint8_t *culled[VIEWS];
    uint32_t count[VIEWS];
    mlod_view view[VIEWS];
    int known[VIEWS];
    int changed_at[VIEWS];
    uint64_t version[VIEWS];
    int basis_at[VIEWS]; /* the last step whose update did not give the basic cut of the same view and tree */
    int basic[VIEWS];    /* the list is a basic cut (of the tree of the last update) */
    const mlod_tree *tree; /* of the last update */
    int updated_at;
} shadow_cut;

/* What a tile shows, by this file's record: the step it was drawn or last
   kept at, the cut and tree it shows, -1: nothing known. */
typedef struct shadow_atlas {
    int shown_at[VIEWS];
    const shadow_cut *cut[VIEWS];
    const mlod_tree *tree[VIEWS];
    int basis_at[VIEWS]; /* the cut's basis_at when drawn from a basic cut of the tree as it was; else -2 */
    float scale;
} shadow_atlas;

static void shadow_tree_copy(shadow_tree *s, const mlod_tree *t)
{
    size_t n = t->node_count;
    memcpy(s->spheres, t->spheres, 16 * n);
    if (t->cones) memcpy(s->cones, t->cones, 16 * n);
    if (t->colors) memcpy(s->colors, t->colors, 12 * n);
}

static void shadow_tree_init(shadow_tree *s, const mlod_tree *t)
{
    size_t n = t->node_count;
    s->spheres = (float *)malloc(16 * n);
    s->cones = (float *)malloc(16 * n);
    s->colors = (float *)malloc(12 * n);
    s->changed_at = (int *)calloc(n, sizeof(int));
    s->refit_at = -1;
    s->by_hand = 0;
    s->share = 0.0;
    shadow_tree_copy(s, t);
}

static void shadow_tree_free(shadow_tree *s)
{
    free(s->spheres);
    free(s->cones);
    free(s->colors);
    free(s->changed_at);
}

/* After a refit at `step`: which nodes it changed (bits of the node or of
   a leaf below it), by comparing with the copy. */
static void shadow_tree_refitted(shadow_tree *s, const mlod_tree *t, int step)
{
    uint32_t n = t->node_count, i;
    uint8_t *moved = (uint8_t *)calloc(n, 1);
    for (i = n; i-- > 0;) {
        int differ = memcmp(s->spheres + 4 * (size_t)i, t->spheres + 4 * (size_t)i, 16) != 0 ||
                     (t->cones && memcmp(s->cones + 4 * (size_t)i, t->cones + 4 * (size_t)i, 16) != 0) ||
                     (t->colors && memcmp(s->colors + 3 * (size_t)i, t->colors + 3 * (size_t)i, 12) != 0);
        if (i < t->leaf_count - 1) /* internal: a leaf below changed */
            moved[i] = moved[2 * i + 1] | moved[2 * i + 2];
        else
            moved[i] = (uint8_t)differ;
        if (moved[i]) s->changed_at[i] = step;
    }
    s->refit_at = step;
    s->by_hand = 0;
    free(moved);
    shadow_tree_copy(s, t);
}

static uint32_t deferrals; /* view-updates a lazy update's budget deferred */

static void shadow_cut_init(shadow_cut *s)
{
    memset(s, 0, sizeof *s);
}

static void shadow_cut_free(shadow_cut *s)
{
    uint32_t v;
    for (v = 0; v < VIEWS; v++) {
        free(s->nodes[v]);
        free(s->culled[v]);
    }
}

/* After an update at `step` of a cut in `mode` with `tree`: which views
   changed (view bytes, entries, culled flags), the versions' rule, and
   which lists are basic cuts (a lazy update's when it made no move: then
   its list must equal a basic cut, checked against one). */
static void shadow_cut_updated(shadow_cut *s, const mlod_cut *cut, const mlod_view *views, int step, mlod_cut_mode mode,
                               const mlod_tree *tree)
{
    uint32_t v, i;
    mlod_cut *basic = NULL;
    mlod_cut_params bp;
    mlod_error e;
    memset(&bp, 0, sizeof bp);
    bp.mode = MLOD_CUT_BASIC;
    bp.epsilon = 1.5f; /* run_steps's */
    if (mode == MLOD_CUT_LAZY)
        CHECK(mlod_cut_create(VIEWS, NULL, &basic, &e) == MLOD_OK && mlod_cut_update(basic, tree, views, &bp, &e) == MLOD_OK,
              "a basic cut to compare with: %s", e.message);
    for (v = 0; v < VIEWS; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        int view_same = s->known[v] && memcmp(&s->view[v], &views[v], sizeof(mlod_view)) == 0;
        /* (a view a budget deferred holds its list before, of another view or tree) */
        int is_basic = mode != MLOD_CUT_LAZY || (!cv.deferred && cv.steps == 0 && cv.coarse == 0);
        deferrals += (uint32_t)cv.deferred;
        int same = view_same && s->count[v] == cv.count;
        if (mode == MLOD_CUT_LAZY && is_basic && basic) {
            mlod_cut_view b = mlod_cut_get(basic, v);
            CHECK(b.count == cv.count && memcmp(b.nodes, cv.nodes, 4 * (size_t)cv.count) == 0,
                  "view %u, step %d: a lazy list that made no move is the basic cut", v, step);
        }
        if (!(view_same && s->basic[v] && is_basic && s->tree == tree)) s->basis_at[v] = step;
        s->basic[v] = is_basic;
        for (i = 0; same && i < cv.count; i++)
            same = s->nodes[v][i] == cv.nodes[i] && s->culled[v][i] == (cv.status[i] == MLOD_STATUS_CULLED);
        if (!same) s->changed_at[v] = step;
        if (s->known[v])
            CHECK((cv.version == s->version[v]) == same, "view %u, step %d: the version %s with %s entries", v, step,
                  cv.version == s->version[v] ? "stayed" : "moved", same ? "the same" : "other");
        free(s->nodes[v]);
        free(s->culled[v]);
        s->nodes[v] = (uint32_t *)malloc(sizeof(uint32_t) * (cv.count + 1));
        s->culled[v] = (uint8_t *)malloc(cv.count + 1);
        for (i = 0; i < cv.count; i++) {
            s->nodes[v][i] = cv.nodes[i];
            s->culled[v][i] = cv.status[i] == MLOD_STATUS_CULLED;
        }
        s->count[v] = cv.count;
        s->view[v] = views[v];
        s->known[v] = 1;
        s->version[v] = cv.version;
    }
    s->tree = tree;
    s->updated_at = step;
    mlod_cut_destroy(basic);
}

/* After a reset: every view's entries are gone (the version moves). */
static void shadow_cut_reset(shadow_cut *s, const mlod_cut *cut, int step)
{
    uint32_t v;
    for (v = 0; v < VIEWS; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        CHECK(cv.version != s->version[v] && cv.count == 0, "view %u: a reset gives a new version and no entries", v);
        s->count[v] = 0;
        s->version[v] = cv.version;
        s->changed_at[v] = step;
        s->basic[v] = 0;
        s->basis_at[v] = step;
    }
}

/* The tiles this file expects mlod_splat to draw whole at `step` from cut
   (its record sc) and tree (its record st), and to patch (*patches), and
   its record updated. */
static uint32_t expected_redraws(shadow_atlas *sa, const shadow_cut *sc, const shadow_tree *st, const mlod_tree *tree,
                                 const mlod_atlas *atlas, int step, uint32_t *patches)
{
    uint32_t v, i, redraws = 0;
    *patches = 0;
    for (v = 0; v < VIEWS; v++) {
        int keep = sa->shown_at[v] >= 0 && sa->cut[v] == sc && sa->scale == atlas->disc_scale &&
                   sc->changed_at[v] <= sa->shown_at[v];
        int patch = sa->shown_at[v] >= 0 && sa->cut[v] == sc && sa->scale == atlas->disc_scale && sa->tree[v] == tree &&
                    !atlas->fill_holes && sa->basis_at[v] == sc->basis_at[v] && st->refit_at > sa->shown_at[v] &&
                    !st->by_hand && st->share <= 0.5;
        /* a drawn node changed, or drawn from another tree; a tile that
           draws nothing is the same whatever the tree */
        for (i = 0; keep && i < sc->count[v]; i++)
            if (!sc->culled[v][i] && (sa->tree[v] != tree || st->changed_at[sc->nodes[v][i]] > sa->shown_at[v]))
                keep = 0;
        redraws += (uint32_t)(!keep && !patch);
        *patches += (uint32_t)(!keep && patch);
        sa->shown_at[v] = step;
        sa->cut[v] = sc;
        sa->tree[v] = tree;
        /* a basic cut of the tree as it is: updated with it since its last refit */
        sa->basis_at[v] = sc->basic[v] && sc->tree == tree && sc->updated_at >= st->refit_at ? sc->basis_at[v] : -2;
    }
    sa->scale = atlas->disc_scale;
    return redraws;
}

static void forget_tiles(shadow_atlas *sa)
{
    uint32_t v;
    for (v = 0; v < VIEWS; v++) sa->shown_at[v] = -1;
}

/* The atlas against a full redraw into a new atlas of the same desc (one
   that fills holes: a full redraw without, then mlod_atlas_fill_holes). */
static void check_full(const mlod_atlas *atlas, const mlod_atlas_desc *desc, const mlod_tree *tree,
                       const mlod_cut *cut, const mlod_view *views, const mlod_parallel *par, const char *what)
{
    mlod_atlas *fresh = NULL;
    mlod_error e;
    size_t pixels = (size_t)atlas->width * atlas->height;
    mlod_atlas_desc d = *desc;
    d.disc_scale = atlas->disc_scale;
    d.fill_holes = 0;
    if (mlod_atlas_create(views, VIEWS, &d, NULL, &fresh, &e) != MLOD_OK ||
        mlod_splat(fresh, tree, cut, views, par, &e) != MLOD_OK ||
        (desc->fill_holes && mlod_atlas_fill_holes(fresh, par, &e) != MLOD_OK)) {
        CHECK(0, "%s: a full redraw failed: %s", what, e.message);
        mlod_atlas_destroy(fresh);
        return;
    }
    CHECK(fresh->redrawn == VIEWS, "%s: a new atlas draws every tile (%u)", what, fresh->redrawn);
    CHECK(memcmp(fresh->depth, atlas->depth, 4 * pixels) == 0, "%s: depth equals a full redraw's", what);
    CHECK(!atlas->normal || memcmp(fresh->normal, atlas->normal, 12 * pixels) == 0, "%s: normals equal", what);
    CHECK(!atlas->color || memcmp(fresh->color, atlas->color, 12 * pixels) == 0, "%s: colours equal", what);
    mlod_atlas_destroy(fresh);
}

/* A twisting torus: vertices with y above `above` take the twist of
   time t, the rest stay at rest; colours shifted by `tint` there. */
static void pose(const scene_mesh *rest, scene_mesh *out, float t, float above, float tint)
{
    uint32_t i;
    scene_deform(rest, t, out->positions, out->normals);
    for (i = 0; i < rest->vertex_count; i++) {
        int k;
        if (rest->positions[3 * i + 1] < above) {
            memcpy(out->positions + 3 * i, rest->positions + 3 * i, 12);
            memcpy(out->normals + 3 * i, rest->normals + 3 * i, 12);
        }
        for (k = 0; k < 3; k++)
            out->colors[3 * i + k] = rest->colors[3 * i + k] + (rest->positions[3 * i + 1] >= above ? tint : 0.0f);
    }
}

/* A refit at `step`; all: the revision was counted up by hand before, so
   the refit marks every node (mlod_refit_mesh).  Then the share of the
   internal nodes at depth 10 (or the deepest there are) it changed. */
static void refit(mlod_tree *tree, shadow_tree *st, const scene_mesh *m, const mlod_parallel *par, int step, int all)
{
    mlod_mesh mesh = tu_mesh(m);
    mlod_error e;
    uint32_t i, depth = 0, first = 0, last = 0, changed = 0;
    CHECK(mlod_refit_mesh(tree, &mesh, par, &e) == MLOD_OK, "refit: %s", e.message);
    shadow_tree_refitted(st, tree, step);
    for (i = 0; all && i < tree->node_count; i++) st->changed_at[i] = step;
    while (((uint64_t)2 << depth) <= 2 * (uint64_t)tree->leaf_count - 1) depth++; /* the deepest node's, then 10 */
    if (depth > 10) depth = 10;
    while (depth > 0 && !mlod_tree_depth_nodes(tree->leaf_count, depth, &first, &last)) depth--;
    if (depth == 0) first = last = 0;
    for (i = first; i <= last; i++) changed += st->changed_at[i] == step;
    st->share = (double)changed / (double)(last - first + 1);
}

/* One mode's run through the steps, into an atlas that fills holes or not. */
/* Lazy updates with a budget (mlod_cut_params.budget) when set: a sixth
   of what every view's bound (tu_lazy_bound) asks, so that
   most updates defer views. */
static int budgeted;

static uint64_t budget_of(const mlod_cut *cut, uint32_t lazy_steps)
{
    uint64_t sum = 0;
    uint32_t v;
    if (!budgeted) return 0;
    for (v = 0; v < VIEWS; v++) sum += tu_lazy_bound(mlod_cut_get(cut, v).count, lazy_steps);
    return sum / 6 + 1;
}

static void run_steps(mlod_cut_mode mode, uint32_t fill, const mlod_parallel *par)
{
    static const mlod_view_kind kinds[5] = {MLOD_VIEW_PARABOLOID, MLOD_VIEW_PERSPECTIVE, MLOD_VIEW_DUAL_PARABOLOID,
                                            MLOD_VIEW_ORTHOGRAPHIC, MLOD_VIEW_CUBE};
    scene_mesh rest, posed;
    mlod_tree *tree, *other;
    mlod_cut *cut = NULL, *cut2 = NULL;
    mlod_atlas *atlas = NULL;
    mlod_atlas_desc desc;
    mlod_cut_params params;
    mlod_view views[VIEWS];
    shadow_tree st, st2;
    shadow_cut sc, sc2;
    shadow_atlas sa;
    mlod_error e;
    uint64_t rng = 77 + (uint64_t)mode;
    double c[3], R;
    uint32_t v, expect, patches;
    int step = 0;
    char what[96];
    const char *mode_name = mode == MLOD_CUT_BASIC ? "basic" : mode == MLOD_CUT_INCREMENTAL ? "incremental" : "lazy";
    deferrals = 0;

    memset(&rest, 0, sizeof rest);
    memset(&posed, 0, sizeof posed);
    if (!scene_torus(&rest, 1.0f, 0.35f, 48, 24)) {
        CHECK(0, "scene");
        return;
    }
    scene_color_from_position(&rest);
    scene_alloc(&posed, rest.vertex_count, rest.index_count, 1, 1);
    memcpy(posed.indices, rest.indices, 4 * (size_t)rest.index_count);
    pose(&rest, &posed, 0.0f, -1e9f, 0.0f);
    tree = tu_build(&posed, LEAVES, 5, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    other = tu_build(&posed, LEAVES, 5, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    tu_bounds(&rest, c, &R);
    for (v = 0; v < VIEWS; v++) {
        views[v] = tu_random_view(&rng, kinds[v % 5], c, R);
        if (views[v].kind != MLOD_VIEW_CUBE) views[v].width = views[v].height = 16 + 8 * (v % 4);
        views[v].far_plane = INFINITY;
        if (views[v].kind == MLOD_VIEW_ORTHOGRAPHIC) views[v].far_plane = views[v].near_plane + (float)(10 * R);
    }
    shadow_tree_init(&st, tree);
    shadow_tree_init(&st2, other);
    shadow_cut_init(&sc);
    shadow_cut_init(&sc2);
    forget_tiles(&sa);
    sa.scale = 0.0f;
    memset(&desc, 0, sizeof desc);
    desc.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
    desc.fill_holes = fill;
    memset(&params, 0, sizeof params);
    params.mode = mode;
    params.epsilon = 1.5f;
    params.lazy_steps = 2;
    params.parallel = par;
    if (mlod_cut_create(VIEWS, NULL, &cut, &e) != MLOD_OK || mlod_cut_create(VIEWS, NULL, &cut2, &e) != MLOD_OK ||
        mlod_atlas_create(views, VIEWS, &desc, NULL, &atlas, &e) != MLOD_OK) {
        CHECK(0, "setup: %s", e.message);
        goto done;
    }

#define UPDATE(CUT, SC, TREE)                                                                                          \
    do {                                                                                                               \
        params.budget = budget_of(CUT, params.lazy_steps);                                                             \
        CHECK(mlod_cut_update(CUT, TREE, views, &params, &e) == MLOD_OK, "update: %s", e.message);                  \
        shadow_cut_updated(&SC, CUT, views, step, mode, TREE);                                                         \
    } while (0)
#define SPLAT(CUT, SC, TREE, ST, NAME)                                                                                 \
    do {                                                                                                               \
        snprintf(what, sizeof what, "%s%s, step %d (%s)", mode_name, fill ? " filled" : "", step, NAME);             \
        expect = expected_redraws(&sa, &SC, &ST, TREE, atlas, step, &patches);                                         \
        CHECK(mlod_splat(atlas, TREE, CUT, views, par, &e) == MLOD_OK, "%s: splat: %s", what, e.message);            \
        CHECK(atlas->redrawn == expect, "%s: %u tiles redrawn, %u expected", what, atlas->redrawn, expect);           \
        CHECK(atlas->patched == patches, "%s: %u tiles patched, %u expected", what, atlas->patched, patches);        \
        if (getenv("REDRAW_VERBOSE")) printf("%s: %u redrawn, %u patched\n", what, atlas->redrawn, atlas->patched);   \
        check_full(atlas, &desc, TREE, CUT, views, par, what);                                                         \
        step++;                                                                                                        \
    } while (0)

    /* 0: the first frame draws every tile (a lazy cut converged first) */
    for (v = 0; v < (mode != MLOD_CUT_LAZY ? 1u : budgeted ? 80u : 20u); v++) UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "first frame");
    CHECK(atlas->redrawn == VIEWS, "the first splat draws every tile");
    /* 1: nothing changed */
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "nothing changed");
    CHECK(atlas->redrawn == 0, "nothing changed: nothing redrawn (%u)", atlas->redrawn);
    /* 2: a refit to the same mesh */
    refit(tree, &st, &posed, par, step, 0);
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "refit to the same mesh");
    CHECK(atlas->redrawn == 0, "a refit that changed nothing redraws nothing (%u)", atlas->redrawn);
    /* 3, 4, 5: the top of the torus twisting, the rest still */
    for (v = 0; v < 3; v++) {
        pose(&rest, &posed, 0.3f * (float)(v + 1), 0.15f, 0.0f);
        refit(tree, &st, &posed, par, step, 0);
        UPDATE(cut, sc, tree);
        SPLAT(cut, sc, tree, st, "a part moving");
    }
    /* 6: three views moving a little */
    for (v = 0; v < 3; v++) views[5 * v + 1].position[0] += 0.01f * (float)R;
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "three views moving");
    /* 7: colours alone */
    pose(&rest, &posed, 0.9f, 0.15f, 0.25f);
    refit(tree, &st, &posed, par, step, 0);
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "colours of a part");
    /* 8: another disc_scale */
    atlas->disc_scale = 0.5f;
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "disc_scale");
    /* 9: ISM, then the cut again */
    CHECK(mlod_splat_ism(atlas, tree, views, 64, 3, par, &e) == MLOD_OK, "ism: %s", e.message);
    forget_tiles(&sa);
    SPLAT(cut, sc, tree, st, "after ISM");
    CHECK(atlas->redrawn == VIEWS, "after ISM every tile is drawn");
    /* 10: holes filled, then the cut again (an atlas that fills holes
       itself has nothing to fill) */
    CHECK(mlod_atlas_fill_holes(atlas, par, &e) == MLOD_OK, "fill: %s", e.message);
    if (!fill) forget_tiles(&sa);
    SPLAT(cut, sc, tree, st, "after filling");
    /* 11: mlod_atlas_invalidate */
    mlod_atlas_invalidate(atlas);
    forget_tiles(&sa);
    SPLAT(cut, sc, tree, st, "invalidated");
    CHECK(atlas->redrawn == VIEWS, "an invalidated atlas draws every tile");
    /* 12: another cut of the same views and tree */
    UPDATE(cut2, sc2, tree);
    SPLAT(cut2, sc2, tree, st, "another cut");
    for (v = 0; v < VIEWS; v++)
        CHECK(mlod_cut_get(cut, v).version != mlod_cut_get(cut2, v).version, "two cuts never share a version");
    /* 13: back to the first cut, nothing changed in it */
    SPLAT(cut, sc, tree, st, "the first cut again");
    /* 14: the first cut reset, then updated */
    mlod_cut_reset(cut);
    shadow_cut_reset(&sc, cut, step);
    SPLAT(cut, sc, tree, st, "reset");
    UPDATE(cut, sc, tree);
    SPLAT(cut, sc, tree, st, "after the reset");
    /* 16: the same cut splatted with another tree of the same mesh (a cut
       of `tree` drawn with `other`'s nodes): all but empty tiles */
    SPLAT(cut, sc, other, st2, "another tree");
    /* 17: the cut moved to the other tree */
    UPDATE(cut, sc, other);
    SPLAT(cut, sc, other, st2, "cut of the other tree");
    /* 18: arrays written by hand, the revision counted up: every tile */
    other->spheres[4 * (size_t)(other->node_count - 1) + 3] *= 1.0f;
    other->revision++;
    for (v = 0; v < other->node_count; v++) st2.changed_at[v] = step;
    st2.by_hand = 1;
    UPDATE(cut, sc, other);
    SPLAT(cut, sc, other, st2, "revision counted up by hand");
    /* 19, 20: the whole torus twisting, the views turning */
    for (v = 0; v < 2; v++) {
        uint32_t w;
        pose(&rest, &posed, 1.2f + 0.2f * (float)v, -1e9f, 0.0f);
        refit(other, &st2, &posed, par, step, v == 0);
        for (w = 0; w < VIEWS; w += 2) views[w].forward[1] += 0.01f;
        UPDATE(cut, sc, other);
        SPLAT(cut, sc, other, st2, "everything moving");
    }
#undef UPDATE
#undef SPLAT
    if (budgeted) {
        CHECK(deferrals >= 4 * VIEWS, "a budget deferred only %u view-updates", deferrals);
        printf("  %s%s with a budget: %u view-updates deferred\n", mode_name, fill ? " filled" : "", deferrals);
    }
done:
    mlod_atlas_destroy(atlas);
    mlod_cut_destroy(cut);
    mlod_cut_destroy(cut2);
    mlod_tree_destroy(tree);
    mlod_tree_destroy(other);
    shadow_tree_free(&st);
    shadow_tree_free(&st2);
    shadow_cut_free(&sc);
    shadow_cut_free(&sc2);
    scene_free(&rest);
    scene_free(&posed);
}

/* A patch leaves out the entries whose sphere lies outside the cones of
   the marked pixels (mlod__marked_cones, mlod__patch_outside): checked
   against drawing each node alone.  Square paraboloid views at random,
   sphere and tangent discs, disc_scale 1 and 0.5, marked pixels at random
   (scattered, or a few clusters); for every node of the tree the cones
   leave out, none of the pixels its disc draws into an empty tile is
   marked.  The cones must leave out a good share of the nodes (else the
   check says little). */
static void test_patch_cones(void)
{
    scene_mesh mesh;
    mlod_tree *tree;
    uint64_t rng = 4242;
    double c[3], R;
    uint32_t trial, left_out = 0, looked = 0;
    memset(&mesh, 0, sizeof mesh);
    if (!scene_torus(&mesh, 1.0f, 0.35f, 48, 24)) {
        CHECK(0, "scene");
        return;
    }
    tree = tu_build(&mesh, 3000, 9, MLOD_ATTR_CONE);
    tu_bounds(&mesh, c, &R);
    for (trial = 0; trial < 48 && tree; trial++) {
        mlod_view view = tu_random_view(&rng, MLOD_VIEW_PARABOLOID, c, R);
        mlod_atlas_desc desc;
        mlod_atlas *atlas = NULL;
        mlod__band band;
        mlod__pview pv;
        mlod__fdiscs fast;
        mlod__cones cones;
        mlod_error e;
        uint8_t *mask;
        uint32_t side = 8 + (uint32_t)(scene_rng_double(&rng) * 56), x, y, k, node, clusters;
        view.width = view.height = side;
        memset(&desc, 0, sizeof desc);
        desc.splat = trial % 2 ? MLOD_SPLAT_SPHERES : MLOD_SPLAT_TANGENT;
        desc.disc_scale = trial % 4 < 2 ? 1.0f : 0.5f;
        if (mlod_atlas_create(&view, 1, &desc, NULL, &atlas, &e) != MLOD_OK || mlod__atlas_ids(atlas, NULL) != MLOD_OK) {
            CHECK(0, "atlas: %s", e.message);
            mlod_atlas_destroy(atlas);
            break;
        }
        mask = (uint8_t *)calloc((size_t)atlas->width * atlas->height, 1);
        clusters = trial % 3; /* 0: scattered pixels, else that many clusters */
        for (k = 0; k < (clusters ? clusters : 6u); k++) {
            uint32_t cx = (uint32_t)(scene_rng_double(&rng) * side), cy = (uint32_t)(scene_rng_double(&rng) * side);
            uint32_t reach = clusters ? 1 + (uint32_t)(scene_rng_double(&rng) * 3) : 0;
            for (y = cy >= reach ? cy - reach : 0; y <= cy + reach && y < side; y++)
                for (x = cx >= reach ? cx - reach : 0; x <= cx + reach && x < side; x++) mask[y * atlas->width + x] = 1;
        }
        mlod__tile_band(atlas, tree, 0, &band);
        band.mask = mask;
        CHECK(mlod__view_prepare(&view, &pv, NULL) == MLOD_OK, "trial %u: the view", trial);
        mlod__fast_prepare(&pv, 1.0);
        if (mlod__marked_cones(&pv, &band, side, &cones)) {
            uint32_t wrong = 0, first = 0;
            band.mask = NULL;
            band.fast = mlod__disc_prepare(&pv, &fast) ? &fast : NULL;
            for (node = 0; node < tree->node_count; node++) {
                uint32_t hits = 0;
                if (!mlod__patch_outside(&pv, tree->spheres + 4 * (size_t)node, &cones)) continue;
                left_out++;
                mlod__band_clear(&band, side);
                mlod__draw_nodes(&band, &pv, &node, 1);
                for (y = 0; y < side; y++)
                    for (x = 0; x < side; x++)
                        hits += mask[y * atlas->width + x] && atlas->depth[y * atlas->width + x] < INFINITY;
                if (hits && !wrong++) first = node;
            }
            CHECK(wrong == 0, "trial %u (%ux%u, %s, disc_scale %g): %u nodes left out draw marked pixels (node %u)",
                  trial, side, side, trial % 2 ? "spheres" : "tangent", desc.disc_scale, wrong, first);
            looked += tree->node_count;
        }
        free(mask);
        mlod_atlas_destroy(atlas);
    }
    CHECK(looked > 0 && left_out > looked / 4, "the cones left out %u of %u node-views", left_out, looked);
    mlod_tree_destroy(tree);
    scene_free(&mesh);
}

/* The atlas's bytes: mlod_atlas_bound, with its per-view record. */
static void test_bytes(void)
{
    mlod_view views[3];
    mlod_atlas_desc desc;
    mlod_atlas *atlas = NULL;
    mlod_error e;
    uint32_t v;
    memset(&desc, 0, sizeof desc);
    for (v = 0; v < 3; v++) {
        views[v] = tu_view(MLOD_VIEW_PERSPECTIVE);
        views[v].height = 64 * v + 1; /* 1, 2 and 3 bands */
    }
    CHECK(mlod_atlas_create(views, 3, &desc, NULL, &atlas, &e) == MLOD_OK, "create: %s", e.message);
    if (!atlas) return;
    CHECK(atlas->bytes == mlod_atlas_bound(views, 3, &desc), "bytes %zu = bound %zu", atlas->bytes,
          mlod_atlas_bound(views, 3, &desc));
    CHECK(atlas->bytes == sizeof(mlod_atlas) + 4 * (size_t)atlas->width * atlas->height + 3 * 44 + 4 + 6 * 4,
          "bytes: pixels, 44 per view and 4 more, 4 per band (%zu)", atlas->bytes);
    mlod_atlas_invalidate(NULL);
    mlod_atlas_destroy(atlas);
    atlas = NULL;
    desc.fill_holes = 2;
    CHECK(mlod_atlas_create(views, 3, &desc, NULL, &atlas, &e) == MLOD_ERROR_INVALID_ARGUMENT && !atlas &&
              strstr(e.message, "fill_holes"),
          "fill_holes 2 is refused: %s", e.message);
    CHECK(mlod_atlas_bound(views, 3, &desc) == 0, "mlod_atlas_bound refuses fill_holes 2");
}

int main(int argc, char **argv)
{
    mlod_pool *pools[3];
    mlod_parallel hooks[5];
    test_groups_begin(argc, argv);
    tu_hooks(pools, hooks);
    TEST_GROUP("incremental", run_steps(MLOD_CUT_INCREMENTAL, 0, &hooks[1]));
    TEST_GROUP("basic", run_steps(MLOD_CUT_BASIC, 0, &hooks[4]));
    TEST_GROUP("lazy", run_steps(MLOD_CUT_LAZY, 0, &hooks[2]));
    TEST_GROUP("filled", run_steps(MLOD_CUT_INCREMENTAL, 1, &hooks[3]));
    TEST_GROUP("filled_lazy", run_steps(MLOD_CUT_LAZY, 1, &hooks[0]));
    budgeted = 1;
    TEST_GROUP("lazy_budget", run_steps(MLOD_CUT_LAZY, 0, &hooks[1]));
    TEST_GROUP("filled_lazy_budget", run_steps(MLOD_CUT_LAZY, 1, &hooks[2]));
    budgeted = 0;
    TEST_GROUP("bytes", test_bytes());
    TEST_GROUP("patch_cones", test_patch_cones());
    mlod_pool_destroy(pools[0]);
    mlod_pool_destroy(pools[1]);
    mlod_pool_destroy(pools[2]);
    test_groups_end();
    return test_finish();
}
