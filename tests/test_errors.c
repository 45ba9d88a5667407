/* tests/test_errors.c - bad input returns the documented code with a
   message, outputs are NULL and objects unchanged; memory: every byte the
   library takes comes from the given allocator, is reported, and is given
   back; a failing allocator (each allocation in turn) gives
   MLOD_ERROR_OUT_OF_MEMORY and no leak. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

static tu_counter counter;
static mlod_allocator counting;

/* The returned code is a or b, the error struct agrees and has a message. */
static void check_error(mlod_result got, const mlod_error *e, mlod_result a, mlod_result b, const char *what)
{
    size_t len = 0;
    while (len < sizeof e->message && e->message[len]) len++;
    CHECK(got == a || got == b, "%s: returned %s, expected %s%s%s", what, mlod_result_name(got), mlod_result_name(a),
          a != b ? " or " : "", a != b ? mlod_result_name(b) : "");
    CHECK(e->code == got, "%s: error.code %d, returned %d", what, (int)e->code, (int)got);
    CHECK(len > 0 && len < sizeof e->message && e->message[len - 1] != '\n', "%s: message \"%.200s\" empty, unterminated or ending in a newline",
          what, e->message);
}

/* ------------------------------------------------------------------ build */

static void expect_build(const mlod_mesh *m, const mlod_build_desc *d, mlod_result a, mlod_result b, const char *what)
{
    mlod_tree *t = (mlod_tree *)&counter; /* any non-NULL value */
    mlod_error e;
    mlod_result r;
    memset(&e, 0, sizeof e);
    r = mlod_build_mesh(m, d, &t, &e);
    check_error(r, &e, a, b, what);
    CHECK(t == NULL, "%s: *out_tree not set to NULL", what);
    if (r == MLOD_OK) mlod_tree_destroy(t);
    CHECK(counter.live_blocks == 0, "%s: %lu blocks leaked", what, counter.live_blocks);
}

static void expect_points(const mlod_points *p, const mlod_build_desc *d, mlod_result a, mlod_result b, const char *what)
{
    mlod_tree *t = (mlod_tree *)&counter;
    mlod_error e;
    mlod_result r;
    memset(&e, 0, sizeof e);
    r = mlod_build_points(p, d, &t, &e);
    check_error(r, &e, a, b, what);
    CHECK(t == NULL, "%s: *out_tree not set to NULL", what);
    if (r == MLOD_OK) mlod_tree_destroy(t);
    CHECK(counter.live_blocks == 0, "%s: %lu blocks leaked", what, counter.live_blocks);
}

static int cancel_at_half(void *user, float f)
{
    (void)user;
    return f >= 0.5f;
}

