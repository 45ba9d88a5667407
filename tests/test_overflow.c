/* tests/test_overflow.c - sizes that do not fit: N, view counts and atlas
   sizes near the 32- and 64-bit limits, through the public API on a 64-bit
   machine.  Each must return MLOD_ERROR_OVERFLOW (a size that does not fit
   in its type, the header's promise for mlod_atlas_create) or
   MLOD_ERROR_OUT_OF_MEMORY (a size that fits but that the allocator
   refuses), with a message, a NULL output and no leak; never a wrapped,
   small allocation.  The allocator here refuses every block above 1 GiB and
   records the largest request, so no case costs memory: a request that
   wrapped around would show as a small largest request (and a success). */
#define MANYLODS_IMPLEMENTATION
#include "../manylods.h"
#include "harness.h"

#include <stdlib.h>
#include <string.h>

#define GIB ((size_t)1 << 30)

typedef struct ov_allocator {
    unsigned long calls, live, refused;
    size_t largest; /* largest request, granted or not */
} ov_allocator;

static void *ov_alloc(void *user, size_t bytes)
{
    ov_allocator *a = (ov_allocator *)user;
    void *p;
    a->calls++;
    if (bytes > a->largest) a->largest = bytes;
    if (bytes > GIB) {
        a->refused++;
        return NULL;
    }
    p = malloc(bytes);
    if (p) a->live++;
    return p;
}

static void ov_free(void *user, void *p)
{
    ov_allocator *a = (ov_allocator *)user;
    if (!p) return;
    a->live--;
    free(p);
}

static ov_allocator counter;
static mlod_allocator allocator = {ov_alloc, ov_free, &counter};

static void reset(void) { memset(&counter, 0, sizeof counter); }

/* The call returned `want` (or `also`), error.code agrees, the message is
   there, the output is NULL and nothing leaked. */
static void expect(mlod_result got, const mlod_error *e, const void *out, mlod_result want, mlod_result also,
                   const char *what)
{
    CHECK(got == want || got == also, "%s: returned %s, expected %s%s%s", what, mlod_result_name(got),
          mlod_result_name(want), want != also ? " or " : "", want != also ? mlod_result_name(also) : "");
    CHECK(e->code == got && e->message[0] != '\0', "%s: error.code %s, message \"%s\"", what, mlod_result_name(e->code),
          e->message);
    CHECK(out == NULL, "%s: the output pointer is not NULL", what);
    CHECK(counter.live == 0, "%s: %lu blocks not given back", what, counter.live);
}

/* OVERFLOW before the allocator is called at all. */
static void expect_overflow_early(mlod_result got, const mlod_error *e, const void *out, const char *what)
{
    expect(got, e, out, MLOD_ERROR_OVERFLOW, MLOD_ERROR_OVERFLOW, what);
    CHECK(counter.calls == 0, "%s: the allocator was called %lu times (largest request %zu bytes)", what,
          counter.calls, counter.largest);
}

/* OUT_OF_MEMORY (or OVERFLOW) after asking for at least `at_least` bytes:
   the size was computed in full, not wrapped around. */
static void expect_refused(mlod_result got, const mlod_error *e, const void *out, size_t at_least, const char *what)
{
    expect(got, e, out, MLOD_ERROR_OUT_OF_MEMORY, MLOD_ERROR_OVERFLOW, what);
    if (got == MLOD_ERROR_OUT_OF_MEMORY)
        CHECK(counter.largest >= at_least && counter.refused > 0,
              "%s: largest request %zu bytes, expected at least %zu (a size that wrapped around?)", what,
              counter.largest, at_least);
}

/* ------------------------------------------------------------ N */

static const float triangle_positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const uint32_t triangle_indices[3] = {0, 1, 2};

static void test_sample_count(void)
{
    static const struct {
        uint32_t n;
        const char *what;
    } overflowing[] = {{MANYLODS_MAX_LEAVES + 1u, "mesh, N = MANYLODS_MAX_LEAVES + 1"},
                       {0x80000000u, "mesh, N = 2^31 (2^32 - 1 nodes)"},
                       {0xffffffffu, "mesh, N = 2^32 - 1"}};
    mlod_mesh mesh;
    mlod_build_desc desc;
    mlod_tree *tree;
    mlod_error e;
    mlod_result res;
    size_t i;
    memset(&mesh, 0, sizeof mesh);
    mesh.positions = triangle_positions;
    mesh.vertex_count = 3;
    mesh.indices = triangle_indices;
    mesh.index_count = 3;
    memset(&desc, 0, sizeof desc);
    desc.allocator = &allocator;
    desc.attributes = MLOD_ATTR_CONE | MLOD_ATTR_AREA | MLOD_ATTR_REFIT;
    for (i = 0; i < sizeof overflowing / sizeof overflowing[0]; i++) {
        reset();
        desc.sample_count = overflowing[i].n;
        tree = (mlod_tree *)&counter;
        res = mlod_build_mesh(&mesh, &desc, &tree, &e);
        expect_overflow_early(res, &e, tree, overflowing[i].what);
    }
    /* N = MANYLODS_MAX_LEAVES fits (2^31 - 1 nodes) but needs gigabytes per
       array: refused, and the requests are the full sizes (4 bytes and
       more per sample) */
    reset();
    desc.sample_count = MANYLODS_MAX_LEAVES;
    tree = (mlod_tree *)&counter;
    res = mlod_build_mesh(&mesh, &desc, &tree, &e);
    expect_refused(res, &e, tree, (size_t)MANYLODS_MAX_LEAVES * 4, "mesh, N = MANYLODS_MAX_LEAVES");
    /* a small N still works with this allocator */
    reset();
    desc.sample_count = 1000;
    tree = NULL;
    CHECK(mlod_build_mesh(&mesh, &desc, &tree, &e) == MLOD_OK && tree && tree->node_count == 1999,
          "mesh, N = 1000: %s", e.message);
    CHECK(counter.largest < ((size_t)1 << 20), "mesh, N = 1000: largest request %zu bytes", counter.largest);
    mlod_tree_destroy(tree);
    CHECK(counter.live == 0, "mesh, N = 1000: %lu blocks not given back", counter.live);
}

