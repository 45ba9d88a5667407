/* tests/test_meshio.c - the OBJ and PLY loader of the examples and the
   benchmark (examples/meshio.h).

   - valid files: OBJ with comments, texture and normal lines, every face
     form (i, i/t, i//n, i/t/n), quads and larger polygons (fans), negative
     indices, CRLF and tabs; PLY in ASCII, binary little- and big-endian,
     with extra properties and elements, vertex_index, integer and double
     coordinates; files on disk by extension in any case, and by content;
   - hostile files, each rejected with a message naming the file, leaving
     the output empty: empty, comments only, no faces, truncated (every
     prefix of a binary PLY, of an ASCII PLY up to its last number, a cut
     OBJ line), huge counts (elements and lists claiming billions, an element
     of 10^18 entries without properties, which must also be quick),
     counts that are not whole numbers, out-of-range, zero, fractional and
     negative indices, NaN, infinite and oversized coordinates (text and
     binary), binary garbage with and without a "ply" line, malformed
     headers, faces of two vertices, a missing file;
   - every single-byte change of three small valid files: no crash (the
     sanitizer build runs this too) and either a message, or a mesh whose
     indices are in range and coordinates finite. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "harness.h"
#include "tempdir.h"
#include "../examples/meshio.h"

static char message[512];

/* Parse bytes as `name`: 1 on success (mesh in *out), else 0 with the
   message in `message`. */
static int parse(const char *name, const void *data, size_t size, scene_mesh *out)
{
    message[0] = '\0';
    return meshio_parse(name, data, size, out, message, sizeof message);
}

static int parse_text(const char *name, const char *text, scene_mesh *out)
{
    return parse(name, text, strlen(text), out);
}

static int mesh_is_empty(const scene_mesh *m)
{
    return !m->positions && !m->indices && !m->normals && !m->colors && m->vertex_count == 0 && m->index_count == 0;
}

/* Check that parsing fails with a message naming the file (and containing
   `expect` when given), leaving the mesh empty. */
static void expect_failure(const char *what, const char *name, const void *data, size_t size, const char *expect)
{
    scene_mesh m;
    int ok = parse(name, data, size, &m);
    CHECK(!ok, "%s: rejected", what);
    CHECK(strstr(message, name) != NULL, "%s: the message names the file: \"%s\"", what, message);
    CHECK(!expect || strstr(message, expect) != NULL, "%s: the message says \"%s\": \"%s\"", what, expect ? expect : "",
          message);
    CHECK(mesh_is_empty(&m), "%s: the output is left empty", what);
    if (ok) scene_free(&m);
}

static void expect_text_failure(const char *what, const char *name, const char *text, const char *expect)
{
    expect_failure(what, name, text, strlen(text), expect);
}

/* Check a parsed mesh against expected counts, positions and indices. */
static void expect_mesh(const char *what, const scene_mesh *m, uint32_t vertices, const float *positions,
                        uint32_t indices, const uint32_t *index)
{
    CHECK(m->vertex_count == vertices && m->index_count == indices, "%s: %u vertices and %u indices (got %u, %u)", what,
          vertices, indices, m->vertex_count, m->index_count);
    CHECK(m->normals == NULL && m->colors == NULL, "%s: no normals or colours", what);
    if (m->vertex_count == vertices && positions)
        CHECK(memcmp(m->positions, positions, sizeof(float) * 3 * vertices) == 0, "%s: positions", what);
    if (m->index_count == indices && index)
        CHECK(memcmp(m->indices, index, sizeof(uint32_t) * indices) == 0, "%s: indices", what);
}

/* ------------------------------------------------------------ valid OBJ */