static void test_build_errors(void)
{
    scene_mesh s;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(500, 1, MLOD_ATTR_CONE | MLOD_ATTR_COLOR | MLOD_ATTR_AREA | MLOD_ATTR_REFIT), d2;
    mlod_error e;
    uint32_t used, i;
    float keep;
    mlod_tree *t;
    scene_torus(&s, 1.0f, 0.3f, 12, 6);
    d.allocator = &counting;
    m = tu_mesh(&s);
    used = s.indices[s.index_count - 1];
    expect_build(NULL, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL mesh");
    expect_build(&m, NULL, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL desc");
    memset(&e, 0, sizeof e);
    check_error(mlod_build_mesh(&m, &d, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL out_tree");
    CHECK(mlod_build_mesh(NULL, &d, &t, NULL) == MLOD_ERROR_INVALID_ARGUMENT && t == NULL, "NULL error pointer: still a code");
    d2 = d;
    d2.sample_count = 0;
    expect_build(&m, &d2, MLOD_ERROR_EMPTY, MLOD_ERROR_EMPTY, "N = 0");
    d2.sample_count = MANYLODS_MAX_LEAVES + 1;
    expect_build(&m, &d2, MLOD_ERROR_OVERFLOW, MLOD_ERROR_INVALID_ARGUMENT, "N = MANYLODS_MAX_LEAVES + 1");
    d2.sample_count = 0xFFFFFFFFu;
    expect_build(&m, &d2, MLOD_ERROR_OVERFLOW, MLOD_ERROR_INVALID_ARGUMENT, "N = 2^32 - 1");
    /* N = MANYLODS_MAX_LEAVES is valid, but needs tens of GB: an allocator
       that refuses blocks above 64 MB makes it run out of memory */
    d2.sample_count = MANYLODS_MAX_LEAVES;
    counter.max_bytes = (size_t)64 << 20;
    expect_build(&m, &d2, MLOD_ERROR_OUT_OF_MEMORY, MLOD_ERROR_OUT_OF_MEMORY, "N = MANYLODS_MAX_LEAVES, 64 MB blocks");
    counter.max_bytes = 0;
    d2 = d;
    d2.attributes |= 1u << 9;
    expect_build(&m, &d2, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "unknown attribute bit");
    d2 = d;
    d2.attributes = (d.attributes & ~(uint32_t)MLOD_ATTR_REFIT) | MLOD_ATTR_REFIT_CACHE;
    expect_build(&m, &d2, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "MLOD_ATTR_REFIT_CACHE without MLOD_ATTR_REFIT");
    d2 = d;
    d2.radius_scale = NAN;
    expect_build(&m, &d2, MLOD_ERROR_NON_FINITE, MLOD_ERROR_INVALID_ARGUMENT, "radius_scale NaN");
    d2.radius_scale = INFINITY;
    expect_build(&m, &d2, MLOD_ERROR_NON_FINITE, MLOD_ERROR_INVALID_ARGUMENT, "radius_scale +inf");
    d2.radius_scale = -1.0f;
    expect_build(&m, &d2, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "radius_scale -1");
    /* the mesh */
    m.index_count = s.index_count - 2;
    expect_build(&m, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "index_count not a multiple of 3");
    m.index_count = 0;
    expect_build(&m, &d, MLOD_ERROR_EMPTY, MLOD_ERROR_EMPTY, "no triangles");
    m = tu_mesh(&s);
    m.positions = NULL;
    expect_build(&m, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL positions");
    m = tu_mesh(&s);
    m.indices = NULL;
    expect_build(&m, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL indices");
    m = tu_mesh(&s);
    s.indices[s.index_count - 1] = s.vertex_count;
    expect_build(&m, &d, MLOD_ERROR_INDEX_OUT_OF_RANGE, MLOD_ERROR_INDEX_OUT_OF_RANGE, "index == vertex_count");
    s.indices[s.index_count - 1] = 0xFFFFFFFFu;
    expect_build(&m, &d, MLOD_ERROR_INDEX_OUT_OF_RANGE, MLOD_ERROR_INDEX_OUT_OF_RANGE, "index 2^32 - 1");
    s.indices[s.index_count - 1] = used;
    m.vertex_count = 0;
    expect_build(&m, &d, MLOD_ERROR_INDEX_OUT_OF_RANGE, MLOD_ERROR_EMPTY, "vertex_count 0 (indices out of range, or empty)");
    m = tu_mesh(&s);
    for (i = 0; i < 3; i++) {
        static const char *names[3] = {"NaN position", "+inf position", "-inf position"};
        keep = s.positions[3 * used + i];
        s.positions[3 * used + i] = i == 0 ? NAN : i == 1 ? INFINITY : -INFINITY;
        expect_build(&m, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, names[i]);
        s.positions[3 * used + i] = keep;
    }
    keep = s.normals[3 * used + 1];
    s.normals[3 * used + 1] = NAN;
    expect_build(&m, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN normal (cones asked)");
    s.normals[3 * used + 1] = keep;
    keep = s.colors[3 * used + 2];
    s.colors[3 * used + 2] = INFINITY;
    expect_build(&m, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "infinite colour (colours asked)");
    s.colors[3 * used + 2] = keep;
    /* every triangle of zero area */
    {
        float *flat = (float *)malloc(sizeof(float) * 3 * s.vertex_count);
        for (i = 0; i < s.vertex_count; i++) scene_set3(flat, i, (double)(i % 5), 2.0 * (i % 5), -1.0 * (i % 5));
        m.positions = flat;
        expect_build(&m, &d, MLOD_ERROR_EMPTY, MLOD_ERROR_EMPTY, "all triangles of zero area");
        for (i = 0; i < 3 * s.vertex_count; i++) flat[i] = s.positions[i] * 2e38f;
        expect_build(&m, &d, MLOD_ERROR_RANGE, MLOD_ERROR_RANGE, "coordinates near FLT_MAX");
        free(flat);
        m.positions = s.positions;
    }
    /* cancel */
    d2 = d;
    d2.sample_count = 100000;
    d2.progress = cancel_at_half;
    expect_build(&m, &d2, MLOD_ERROR_CANCELLED, MLOD_ERROR_CANCELLED, "progress callback cancels");
    /* and the mesh is still fine */
    t = NULL;
    CHECK(mlod_build_mesh(&m, &d, &t, NULL) == MLOD_OK && t, "the good mesh builds after all that");
    mlod_tree_destroy(t);
    CHECK(counter.live_blocks == 0 && counter.frees_of_unknown == 0, "build errors: %lu blocks leaked, %lu bad frees",
          counter.live_blocks, counter.frees_of_unknown);
    scene_free(&s);
}

static void test_points_errors(void)
{
    float pos[30], rad[10], nrm[30];
    mlod_points p;
    mlod_build_desc d = tu_desc(0, 1, MLOD_ATTR_CONE);
    uint32_t i;
    for (i = 0; i < 30; i++) {
        pos[i] = (float)(i * 7 % 11);
        nrm[i] = i % 3 == 2 ? 1.0f : 0.0f;
    }
    for (i = 0; i < 10; i++) rad[i] = 0.1f;
    d.allocator = &counting;
    memset(&p, 0, sizeof p);
    p.positions = pos;
    p.normals = nrm;
    p.radii = rad;
    p.count = 10;
    expect_points(NULL, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "points: NULL");
    expect_points(&p, NULL, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "points: NULL desc");
    p.count = 0;
    expect_points(&p, &d, MLOD_ERROR_EMPTY, MLOD_ERROR_EMPTY, "points: none");
    p.count = 10;
    p.positions = NULL;
    expect_points(&p, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "points: NULL positions");
    p.positions = pos;
    pos[13] = NAN;
    expect_points(&p, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "points: NaN position");
    pos[13] = -INFINITY;
    expect_points(&p, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "points: -inf position");
    pos[13] = 1;
    rad[4] = NAN;
    expect_points(&p, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "points: NaN radius");
    rad[4] = -0.5f;
    expect_points(&p, &d, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_RANGE, "points: negative radius");
    rad[4] = 0.1f;
    nrm[5] = NAN;
    expect_points(&p, &d, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "points: NaN normal (cones asked)");
    nrm[5] = 0;
    pos[0] = 2e38f;
    pos[3] = -2e38f;
    expect_points(&p, &d, MLOD_ERROR_RANGE, MLOD_ERROR_RANGE, "points: coordinates near FLT_MAX");
    pos[0] = pos[3] = 0;
    {
        mlod_tree *t = NULL;
        CHECK(mlod_build_points(&p, &d, &t, NULL) == MLOD_OK && t, "points: the good cloud builds after all that");
        mlod_tree_destroy(t);
        CHECK(counter.live_blocks == 0, "points: %lu blocks leaked", counter.live_blocks);
    }
}

/* ------------------------------------------------------------------ views */

static mlod_view valid_view(int kind)
{
    mlod_view v = tu_view((mlod_view_kind)kind);
    v.position[2] = 5;
    return v;
}

static void expect_view(const mlod_view *v, mlod_result a, mlod_result b, const char *what, const mlod_tree *t,
                        mlod_cut *cut)
{
    mlod_error e;
    mlod_view views[3];
    mlod_cut_params p;
    mlod_cut_view before = mlod_cut_get(cut, 1), after;
    uint32_t *nodes = (uint32_t *)malloc(sizeof(uint32_t) * (before.count + 1));
    uint8_t *status = (uint8_t *)malloc(before.count + 1);
    double c;
    memcpy(nodes, before.nodes, sizeof(uint32_t) * before.count);
    memcpy(status, before.status, before.count);
    memset(&e, 0, sizeof e);
    check_error(mlod_view_check(v, &e), &e, a, b, what);
    c = mlod_criterion(t, 0, v);
    CHECK(isnan(c), "%s: mlod_criterion %g, expected NaN", what, c);
    views[0] = valid_view(0);
    views[1] = *v;
    views[2] = valid_view(3);
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    p.mode = MLOD_CUT_INCREMENTAL;
    memset(&e, 0, sizeof e);
    check_error(mlod_cut_update(cut, t, views, &p, &e), &e, a, b, what);
    after = mlod_cut_get(cut, 1);
    CHECK(after.count == before.count && memcmp(after.nodes, nodes, sizeof(uint32_t) * before.count) == 0 &&
              memcmp(after.status, status, before.count) == 0,
          "%s: the failed update changed the previous cut", what);
    free(nodes);
    free(status);
}

static void expect_valid_view(const mlod_view *v, const char *what, const mlod_tree *t)
{
    mlod_error e;
    memset(&e, 0, sizeof e);
    CHECK(mlod_view_check(v, &e) == MLOD_OK, "%s: rejected (%s)", what, e.message);
    CHECK(!isnan(mlod_criterion(t, 0, v)), "%s: criterion NaN", what);
}

/* One rule for the fields a kind does not read (fov_y, near_plane,
   far_plane, half_width, half_height): any value, NaN and infinities
   included, is accepted and changes nothing; in a field it reads, NaN is
   MLOD_ERROR_NON_FINITE and so is an infinity where the value must be
   finite. */
static void test_view_unused_fields(const mlod_tree *t)
{
    static const float values[5] = {NAN, INFINITY, -INFINITY, -1e30f, 0.0f};
    /* which kinds read each field: perspective 1, paraboloids 2 and 4,
       orthographic 8, cube map 16 (near and far only) */
    static const unsigned readers[5] = {1u, 1u | 8u | 16u, 1u | 8u | 16u, 8u, 8u};
    static const char *names[5] = {"fov_y", "near_plane", "far_plane", "half_width", "half_height"};
    int kind, field, k;
    for (kind = 0; kind < 5; kind++)
        for (field = 0; field < 5; field++)
            for (k = 0; k < 5; k++) {
                mlod_view base = valid_view(kind), v = base;
                mlod_view_frame fa, fb;
                mlod_error e;
                float *f[5];
                char what[128];
                f[0] = &v.fov_y, f[1] = &v.near_plane, f[2] = &v.far_plane, f[3] = &v.half_width,
                f[4] = &v.half_height;
                *f[field] = values[k];
                snprintf(what, sizeof what, "view kind %d, %s = %g", kind, names[field], values[k]);
                memset(&e, 0, sizeof e);
                if (!(readers[field] & (1u << kind))) {
                    uint32_t node;
                    int same = 1;
                    memset(&fa, 0, sizeof fa);
                    memset(&fb, 0, sizeof fb);
                    CHECK(mlod_view_frame_of(&v, &fa, &e) == MLOD_OK && mlod_view_frame_of(&base, &fb, NULL) == MLOD_OK,
                          "%s (a field the kind does not read): refused (%s)", what, e.message);
                    for (node = 0; node < t->node_count; node += 97)
                        same = same && mlod_criterion(t, node, &v) == mlod_criterion(t, node, &base);
                    CHECK(same && memcmp(&fa, &fb, sizeof fa) == 0,
                          "%s (a field the kind does not read): the frame or criterion changed", what);
                } else if (isnan(values[k]) || (isinf(values[k]) && field != 2)) {
                    CHECK(mlod_view_check(&v, &e) == MLOD_ERROR_NON_FINITE && e.message[0],
                          "%s (a field the kind reads): %s, expected MLOD_ERROR_NON_FINITE", what,
                          mlod_result_name(e.code));
                }
            }
}

static void test_view_errors(void)
{
    scene_mesh s;
    mlod_tree *t;
    mlod_cut *cut = NULL;
    mlod_view v, views[3];
    mlod_cut_params p;
    int kind;
    char what[96];
    scene_uv_sphere(&s, 1.0f, 8, 16);
    t = tu_build(&s, 2000, 1, 0);
    mlod_cut_create(3, &counting, &cut, NULL);
    CHECK(t && cut, "views: setup");
    if (!t || !cut) return;
    views[0] = valid_view(0);
    views[1] = valid_view(1);
    views[2] = valid_view(3);
    memset(&p, 0, sizeof p);
    p.epsilon = 2.0f;
    CHECK(mlod_cut_update(cut, t, views, &p, NULL) == MLOD_OK && mlod_cut_get(cut, 1).count > 1, "views: a first cut");
    for (kind = 0; kind < 5; kind++) {
#define VIEW_CASE(change, a, b, name)                                                                                  \
    do {                                                                                                               \
        v = valid_view(kind);                                                                                          \
        change;                                                                                                        \
        snprintf(what, sizeof what, "view kind %d: %s", kind, name);                                                   \
        expect_view(&v, a, b, what, t, cut);                                                                           \
    } while (0)
        VIEW_CASE(v.forward[2] = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "zero forward");
        VIEW_CASE(v.up[1] = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "zero up");
        VIEW_CASE((v.up[1] = 0, v.up[2] = 3), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "up parallel to forward");
        VIEW_CASE((v.up[1] = 0, v.up[2] = 1), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "up opposite to forward");
        VIEW_CASE(v.width = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "width 0");
        VIEW_CASE(v.height = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "height 0");
        VIEW_CASE(v.position[0] = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN position");
        VIEW_CASE(v.position[1] = INFINITY, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "infinite position");
        VIEW_CASE(v.forward[1] = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN forward");
        VIEW_CASE(v.up[0] = -INFINITY, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "infinite up");
        VIEW_CASE(v.kind = (mlod_view_kind)7, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_INVALID_ARGUMENT, "kind 7");
        if (kind == MLOD_VIEW_PERSPECTIVE) {
            VIEW_CASE(v.fov_y = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "fov 0");
            VIEW_CASE(v.fov_y = -0.5f, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "fov -0.5");
            VIEW_CASE(v.fov_y = (float)TU_PI, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "fov pi");
            VIEW_CASE(v.fov_y = 4.0f, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "fov 4");
            VIEW_CASE(v.fov_y = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN fov");
            VIEW_CASE(v.near_plane = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "near 0");
            VIEW_CASE(v.near_plane = -1, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "near -1");
            VIEW_CASE(v.near_plane = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN near");
            VIEW_CASE(v.far_plane = v.near_plane, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far == near");
            VIEW_CASE(v.far_plane = v.near_plane / 2, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far < near");
            VIEW_CASE(v.far_plane = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN far");
        }
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            VIEW_CASE(v.half_width = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "half_width 0");
            VIEW_CASE(v.half_height = -1, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "half_height -1");
            VIEW_CASE(v.half_width = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN half_width");
            VIEW_CASE(v.far_plane = v.near_plane, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far == near");
            VIEW_CASE((v.near_plane = 3, v.far_plane = 1), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far < near");
            VIEW_CASE(v.near_plane = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN near");
        }
        if (kind == MLOD_VIEW_CUBE) {
            /* six s x s faces: the tile must be exactly 3s x 2s */
            VIEW_CASE(v.height = 63, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 96x63 (odd height)");
            VIEW_CASE(v.width = 95, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 95x64");
            VIEW_CASE(v.width = 97, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 97x64");
            VIEW_CASE(v.width = 64, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 64x64 (square)");
            VIEW_CASE((v.width = 64, v.height = 96), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 64x96 (2s x 3s)");
            VIEW_CASE(v.width = 192, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 192x64 (6s x s)");
            VIEW_CASE((v.width = 3, v.height = 1), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 3x1");
            VIEW_CASE((v.width = 1, v.height = 1), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 1x1");
            VIEW_CASE((v.width = 2, v.height = 2), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 2x2");
            VIEW_CASE((v.width = 4, v.height = 2), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "tile 4x2");
            VIEW_CASE((v.width = 2, v.height = 2863311532u), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW,
                      "tile 2x2863311532 (3s wraps past 2^32)");
            VIEW_CASE((v.width = 536870912u, v.height = 3221225472u), MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW,
                      "tile 536870912x3221225472 (3s wraps past 2^32)");
            VIEW_CASE(v.near_plane = 0, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "near 0");
            VIEW_CASE(v.near_plane = -0.0f, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "near -0");
            VIEW_CASE(v.near_plane = -1, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "near -1");
            VIEW_CASE(v.near_plane = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN near");
            VIEW_CASE(v.near_plane = INFINITY, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "near +inf");
            VIEW_CASE(v.far_plane = v.near_plane, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far == near");
            VIEW_CASE(v.far_plane = v.near_plane / 2, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far < near");
            VIEW_CASE(v.far_plane = -INFINITY, MLOD_ERROR_BAD_VIEW, MLOD_ERROR_BAD_VIEW, "far -inf");
            VIEW_CASE(v.far_plane = NAN, MLOD_ERROR_NON_FINITE, MLOD_ERROR_NON_FINITE, "NaN far");
        }
#undef VIEW_CASE
        /* valid: far = +inf, 1 x 1 tiles (a cube map's smallest, 3 x 2),
           unnormalised forward and up */
        v = valid_view(kind);
        v.far_plane = INFINITY;
        v.width = kind == MLOD_VIEW_CUBE ? 3 : 1;
        v.height = kind == MLOD_VIEW_CUBE ? 2 : 1;
        v.forward[2] = -1000;
        v.up[0] = 0.001f;
        v.up[1] = 0.002f;
        v.up[2] = 0.5f;
        snprintf(what, sizeof what, "view kind %d: far +inf, smallest tile, unnormalised frame", kind);
        expect_valid_view(&v, what, t);
        if (kind == MLOD_VIEW_PARABOLOID || kind == MLOD_VIEW_DUAL_PARABOLOID) {
            /* fields the kind does not use do not matter */
            v = valid_view(kind);
            v.fov_y = 0;
            v.near_plane = 0;
            v.far_plane = -1;
            v.half_width = 0;
            snprintf(what, sizeof what, "view kind %d: unused fov/near/far/half-extents zero", kind);
            expect_valid_view(&v, what, t);
        }
        if (kind == MLOD_VIEW_ORTHOGRAPHIC) {
            v = valid_view(kind);
            v.near_plane = -10;
            v.far_plane = -5;
            v.fov_y = 0;
            expect_valid_view(&v, "orthographic: near -10, far -5, fov 0", t);
        }
        if (kind == MLOD_VIEW_CUBE) {
            /* a cube map reads neither fov_y nor the half-extents, nor the
               tile's aspect beyond 3s x 2s */
            v = valid_view(kind);
            v.fov_y = NAN;
            v.half_width = INFINITY;
            v.half_height = -INFINITY;
            expect_valid_view(&v, "cube map: fov NaN, half-extents +-inf (unread)", t);
            v.width = 3 * 1000;
            v.height = 2 * 1000;
            v.near_plane = 1e-30f;
            v.far_plane = 1e30f;
            expect_valid_view(&v, "cube map: 3000x2000, near 1e-30, far 1e30", t);
            v.width = 0xFFFFFFFFu; /* s = (2^32 - 1) / 3: the largest 3s x 2s tile */
            v.height = 0xAAAAAAAAu;
            expect_valid_view(&v, "cube map: tile 4294967295x2863311530", t);
        }
    }
    test_view_unused_fields(t);
    CHECK(isnan(mlod_criterion(t, t->node_count, views)), "mlod_criterion of node == node_count is not NaN");
    CHECK(isnan(mlod_criterion(t, 0xFFFFFFFFu, views)), "mlod_criterion of node 2^32-1 is not NaN");
    mlod_cut_destroy(cut);
    mlod_tree_destroy(t);
    CHECK(counter.live_blocks == 0, "views: %lu blocks leaked", counter.live_blocks);
    scene_free(&s);
}

/* -------------------------------------------------------------------- cut */

typedef struct cut_copy {
    uint32_t count[4];
    uint32_t nodes[4][4096];
    uint8_t status[4][4096];
} cut_copy;

static void copy_cut(cut_copy *c, const mlod_cut *cut, uint32_t views)
{
    uint32_t v;
    memset(c, 0, sizeof *c);
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        c->count[v] = cv.count < 4096 ? cv.count : 4096;
        if (c->count[v]) {
            memcpy(c->nodes[v], cv.nodes, sizeof(uint32_t) * c->count[v]);
            memcpy(c->status[v], cv.status, c->count[v]);
        }
    }
}

static int same_as_copy(const cut_copy *c, const mlod_cut *cut, uint32_t views)
{
    uint32_t v;
    for (v = 0; v < views; v++) {
        mlod_cut_view cv = mlod_cut_get(cut, v);
        if (cv.count != c->count[v]) return 0;
        if (cv.count && (memcmp(cv.nodes, c->nodes[v], 4 * cv.count) || memcmp(cv.status, c->status[v], cv.count))) return 0;
    }
    return 1;
}

static void expect_update(mlod_cut *cut, const mlod_tree *t, const mlod_view *views, const mlod_cut_params *p,
                          mlod_result a, mlod_result b, const char *what)
{
    static cut_copy before;
    mlod_error e;
    uint32_t n = cut ? mlod_cut_view_count(cut) : 0;
    if (cut) copy_cut(&before, cut, n);
    memset(&e, 0, sizeof e);
    check_error(mlod_cut_update(cut, t, views, p, &e), &e, a, b, what);
    if (cut) CHECK(same_as_copy(&before, cut, n), "%s: the previous cut changed", what);
}

static void test_cut_errors(void)
{
    scene_mesh s;
    mlod_tree *t;
    mlod_cut *cut = NULL;
    mlod_view views[2];
    mlod_cut_params p;
    mlod_error e;
    static const float bad_eps[] = {0.0f, -0.0f, -1.0f, -INFINITY};
    size_t i;
    scene_uv_sphere(&s, 1.0f, 8, 16);
    t = tu_build(&s, 1000, 1, 0);
    views[0] = valid_view(0);
    views[1] = valid_view(2);
    memset(&e, 0, sizeof e);
    cut = (mlod_cut *)&counter;
    check_error(mlod_cut_create(0, &counting, &cut, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT,
                "cut_create with 0 views");
    CHECK(cut == NULL, "cut_create with 0 views: out not NULL");
    memset(&e, 0, sizeof e);
    check_error(mlod_cut_create(2, &counting, NULL, &e), &e, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT,
                "cut_create with NULL out");
    counter.max_bytes = (size_t)64 << 20;
    memset(&e, 0, sizeof e);
    cut = (mlod_cut *)&counter;
    check_error(mlod_cut_create(0xFFFFFFFFu, &counting, &cut, &e), &e, MLOD_ERROR_OUT_OF_MEMORY, MLOD_ERROR_OVERFLOW,
                "cut_create with 2^32-1 views, 64 MB blocks");
    CHECK(cut == NULL, "cut_create with 2^32-1 views: out not NULL");
    counter.max_bytes = 0;
    CHECK(counter.live_blocks == 0, "cut_create errors leaked %lu blocks", counter.live_blocks);
    CHECK(t && mlod_cut_create(2, &counting, &cut, NULL) == MLOD_OK && cut, "cut: create");
    if (!t || !cut) return;
    memset(&p, 0, sizeof p);
    p.epsilon = 1.5f;
    p.lazy_steps = 0;
    CHECK(mlod_cut_update(cut, t, views, &p, NULL) == MLOD_OK, "basic ignores lazy_steps 0");
    p.mode = MLOD_CUT_INCREMENTAL;
    p.epsilon = 3.0f;
    CHECK(mlod_cut_update(cut, t, views, &p, NULL) == MLOD_OK, "incremental ignores lazy_steps 0");
    for (i = 0; i < sizeof bad_eps / sizeof bad_eps[0]; i++) {
        char what[64];
        p.epsilon = bad_eps[i];
        snprintf(what, sizeof what, "epsilon %g", bad_eps[i]);
        expect_update(cut, t, views, &p, MLOD_ERROR_BAD_EPSILON, MLOD_ERROR_BAD_EPSILON, what);
    }
    p.epsilon = NAN;
    expect_update(cut, t, views, &p, MLOD_ERROR_BAD_EPSILON, MLOD_ERROR_BAD_EPSILON, "epsilon NaN");
    p.epsilon = 1.0f;
    p.mode = MLOD_CUT_LAZY;
    expect_update(cut, t, views, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "lazy_steps 0");
    p.lazy_steps = 1;
    p.mode = (mlod_cut_mode)3;
    expect_update(cut, t, views, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "mode 3");
    p.mode = (mlod_cut_mode)-1;
    expect_update(cut, t, views, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "mode -1");
    p.mode = MLOD_CUT_BASIC;
    expect_update(cut, NULL, views, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL tree");
    expect_update(cut, t, NULL, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL views");
    expect_update(cut, t, views, NULL, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL params");
    expect_update(NULL, t, views, &p, MLOD_ERROR_INVALID_ARGUMENT, MLOD_ERROR_INVALID_ARGUMENT, "NULL cut");
    CHECK(mlod_cut_update(cut, t, views, &p, NULL) == MLOD_OK, "a good update after the errors");
    mlod_cut_destroy(cut);
    mlod_cut_destroy(NULL);
    mlod_tree_destroy(NULL);
    mlod_tree_destroy(t);
    CHECK(counter.live_blocks == 0, "cut errors: %lu blocks leaked", counter.live_blocks);
    scene_free(&s);
}

/* ------------------------------------------------------------- allocators */

/* Bytes reported = bytes held from the allocator; everything comes back. */
static void test_counting(void)
{
    scene_mesh s;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(3000, 1, MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    tu_counter tc, cc;
    mlod_allocator ta, ca;
    mlod_tree *t = NULL;
    mlod_cut *cut = NULL;
    mlod_view views[6];
    mlod_cut_params p;
    uint64_t rng = 4;
    double c[3] = {0, 0, 0};
    unsigned long calls;
    int v, mode;
    memset(&tc, 0, sizeof tc);
    memset(&cc, 0, sizeof cc);
    ta = tu_allocator(&tc);
    ca = tu_allocator(&cc);
    scene_torus(&s, 1.0f, 0.3f, 24, 12);
    m = tu_mesh(&s);
    d.allocator = &ta;
    CHECK(mlod_build_mesh(&m, &d, &t, NULL) == MLOD_OK && t, "counting: build");
    if (!t) return;
    CHECK(tc.calls > 0, "counting: the build never called the allocator");
    CHECK(t->bytes == tc.live_bytes, "counting: tree reports %zu bytes, holds %zu from its allocator", t->bytes,
          tc.live_bytes);
    CHECK(t->allocator.alloc == ta.alloc && t->allocator.user == &tc, "counting: the tree does not keep its allocator");
    calls = tc.calls;
    CHECK(mlod_refit_mesh(t, &m, NULL, NULL) == MLOD_OK && tc.calls == calls, "counting: refit allocated (%lu calls)",
          tc.calls - calls);
    CHECK(mlod_cut_create(6, &ca, &cut, NULL) == MLOD_OK && cut, "counting: cut_create");
    if (cut) {
        CHECK(mlod_cut_bytes(cut) == cc.live_bytes, "counting: new cut reports %zu bytes, holds %zu", mlod_cut_bytes(cut),
              cc.live_bytes);
        for (v = 0; v < 6; v++) views[v] = tu_random_view(&rng, (mlod_view_kind)(v % 5), c, 1.3);
        memset(&p, 0, sizeof p);
        p.lazy_steps = 2;
        for (mode = 0; mode < 6; mode++) {
            p.mode = (mlod_cut_mode)(mode % 3);
            p.epsilon = mode < 3 ? 0.5f : 4.0f;
            CHECK(mlod_cut_update(cut, t, views, &p, NULL) == MLOD_OK, "counting: update %d", mode);
            CHECK(mlod_cut_bytes(cut) == cc.live_bytes, "counting: update %d: cut reports %zu bytes, holds %zu", mode,
                  mlod_cut_bytes(cut), cc.live_bytes);
        }
        CHECK(tc.calls == calls, "counting: cut updates used the tree's allocator");
        mlod_cut_destroy(cut);
    }
    mlod_tree_destroy(t);
    CHECK(tc.live_blocks == 0 && cc.live_blocks == 0, "counting: %lu + %lu blocks left after destroy", tc.live_blocks,
          cc.live_blocks);
    CHECK(tc.frees_of_unknown == 0 && cc.frees_of_unknown == 0, "counting: frees of pointers not from the allocator");
    scene_free(&s);
}

/* One build + cut scenario with an allocator that fails its k-th call
   (and, when fail_after, every later one).  Returns the number of
   allocations the scenario makes when nothing fails. */
static unsigned long failing_scenario(unsigned long k, int fail_after, uint32_t *bad)
{
    static scene_mesh s;
    static int ready;
    tu_counter fc;
    mlod_allocator fa;
    mlod_mesh m;
    mlod_build_desc d = tu_desc(700, 1, MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_COLOR | MLOD_ATTR_REFIT);
    mlod_tree *t = (mlod_tree *)&fc;
    mlod_cut *cut = (mlod_cut *)&fc;
    mlod_view views[4];
    mlod_cut_params p;
    mlod_error e;
    mlod_result r;
    uint64_t rng = 9;
    double c[3] = {0, 0, 0};
    int v, step;
    if (!ready) {
        scene_room(&s);
        ready = 1;
    }
    memset(&fc, 0, sizeof fc);
    fc.fail_at = k;
    fc.fail_after = fail_after;
    fa = tu_allocator(&fc);
    m = tu_mesh(&s);
    d.allocator = &fa;
    memset(&e, 0, sizeof e);
    r = mlod_build_mesh(&m, &d, &t, &e);
    if (r != MLOD_OK) {
        bad[0] += r != MLOD_ERROR_OUT_OF_MEMORY || e.code != r || !e.message[0] || t != NULL;
        bad[1] += fc.live_blocks != 0;
        return fc.calls;
    }
    r = mlod_cut_create(4, &fa, &cut, &e);
    if (r != MLOD_OK) {
        bad[0] += r != MLOD_ERROR_OUT_OF_MEMORY || e.code != r || !e.message[0] || cut != NULL;
        mlod_tree_destroy(t);
        bad[1] += fc.live_blocks != 0;
        return fc.calls;
    }
    for (v = 0; v < 4; v++) views[v] = tu_random_view(&rng, (mlod_view_kind)v, c, 2.0);
    memset(&p, 0, sizeof p);
    p.lazy_steps = 1;
    for (step = 0; step < 5; step++) {
        p.mode = (mlod_cut_mode)(step % 3);
        p.epsilon = step < 3 ? 1.0f : 0.3f;
        uint64_t version[4];
        for (v = 0; v < 4; v++) version[v] = mlod_cut_get(cut, v).version;
        memset(&e, 0, sizeof e);
        r = mlod_cut_update(cut, t, views, &p, &e);
        if (r != MLOD_OK) { /* the cut is reset: no entries, every version new */
            bad[0] += r != MLOD_ERROR_OUT_OF_MEMORY || e.code != r || !e.message[0];
            for (v = 0; v < 4; v++) bad[2] += mlod_cut_get(cut, v).count != 0 || mlod_cut_get(cut, v).version == version[v];
        }
    }
    mlod_cut_destroy(cut);
    mlod_tree_destroy(t);
    bad[1] += fc.live_blocks != 0;
    bad[3] += fc.frees_of_unknown != 0;
    return fc.calls;
}

static void test_failing_allocator(void)
{
    uint32_t bad[4] = {0, 0, 0, 0};
    unsigned long total = failing_scenario(0, 0, bad), k;
    int after;
    CHECK(bad[0] + bad[1] + bad[2] + bad[3] == 0, "failing allocator: the scenario fails without failures");
    for (after = 0; after < 2; after++) {
        memset(bad, 0, sizeof bad);
        for (k = 1; k <= total; k++) failing_scenario(k, after, bad);
        CHECK(bad[0] == 0, "failing allocator (%s): %u of %lu failures not reported as MLOD_ERROR_OUT_OF_MEMORY with a message",
              after ? "k-th and later" : "k-th only", bad[0], total);
        CHECK(bad[1] == 0, "failing allocator (%s): %u of %lu runs leaked", after ? "k-th and later" : "k-th only", bad[1],
              total);
        CHECK(bad[2] == 0, "failing allocator (%s): %u views of failed updates not reset",
              after ? "k-th and later" : "k-th only", bad[2]);
        CHECK(bad[3] == 0, "failing allocator (%s): %u runs freed pointers the allocator never gave",
              after ? "k-th and later" : "k-th only", bad[3]);
    }
    printf("  failing allocator: %lu allocations in the scenario, each failed in turn\n", total);
}

static void test_result_names(void)
{
    static const char *names[] = {"MLOD_OK",
                                  "MLOD_ERROR_INVALID_ARGUMENT",
                                  "MLOD_ERROR_NON_FINITE",
                                  "MLOD_ERROR_INDEX_OUT_OF_RANGE",
                                  "MLOD_ERROR_EMPTY",
                                  "MLOD_ERROR_BAD_EPSILON",
                                  "MLOD_ERROR_BAD_VIEW",
                                  "MLOD_ERROR_OVERFLOW",
                                  "MLOD_ERROR_OUT_OF_MEMORY",
                                  "MLOD_ERROR_MISMATCH",
                                  "MLOD_ERROR_RANGE",
                                  "MLOD_ERROR_CANCELLED",
                                  "MLOD_ERROR_DEVICE"};
    int i;
    const char *unknown = mlod_result_name((mlod_result)99);
    for (i = 0; i < 13; i++) {
        const char *n = mlod_result_name((mlod_result)i);
        CHECK(n && strcmp(n, names[i]) == 0, "mlod_result_name(%d) = \"%s\", expected %s", i, n ? n : "(null)", names[i]);
    }
    CHECK(unknown && unknown[0], "mlod_result_name(99) is NULL or empty");
}

/* The checks and tree helpers other backends share (manylods_vk.h). */
static void test_shared_checks(void)
{
    mlod_cut_params p;
    mlod_error e;
    uint32_t n, d, first, last;
    int bad = 0;
    memset(&p, 0, sizeof p);
    p.epsilon = 1.0f;
    CHECK(mlod_cut_params_check(NULL, &e) == MLOD_ERROR_INVALID_ARGUMENT, "params check: NULL");
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_OK, "params check: basic, epsilon 1");
    p.epsilon = 0.0f;
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_ERROR_BAD_EPSILON, "params check: epsilon 0");
    p.epsilon = NAN;
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_ERROR_BAD_EPSILON, "params check: epsilon NaN");
    p.epsilon = INFINITY;
    p.mode = MLOD_CUT_LAZY;
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_ERROR_INVALID_ARGUMENT, "params check: lazy with 0 steps");
    p.lazy_steps = 1;
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_OK, "params check: lazy, 1 step, epsilon +inf");
    p.mode = (mlod_cut_mode)7;
    CHECK(mlod_cut_params_check(&p, &e) == MLOD_ERROR_INVALID_ARGUMENT, "params check: mode 7");
    /* depth ranges against the depth of every internal node */
    for (n = 1; n <= 70 && !bad; n++)
        for (d = 0; d < 8 && !bad; d++) {
            uint32_t i, lo = UINT32_MAX, hi = 0;
            int any = 0;
            for (i = 0; i + 1 < n; i++)
                if (tu_depth(i) == d) {
                    any = 1;
                    if (i < lo) lo = i;
                    if (i > hi) hi = i;
                }
            if (mlod_tree_depth_nodes(n, d, &first, &last) != any || (any && (first != lo || last != hi))) bad = 1;
        }
    CHECK(!bad, "mlod_tree_depth_nodes differs from the depths of the internal nodes (N %u, depth %u)", n - 1, d - 1);
    /* any depth is fine: none from 32 on (a shift by 64 was undefined) */
    CHECK(mlod_tree_depth_nodes(UINT32_MAX, 31, &first, &last) == 1 && first == 0x7fffffffu && last == 0xfffffffdu,
          "depth 31 of 2^32 - 1 leaves: nodes 2^31 - 1 .. 2^32 - 3");
    CHECK(!mlod_tree_depth_nodes(UINT32_MAX, 32, &first, &last) && !mlod_tree_depth_nodes(UINT32_MAX, 63, &first, &last) &&
              !mlod_tree_depth_nodes(UINT32_MAX, 64, &first, &last) &&
              !mlod_tree_depth_nodes(UINT32_MAX, UINT32_MAX, &first, &last) && !mlod_tree_depth_nodes(5, 64, &first, &last),
          "depths 32, 63, 64 and 2^32 - 1 have no nodes");
    /* the growth limit: radii and summed areas within 1e37 */
    CHECK(mlod_refit_check_growth(1.0f, 1.0, 1000, 1e30, &e) == MLOD_OK, "growth 1e30 of 1000 leaves is fine");
    CHECK(mlod_refit_check_growth(1.0f, 1.0, 1000, 1e35, &e) == MLOD_ERROR_RANGE, "growth 1e35 of 1000 leaves: summed areas");
    CHECK(mlod_refit_check_growth(1.0f, 1e60, 1, 1e20, &e) == MLOD_ERROR_RANGE, "a radius sqrt(1e80): too large");
    CHECK(mlod_refit_check_growth(1.0f, 1.0, 1, NAN, &e) == MLOD_ERROR_RANGE, "growth NaN is refused");
}

/* Outputs the caller passes as NULL: the functions that write through
   pointers return 0 rather than crash; a NULL pool's hook has no run
   function (the library then runs on the calling thread). */
static void test_null_outputs(void)
{
    mlod_view v = tu_view(MLOD_VIEW_PERSPECTIVE);
    float o[3], d[3];
    uint32_t first = 0, last = 0;
    mlod_parallel serial = mlod_pool_parallel(NULL);
    CHECK(mlod_view_pixel_ray(&v, 32.5f, 32.5f, o, d) == 1 && mlod_view_pixel_ray(&v, 32.5f, 32.5f, NULL, d) == 0 &&
              mlod_view_pixel_ray(&v, 32.5f, 32.5f, o, NULL) == 0,
          "mlod_view_pixel_ray: 0 for NULL outputs");
    CHECK(mlod_tree_depth_nodes(100, 2, &first, &last) == 1 && mlod_tree_depth_nodes(100, 2, NULL, &last) == 0 &&
              mlod_tree_depth_nodes(100, 2, &first, NULL) == 0,
          "mlod_tree_depth_nodes: 0 for NULL outputs");
    CHECK(serial.run == NULL, "mlod_pool_parallel(NULL): a hook without run (the calling thread)");
}

int main(void)
{
    int rc;
    counting = tu_allocator(&counter);
    test_result_names();
    test_shared_checks();
    test_build_errors();
    test_points_errors();
    test_view_errors();
    test_cut_errors();
    test_counting();
    test_failing_allocator();
    test_null_outputs();
    rc = test_finish();
    fflush(stdout); /* keep the result line even if a sanitizer reports at exit */
    return rc;
}