static void test_point_count(void)
{
    static const struct {
        uint32_t n;
        const char *what;
    } overflowing[] = {{MANYLODS_MAX_LEAVES + 1u, "points, count = MANYLODS_MAX_LEAVES + 1"},
                       {0xffffffffu, "points, count = 2^32 - 1"}};
    mlod_points points;
    mlod_build_desc desc;
    mlod_tree *tree;
    mlod_error e;
    mlod_result res;
    size_t i;
    /* positions hold one point: the count must be refused before any read
       (AddressSanitizer would see one) */
    memset(&points, 0, sizeof points);
    points.positions = triangle_positions;
    memset(&desc, 0, sizeof desc);
    desc.allocator = &allocator;
    for (i = 0; i < sizeof overflowing / sizeof overflowing[0]; i++) {
        reset();
        points.count = overflowing[i].n;
        tree = (mlod_tree *)&counter;
        res = mlod_build_points(&points, &desc, &tree, &e);
        expect_overflow_early(res, &e, tree, overflowing[i].what);
    }
}

/* ----------------------------------------------------------- views */

static void test_view_count(void)
{
    mlod_cut *cut;
    mlod_error e;
    mlod_result res;
    reset();
    cut = (mlod_cut *)&counter;
    res = mlod_cut_create(0xffffffffu, &allocator, &cut, &e);
    expect_overflow_early(res, &e, cut, "mlod_cut_create(2^32 - 1 views)");
    /* 2^32 - 2 views: per-view arrays of 8 bytes a view, 32 GiB */
    reset();
    cut = (mlod_cut *)&counter;
    res = mlod_cut_create(0xfffffffeu, &allocator, &cut, &e);
    expect_refused(res, &e, cut, (size_t)0xfffffffeu * 8, "mlod_cut_create(2^32 - 2 views)");
    reset();
    cut = (mlod_cut *)&counter;
    res = mlod_cut_create(0x80000001u, &allocator, &cut, &e);
    expect_refused(res, &e, cut, (size_t)0x80000001u * 8, "mlod_cut_create(2^31 + 1 views)");
    reset();
    cut = (mlod_cut *)&counter;
    res = mlod_cut_create(1u << 28, &allocator, &cut, &e);
    expect_refused(res, &e, cut, (size_t)1 << 31, "mlod_cut_create(2^28 views)");
    reset();
    cut = NULL;
    CHECK(mlod_cut_create(1u << 16, &allocator, &cut, &e) == MLOD_OK && cut, "mlod_cut_create(2^16 views): %s",
          e.message);
    CHECK(mlod_cut_bytes(cut) >= ((size_t)1 << 16) * 8 && counter.largest >= ((size_t)1 << 16) * 8 &&
              counter.largest < ((size_t)1 << 24),
          "mlod_cut_create(2^16 views): %zu bytes, largest request %zu", mlod_cut_bytes(cut), counter.largest);
    mlod_cut_destroy(cut);
    CHECK(counter.live == 0, "mlod_cut_create(2^16 views): %lu blocks not given back", counter.live);
}

/* ----------------------------------------------------------- atlas */

static mlod_view tile_view(uint32_t width, uint32_t height)
{
    mlod_view v;
    memset(&v, 0, sizeof v);
    v.kind = MLOD_VIEW_PARABOLOID;
    v.forward[2] = -1.0f;
    v.up[1] = 1.0f;
    v.width = width;
    v.height = height;
    return v;
}