static const float square[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const uint32_t square_fan[6] = {0, 1, 2, 0, 2, 3};

static void test_obj_valid(void)
{
    scene_mesh m;
    static const char *triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t tri_index[3] = {0, 1, 2};
    static const char *forms =
        "# a square in every face form\r\n"
        "o square\r\ng group\r\nusemtl none\r\ns off\r\n"
        "v 0 0 0\r\nv\t1 0 0\r\nv 1 1 0 1.0\r\n  v 0 1 0\r\n"
        "vt 0 0\r\nvt 1 0\r\nvn 0 0 1\r\nvp 0.5\r\n"
        "f 1/1/1 2/2/1 3/2/1 4/1/1\r\n"
        "f 1//1 2//1 3//1   # a comment after the face\r\n"
        "f\t1/1 2/2 3/2\r\n"
        "l 1 2\r\np 1\r\n"
        "f -4 -3 -2 -1"; /* negative indices, no newline at the end */
    static const uint32_t forms_index[] = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 2, 3};
    static const char *hexagon = "v 1 0 0\nv 0.5 0.8 0\nv -0.5 0.8 0\nv -1 0 0\nv -0.5 -0.8 0\nv 0.5 -0.8 0\n"
                                 "f 1 2 3 4 5 6\n";
    static const uint32_t hexagon_index[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5};
    CHECK(parse_text("triangle.obj", triangle, &m), "a triangle: %s", message);
    expect_mesh("a triangle", &m, 3, tri, 3, tri_index);
    scene_free(&m);
    CHECK(parse_text("forms.obj", forms, &m), "every face form: %s", message);
    expect_mesh("every face form", &m, 4, square, 18, forms_index);
    scene_free(&m);
    CHECK(parse_text("hexagon.obj", hexagon, &m), "a hexagon: %s", message);
    expect_mesh("a hexagon", &m, 6, NULL, 12, hexagon_index);
    scene_free(&m);
    CHECK(parse_text("relative.obj", "v 9 9 9\nf 1 1 1\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", &m),
          "relative indices count from the last vertex so far: %s", message);
    if (m.index_count == 9) CHECK(m.indices[3] == 1 && m.indices[8] == 4, "relative indices resolve to 1..4");
    scene_free(&m);
}

/* ------------------------------------------------------------ valid PLY */

static const char *ply_ascii =
    "ply\n"
    "format ascii 1.0\n"
    "comment four corners with normals and colours, one quad, one edge\n"
    "obj_info made by hand\n"
    "element vertex 4\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "property float nx\n"
    "property float ny\n"
    "property float nz\n"
    "property uchar red\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "element edge 1\n"
    "property int vertex1\n"
    "property int vertex2\n"
    "end_header\n"
    "0 0 0 0 0 1 255\n"
    "1 0 0 0 0 1 0\n"
    "1 1 0 0 0 1 7\n"
    "0 1 0 0 0 1 9\n"
    "4 0 1 2 3\n"
    "0 2\n";

/* Append value (of `bytes` bytes, host order) in the given byte order. */
static void put(uint8_t **p, const void *value, size_t bytes, int big)
{
    const uint8_t *v = (const uint8_t *)value;
    uint16_t probe = 1;
    int host_little = *(const uint8_t *)&probe == 1;
    size_t i;
    for (i = 0; i < bytes; i++) (*p)[i] = v[(host_little != !big) ? bytes - 1 - i : i];
    *p += bytes;
}

/* A binary PLY of the square (a double "quality" property first, float
   coordinates, a uchar-counted uint list) in either byte order; returns its
   size. */
static size_t make_binary_ply(uint8_t *out, int big)
{
    uint8_t *p = out;
    uint32_t v, k;
    int n = sprintf((char *)out,
                    "ply\r\nformat %s 1.0\r\nelement vertex 4\r\nproperty double quality\r\n"
                    "property float x\r\nproperty float y\r\nproperty float z\r\n"
                    "element face 1\r\nproperty list uchar uint vertex_indices\r\nend_header\r\n",
                    big ? "binary_big_endian" : "binary_little_endian");
    p += n;
    for (v = 0; v < 4; v++) {
        double quality = 0.5 * v;
        put(&p, &quality, 8, big);
        for (k = 0; k < 3; k++) put(&p, &square[3 * v + k], 4, big);
    }
    *p++ = 4;
    for (v = 0; v < 4; v++) put(&p, &v, 4, big);
    return (size_t)(p - out);
}