static void test_atlas(void)
{
    /* sizes whose pixel count or layout overflows 32 bits, or whose bytes
       overflow size_t */
    static const struct {
        uint32_t count, columns, width, height, channels;
        const char *what;
    } overflowing[] = {
        {1, 0, 0xffffffffu, 0xffffffffu, 0, "one tile of (2^32-1) x (2^32-1) pixels"},
        {1, 0, 0x80000000u, 0x80000000u, 0, "one tile of 2^31 x 2^31 pixels (2^64 bytes of depth)"},
        {3, 3, 0x80000000u, 1, 0, "a row of 3 tiles 2^31 wide"},
        {3, 1, 1, 0x80000000u, 0, "a column of 3 tiles 2^31 high"},
        {2, 0, 0xffffffffu, 1, 0, "2 tiles (2^32-1) wide side by side"},
        {5, 0, 0x60000000u, 1, 0, "5 tiles 3 * 2^29 wide, 3 to a row by default"},
        {40, 40, 1, 0xffffff00u, 0, "40 tiles of 2^32-256 rows (2^31 row bands of 64)"},
        {40, 40, 1, 0xffffffffu, 0, "40 tiles of 2^32-1 rows"},
        /* 2^61 pixels: depth (2^63 bytes) fits in size_t, normals or
           colours (3 floats a pixel, 1.5 * 2^64 bytes) do not */
        {1, 0, 0x80000000u, 0x40000000u, MLOD_ATLAS_NORMAL, "2^31 x 2^30 pixels with normals (12 * 2^61 bytes)"},
        {1, 0, 0x80000000u, 0x40000000u, MLOD_ATLAS_COLOR, "2^31 x 2^30 pixels with colours (12 * 2^61 bytes)"},
        {1, 0, 0xffffffffu, 0x20000000u, MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR,
         "(2^32-1) x 2^29 pixels with normals and colours"}};
    /* sizes that fit in size_t but not in memory: refused by the allocator,
       at their full size */
    static const struct {
        uint32_t count, columns, width, height, channels;
        size_t at_least;
        const char *what;
    } refused[] = {
        {1, 0, 0x10000u, 0x10000u, 0, (size_t)1 << 34, "one tile of 2^16 x 2^16 (2^32 pixels, 16 GiB of depth)"},
        {1, 0, 0x10001u, 0x10000u, 0, ((size_t)1 << 34) + ((size_t)1 << 18), "one tile of (2^16+1) x 2^16"},
        {4, 0, 0xffffffffu / 2, 0x10000u, MLOD_ATLAS_COLOR, (size_t)0xfffffffeu * 0x20000u * 4,
         "4 tiles of (2^31-1) x 2^16 with colours"},
        {1, 0, 0x80000000u, 0x40000000u, 0, (size_t)1 << 63, "one tile of 2^31 x 2^30, depth only (2^63 bytes)"},
        {1, 0, 0xffffffffu, 1, MLOD_ATLAS_NORMAL, (size_t)0xffffffffu * 4, "one tile of (2^32-1) x 1 with normals"}};
    mlod_view views[40];
    mlod_atlas_desc desc;
    mlod_atlas *atlas;
    mlod_error e;
    mlod_result res;
    size_t i;
    uint32_t v;
    char what[200];
    for (i = 0; i < sizeof overflowing / sizeof overflowing[0]; i++) {
        for (v = 0; v < overflowing[i].count; v++) views[v] = tile_view(overflowing[i].width, overflowing[i].height);
        memset(&desc, 0, sizeof desc);
        desc.columns = overflowing[i].columns;
        desc.channels = overflowing[i].channels;
        reset();
        atlas = (mlod_atlas *)&counter;
        snprintf(what, sizeof what, "mlod_atlas_create, %s", overflowing[i].what);
        res = mlod_atlas_create(views, overflowing[i].count, &desc, &allocator, &atlas, &e);
        expect_overflow_early(res, &e, atlas, what);
    }
    for (i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        for (v = 0; v < refused[i].count; v++) views[v] = tile_view(refused[i].width, refused[i].height);
        memset(&desc, 0, sizeof desc);
        desc.columns = refused[i].columns;
        desc.channels = refused[i].channels;
        reset();
        atlas = (mlod_atlas *)&counter;
        snprintf(what, sizeof what, "mlod_atlas_create, %s", refused[i].what);
        res = mlod_atlas_create(views, refused[i].count, &desc, &allocator, &atlas, &e);
        expect_refused(res, &e, atlas, refused[i].at_least, what);
    }
    /* a small atlas: requests of its own size */
    views[0] = tile_view(256, 128);
    views[1] = tile_view(64, 256);
    memset(&desc, 0, sizeof desc);
    desc.channels = MLOD_ATLAS_NORMAL | MLOD_ATLAS_COLOR;
    reset();
    atlas = NULL;
    CHECK(mlod_atlas_create(views, 2, &desc, &allocator, &atlas, &e) == MLOD_OK && atlas && atlas->width == 512 &&
              atlas->height == 256,
          "mlod_atlas_create, two small tiles: %s", e.message);
    CHECK(counter.largest == (size_t)512 * 256 * 12, "two small tiles: largest request %zu bytes, expected %zu",
          counter.largest, (size_t)512 * 256 * 12);
    mlod_atlas_destroy(atlas);
    CHECK(counter.live == 0, "two small tiles: %lu blocks not given back", counter.live);
}

int main(void)
{
    test_sample_count();
    test_point_count();
    test_view_count();
    test_atlas();
    return test_finish();
}