static void test_ply_valid(void)
{
    scene_mesh m;
    uint8_t binary[1024];
    size_t size;
    int big;
    CHECK(parse_text("square.ply", ply_ascii, &m), "ASCII PLY: %s", message);
    expect_mesh("ASCII PLY", &m, 4, square, 6, square_fan);
    scene_free(&m);
    for (big = 0; big < 2; big++) {
        size = make_binary_ply(binary, big);
        CHECK(parse(big ? "big.ply" : "little.ply", binary, size, &m), "binary %s-endian PLY: %s", big ? "big" : "little",
              message);
        expect_mesh(big ? "binary big-endian PLY" : "binary little-endian PLY", &m, 4, square, 6, square_fan);
        scene_free(&m);
    }
    { /* vertex_index, short coordinates, a ushort list of int8 indices, no extension */
        uint8_t data[512], *p = data;
        int16_t xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        int k;
        p += sprintf((char *)data, "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty short x\n"
                                   "property short y\nproperty short z\nelement face 1\n"
                                   "property list ushort char vertex_index\nend_header\n");
        for (k = 0; k < 9; k++) put(&p, &xyz[k], 2, 0);
        *p++ = 3;
        *p++ = 0;
        *p++ = 0;
        *p++ = 1;
        *p++ = 2;
        CHECK(parse("noextension", data, (size_t)(p - data), &m), "PLY found by its first bytes: %s", message);
        if (m.vertex_count == 3) CHECK(m.positions[3] == 1.0f && m.positions[7] == 1.0f, "short coordinates");
        CHECK(m.index_count == 3 && m.indices[2] == 2, "vertex_index with a ushort count");
        scene_free(&m);
    }
}

/* ---------------------------------------------------------------- files */

static char temp_dir[256];

static const char *write_temp(const char *name, const void *data, size_t size)
{
    static char path[512];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", temp_dir, name);
    f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, size, f);
        fclose(f);
    }
    return path;
}

static void test_files(void)
{
    scene_mesh m;
    uint8_t binary[1024];
    size_t size = make_binary_ply(binary, 0);
    const char *path, *obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    char missing[512];
    path = write_temp("SQUARE.OBJ", obj, strlen(obj));
    CHECK(meshio_load(path, &m, message, sizeof message), "an .OBJ file: %s", message);
    expect_mesh("an .OBJ file", &m, 4, square, 6, square_fan);
    scene_free(&m);
    remove(path);
    path = write_temp("square.Ply", binary, size);
    CHECK(meshio_load(path, &m, message, sizeof message), "a binary .Ply file: %s", message);
    expect_mesh("a binary .Ply file", &m, 4, square, 6, square_fan);
    scene_free(&m);
    remove(path);
    path = write_temp("empty.ply", "", 0);
    CHECK(!meshio_load(path, &m, message, sizeof message) && strstr(message, path) && mesh_is_empty(&m),
          "an empty .ply file is rejected, naming it: %s", message);
    remove(path);
    snprintf(missing, sizeof missing, "%s/no-such-file.obj", temp_dir);
    CHECK(!meshio_load(missing, &m, message, sizeof message) && strstr(message, missing) &&
              strstr(message, "cannot open") && mesh_is_empty(&m),
          "a missing file is rejected, naming it: %s", message);
}

/* -------------------------------------------------------------- hostile */

static void test_hostile_obj(void)
{
    expect_failure("an empty file", "empty.obj", "", 0, "no vertices");
    expect_text_failure("comments only", "comments.obj", "# nothing\n# here\n\n", "no vertices");
    expect_text_failure("vertices, no faces", "nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces");
    expect_text_failure("a cut vertex line", "cut.obj", "v 0 0 0\nv 1 0 0\nv 0 1", "cut.obj:3:");
    expect_text_failure("index past the end", "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "range.obj:4:");
    expect_text_failure("index zero", "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "non-zero");
    expect_text_failure("a negative index before the first vertex", "negative.obj",
                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n", "out of range");
    expect_text_failure("an index beyond long", "long.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 99999999999999999999999 1 2\n",
                        "out of range");
    expect_text_failure("a forward reference", "forward.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n", "out of range");
    expect_text_failure("a fractional index", "fraction.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1.5 2 3\n", "bad face vertex");
    expect_text_failure("junk after an index", "junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1x 2 3\n", "bad face vertex");
    expect_text_failure("a face of two vertices", "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "at least 3");
    expect_text_failure("NaN", "nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not finite");
    expect_text_failure("infinity", "inf.obj", "v 0 -inf 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "not finite");
    expect_text_failure("1e31", "big.obj", "v 0 0 1e31\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "beyond 1e30");
    expect_text_failure("1e400 (overflows double)", "huge.obj", "v 1e400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                        "not finite");
    expect_failure("a NUL byte in an OBJ", "nul.obj", "v 0 0 0\nv 1 0\0 0\nv 0 1 0\nf 1 2 3\n", 34, "binary data");
}

static void test_hostile_ply(void)
{
    char text[2048];
    const char *head3 = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const char *verts = "0 0 0\n1 0 0\n0 1 0\n";
    expect_text_failure("only \"ply\"", "ply.ply", "ply\n", "end_header");
    expect_text_failure("not ply", "notply.ply", "hello\nend_header\n", "not a PLY");
    expect_text_failure("no format", "noformat.ply", "ply\nelement vertex 0\nend_header\n", "no format");
    expect_text_failure("an unknown format", "format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
                        "unknown format");
    expect_text_failure("a property before any element", "orphan.ply",
                        "ply\nformat ascii 1.0\nproperty float x\nend_header\n", "before any element");
    expect_text_failure("an unknown property type", "type.ply",
                        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "unknown property type");
    expect_text_failure("a list without a name", "listname.ply",
                        "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int\nend_header\n", "list");
    expect_text_failure("a float list count", "listcount.ply",
                        "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n",
                        "bad list types");
    expect_text_failure("an element without a count", "nocount.ply", "ply\nformat ascii 1.0\nelement vertex\nend_header\n",
                        "element NAME COUNT");
    expect_text_failure("a count that is not a number", "count.ply",
                        "ply\nformat ascii 1.0\nelement vertex 1e30\nend_header\n", "bad element count");
    expect_text_failure("an unexpected header line", "header.ply", "ply\nformat ascii 1.0\nbanana\nend_header\n",
                        "unexpected header line");
    { /* 17 elements, 17 properties */
        char *p = text;
        int i;
        p += sprintf(p, "ply\nformat ascii 1.0\n");
        for (i = 0; i < 17; i++) p += sprintf(p, "element e%d 0\n", i);
        sprintf(p, "end_header\n");
        expect_text_failure("17 elements", "elements.ply", text, "more than 16 elements");
        p = text + sprintf(text, "ply\nformat ascii 1.0\nelement vertex 1\n");
        for (i = 0; i < 17; i++) p += sprintf(p, "property float p%d\n", i);
        sprintf(p, "end_header\n");
        expect_text_failure("17 properties", "properties.ply", text, "more than 16 properties");
    }
    expect_text_failure("a vertex without z", "noz.ply",
                        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                        "lacks one of");
    expect_text_failure("a face without indices", "noindices.ply",
                        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                        "element face 1\nproperty int flags\nend_header\n0 0 0\n1\n",
                        "no list property");
    expect_text_failure("header only, no vertices", "novertices.ply",
                        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                        "end_header\n",
                        "no vertices");

    snprintf(text, sizeof text, "%s%s3 0 1 3\n", head3, verts);
    expect_text_failure("an index past the end", "range.ply", text, "out of range");
    snprintf(text, sizeof text, "%s%s3 0 -1 2\n", head3, verts);
    expect_text_failure("a negative index", "negative.ply", text, "out of range");
    snprintf(text, sizeof text, "%s%s3 0 1.5 2\n", head3, verts);
    expect_text_failure("a fractional index", "fraction.ply", text, "out of range");
    snprintf(text, sizeof text, "%s%s2 0 1\n", head3, verts);
    expect_text_failure("a face of two vertices", "two.ply", text, "at least 3");
    snprintf(text, sizeof text, "%s%s3.5 0 1 2\n", head3, verts);
    expect_text_failure("a fractional list count", "count.ply", text, "whole number");
    snprintf(text, sizeof text, "%s%s-3 0 1 2\n", head3, verts);
    expect_text_failure("a negative list count", "negcount.ply", text, "whole number");
    snprintf(text, sizeof text, "%s%s1e300 0 1 2\n", head3, verts);
    expect_text_failure("a list count of 1e300", "hugecount.ply", text, "whole number");
    snprintf(text, sizeof text, "%s%s4000000000 0 1 2\n", head3, verts);
    expect_text_failure("a list count of 4 billion with three values", "longlist.ply", text, "truncated");
    snprintf(text, sizeof text, "%snan 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", head3);
    expect_text_failure("NaN in ASCII", "nan.ply", text, "not finite");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1\n", head3);
    expect_text_failure("a cut ASCII body", "cut.ply", text, "truncated");
    snprintf(text, sizeof text, "%s0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n", head3);
    expect_text_failure("a word in an ASCII body", "word.ply", text, "malformed");
    { /* 4 billion vertices claimed, 3 given */
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n%s3 0 1 2\n", verts);
        expect_text_failure("4 billion vertices claimed", "claims.ply", text, "truncated");
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999999\n"
                                    "property float x\nproperty float y\nproperty float z\nend_header\n%s", verts);
        expect_text_failure("a vertex count beyond long", "overflow.ply", text, NULL);
    }
    { /* an element of 10^18 entries without properties, then a valid mesh: skipped at once */
        scene_mesh m;
        clock_t start = clock();
        int ok;
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement nothing 1000000000000000000\n%s%s3 0 1 2\n",
                 head3 + strlen("ply\nformat ascii 1.0\n"), verts);
        ok = parse_text("empty-element.ply", text, &m);
        CHECK(ok && m.index_count == 3, "an element of 10^18 entries without properties is skipped: %s", message);
        CHECK((double)(clock() - start) / CLOCKS_PER_SEC < 1.0, "and quickly");
        if (ok) scene_free(&m);
    }
}

/* Binary PLY hostile cases: every truncation, NaN and infinity bits, a list
   count of 255 with the file ending, garbage. */
static void test_hostile_binary(void)
{
    uint8_t data[1024], copy[1024];
    size_t size = make_binary_ply(data, 0), n, body;
    unsigned long accepted = 0;
    char name[64];
    for (n = 0; n < size; n++) {
        scene_mesh m;
        memcpy(copy, data, n);
        if (parse("prefix.ply", copy, n, &m)) {
            accepted++;
            scene_free(&m);
        } else {
            CHECK(message[0] && strstr(message, "prefix.ply") && mesh_is_empty(&m), "prefix of %lu bytes: a message",
                  (unsigned long)n);
        }
    }
    CHECK(accepted == 0, "every truncation of a binary PLY is rejected (%lu accepted)", accepted);
    body = size - (4 * 20 + 1 + 16);
    { /* NaN, then +infinity, as the first vertex's y; a double of 1e300 does not matter (not x, y, z) */
        uint32_t bits[2] = {0x7fc00000u, 0x7f800000u};
        int b;
        for (b = 0; b < 2; b++) {
            float value;
            uint8_t *p = copy + body + 8 + 4;
            memcpy(copy, data, size);
            memcpy(&value, &bits[b], 4);
            put(&p, &value, 4, 0);
            snprintf(name, sizeof name, "%s.ply", b ? "inf" : "nan");
            expect_failure(b ? "binary infinity" : "binary NaN", name, copy, size, "not finite");
        }
    }
    memcpy(copy, data, size);
    copy[size - 17] = 255; /* the face's count: 255 indices, 16 bytes left */
    expect_failure("a list of 255 in 16 bytes", "list255.ply", copy, size, "truncated");
    memcpy(copy, data, size);
    copy[size - 4] = 4; /* the last index (3 -> 4 bytes, little-endian: low byte first at size - 4) */
    expect_failure("a binary index past the end", "range4.ply", copy, size, "out of range");
    { /* garbage, with and without a "ply" line */
        uint64_t seed = 12345;
        uint8_t garbage[4096];
        size_t i;
        for (i = 0; i < sizeof garbage; i++) garbage[i] = (uint8_t)scene_rng_next(&seed);
        garbage[100] = 0; /* surely binary */
        expect_failure("binary garbage", "garbage.obj", garbage, sizeof garbage, "binary data");
        expect_failure("binary garbage named .ply", "garbage.ply", garbage, sizeof garbage, NULL);
        memcpy(garbage, "ply\n", 4);
        expect_failure("garbage after \"ply\"", "plygarbage.ply", garbage, sizeof garbage, NULL);
        for (i = 0; i < sizeof garbage; i++) garbage[i] = (uint8_t)(' ' + scene_rng_next(&seed) % 95);
        expect_failure("printable garbage", "text.obj", garbage, sizeof garbage, NULL);
    }
}

/* ASCII PLY: every prefix that ends before the last number is rejected. */
static void test_truncated_ascii(void)
{
    size_t size = strlen(ply_ascii), last = size - 2, n; /* "... 0 2\n": the last digit at size - 2 */
    unsigned long accepted = 0;
    for (n = 0; n < last; n++) {
        scene_mesh m;
        if (parse("prefix.ply", ply_ascii, n, &m)) {
            accepted++;
            scene_free(&m);
        }
    }
    CHECK(accepted == 0, "every ASCII PLY prefix before its last number is rejected (%lu accepted)", accepted);
}

/* Every single-byte change of a valid file: a message, or a sound mesh. */
static void mutate_all(const char *name, const uint8_t *data, size_t size)
{
    static const int deltas[] = {1, 0x20, 0x80, 0xff};
    uint8_t *copy = (uint8_t *)malloc(size);
    unsigned long unsound = 0, silent = 0, tried = 0;
    size_t i, d;
    if (!copy) return;
    for (i = 0; i < size; i++)
        for (d = 0; d < 4; d++) {
            scene_mesh m;
            memcpy(copy, data, size);
            copy[i] = (uint8_t)(copy[i] + deltas[d]);
            tried++;
            if (parse(name, copy, size, &m)) {
                uint32_t k;
                int sound = m.vertex_count > 0 && m.index_count > 0 && m.index_count % 3 == 0;
                for (k = 0; k < m.index_count && sound; k++) sound = m.indices[k] < m.vertex_count;
                for (k = 0; k < 3 * m.vertex_count && sound; k++) sound = isfinite(m.positions[k]);
                unsound += !sound;
                scene_free(&m);
            } else {
                silent += !message[0] || !mesh_is_empty(&m);
            }
        }
    CHECK(unsound == 0 && silent == 0, "%s: %lu single-byte changes: %lu unsound meshes, %lu failures without a message",
          name, tried, unsound, silent);
    free(copy);
}

static void test_mutations(void)
{
    uint8_t binary[1024];
    size_t size = make_binary_ply(binary, 1);
    const char *obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2 3/3 4/4\nf -1 -2 -3\n";
    mutate_all("mutated.obj", (const uint8_t *)obj, strlen(obj));
    mutate_all("mutated-ascii.ply", (const uint8_t *)ply_ascii, strlen(ply_ascii));
    mutate_all("mutated-binary.ply", binary, size);
}

int main(void)
{
    if (!test_temp_dir(temp_dir, sizeof temp_dir, "meshio")) {
        perror("test_temp_dir");
        return 1;
    }
    test_obj_valid();
    test_ply_valid();
    test_files();
    test_hostile_obj();
    test_hostile_ply();
    test_hostile_binary();
    test_truncated_ascii();
    test_mutations();
    rmdir(temp_dir);
    return test_finish();
}
