/* tests/test_meshio.c - the OBJ and PLY loader of the examples and the
   benchmark (examples/meshio.h).

   - valid files: OBJ with comments, texture and normal lines, every face
     form (i, i/t, i//n, i/t/n), quads and larger polygons (fans), negative
     indices, CRLF and tabs; PLY in ASCII, binary little- and big-endian,
     with extra properties and elements, vertex_index, integer and double
     coordinates, negative values of every signed type and a signed list
     count in both byte orders; files on disk by extension in any case, and
     by content; the float of 1e30 written out and read back;
   - hostile files, each rejected with a message naming the file, leaving
     the output empty: empty, comments only, no faces, truncated (every
     prefix of a binary PLY, of an ASCII PLY up to its last number, a cut
     OBJ line), huge counts (elements and lists claiming billions, an element
     of 10^18 entries without properties, which must also be quick),
     counts that are not whole numbers, out-of-range, zero, fractional and
     negative indices, NaN, infinite and oversized coordinates (text and
     binary), binary garbage with and without a "ply" line, malformed
     headers, faces of two vertices, a missing file;
   - what the messages say (issue 14): a directory is reported as one, not
     as a size; OBJ indices as written (20 digits, relative ones with the
     vertex count so far); PLY versions other than 1.0 refused at their
     line; every ASCII PLY body error at the line of its value (checked
     against the line counted here), binary PLY body errors at the byte
     offset of the value; header errors at their line; tokens as written;
   - every allocation failing in turn (OBJ, ASCII and binary PLY, a file):
     an "out of memory" message naming the file, an empty mesh, no leak;
   - every single-byte change of three small valid files: no crash (the
     sanitizer build runs this too) and either a message placed as
     documented (a line of the input, a byte offset within it, or a
     message about the whole file), or a mesh whose indices are in range
     and coordinates finite. */
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

/* Allocations through a counter that can fail the k-th one (0: none). */
static unsigned long alloc_count, alloc_fail_at;
static void *test_malloc(size_t size)
{
    return ++alloc_count == alloc_fail_at ? NULL : malloc(size);
}
static void *test_realloc(void *p, size_t size)
{
    return ++alloc_count == alloc_fail_at ? NULL : realloc(p, size);
}
#define MESHIO_MALLOC(size) test_malloc(size)
#define MESHIO_REALLOC(p, size) test_realloc(p, size)
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

/* The 1-based line of data[offset]; the number of lines of data (a last
   line without a newline counts). */
static unsigned long line_of(const char *data, size_t offset)
{
    unsigned long line = 1;
    size_t i;
    for (i = 0; i < offset; i++) line += data[i] == '\n';
    return line;
}

static unsigned long line_count(const char *data, size_t size)
{
    return size == 0 ? 0 : line_of(data, size) - (data[size - 1] == '\n');
}

/* As expect_failure, and the message starts with "name:line: ". */
static void expect_failure_at(const char *what, const char *name, const void *data, size_t size, const char *expect,
                              unsigned long line)
{
    char prefix[128];
    expect_failure(what, name, data, size, expect);
    snprintf(prefix, sizeof prefix, "%s:%lu: ", name, line);
    CHECK(strncmp(message, prefix, strlen(prefix)) == 0, "%s: the message names line %lu: \"%s\"", what, line, message);
}

/* The line is the one holding the first occurrence of marker in text. */
static void expect_text_failure_at(const char *what, const char *name, const char *text, const char *expect,
                                   const char *marker)
{
    const char *at = strstr(text, marker);
    CHECK(at != NULL, "%s: the test's marker \"%s\" is in the text", what, marker);
    if (at) expect_failure_at(what, name, text, strlen(text), expect, line_of(text, (size_t)(at - text)));
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
    for (big = 0; big < 2; big++) { /* negative values of every signed type, in both byte orders */
        uint8_t data[512], *p = data;
        int16_t x = -2;
        int32_t y = -70000;
        int8_t z = -1;
        uint32_t v;
        double d = -0.375;
        p += sprintf((char *)data, "ply\nformat %s 1.0\nelement vertex 3\nproperty short x\nproperty int y\n"
                                   "property char z\nproperty double w\nelement face 1\n"
                                   "property list char int16 vertex_indices\nend_header\n",
                     big ? "binary_big_endian" : "binary_little_endian");
        for (v = 0; v < 3; v++) {
            int16_t xv = (int16_t)(x * (int16_t)v);
            int32_t yv = y + (int32_t)v;
            put(&p, &xv, 2, big);
            put(&p, &yv, 4, big);
            *p++ = (uint8_t)z;
            put(&p, &d, 8, big);
        }
        *p++ = 3;
        for (v = 0; v < 3; v++) {
            int16_t index = (int16_t)(2 - v);
            put(&p, &index, 2, big);
        }
        CHECK(parse(big ? "signed-big.ply" : "signed-little.ply", data, (size_t)(p - data), &m), "signed types: %s",
              message);
        if (m.vertex_count == 3 && m.index_count == 3)
            CHECK(m.positions[3] == -2.0f && m.positions[4] == -69999.0f && m.positions[5] == -1.0f &&
                      m.positions[6] == -4.0f && m.indices[0] == 2 && m.indices[2] == 0,
                  "signed types, %s-endian: (%g %g %g), index %u", big ? "big" : "little", m.positions[3], m.positions[4],
                  m.positions[5], m.indices[0]);
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
    /* a directory: the system's reason, not a size it made up */
    CHECK(!meshio_load(temp_dir, &m, message, sizeof message) && mesh_is_empty(&m), "a directory is rejected");
    CHECK(strncmp(message, temp_dir, strlen(temp_dir)) == 0 && strstr(message, "directory") &&
              !strstr(message, "memory") && !strstr(message, "bytes"),
          "a directory: the message names it and says it is a directory: \"%s\"", message);
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
    expect_failure_at("a NUL byte in an OBJ", "nul.obj", "v 0 0 0\nv 1 0\0 0\nv 0 1 0\nf 1 2 3\n", 34, "binary data", 2);
}

/* What OBJ messages say: the index as written, the vertex count so far,
   the line; tokens as written. */
static void test_obj_messages(void)
{
    const char *tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    char text[512];
    snprintf(text, sizeof text, "%sf 1 2 99999999999999999999\n", tri);
    expect_failure_at("an index of 20 digits", "digits.obj", text, strlen(text),
                      "face index 99999999999999999999 out of range (3 vertices so far)", 4);
    snprintf(text, sizeof text, "%sf 1 2 -99999999999999999999\n", tri);
    expect_failure_at("a relative index of 20 digits", "rdigits.obj", text, strlen(text),
                      "relative face index -99999999999999999999 out of range (3 vertices so far, so -1 .. -3)", 4);
    snprintf(text, sizeof text, "%sf -5 -6 -7\n", tri);
    expect_failure_at("f -5 -6 -7 with 3 vertices", "relative.obj", text, strlen(text),
                      "relative face index -5 out of range (3 vertices so far, so -1 .. -3)", 4);
    snprintf(text, sizeof text, "%sf -1 -2 -4\n", tri);
    expect_failure_at("f -1 -2 -4 with 3 vertices", "relative4.obj", text, strlen(text), "index -4 out of range", 4);
    snprintf(text, sizeof text, "v 0 0 0\nf -1 -2 -3\n%s", tri);
    expect_failure_at("a relative index with 1 vertex so far", "early.obj", text, strlen(text),
                      "index -2 out of range (1 vertices so far, so -1 .. -1)", 2);
    expect_text_failure_at("a relative index before any vertex", "none.obj", "f -1 -2 -3\nv 0 0 0\n",
                           "relative face index -1 out of range (no vertex so far)", "f");
    snprintf(text, sizeof text, "%sf 1 2 +4\n", tri);
    expect_failure_at("an index with a plus sign", "plus.obj", text, strlen(text), "face index +4 out of range", 4);
    snprintf(text, sizeof text, "%sf 1 2 3\nf 1 2 1234567890123456789012345678901234567890123456789\n", tri);
    expect_failure_at("an index of 49 digits", "long49.obj", text, strlen(text),
                      "face index 1234567890123456789012345678901234567890... out of range", 5);
    snprintf(text, sizeof text, "%sf 1 2 -0\n", tri);
    expect_failure_at("index -0", "minuszero.obj", text, strlen(text), "face index -0: expected a non-zero index", 4);
    snprintf(text, sizeof text, "%sf 1/x 2 3\n", tri);
    expect_failure_at("a texture index that is not a number", "tex.obj", text, strlen(text), "bad face vertex \"1/x\"", 4);
    snprintf(text, sizeof text, "%sf 1//x 2 3\n", tri);
    expect_failure_at("a normal index that is not a number", "nrm.obj", text, strlen(text), "\"1//x\"", 4);
    snprintf(text, sizeof text, "%sf 1/1/1/1 2 3\n", tri);
    expect_failure_at("four parts", "four.obj", text, strlen(text), "\"1/1/1/1\"", 4);
    snprintf(text, sizeof text, "%sf 1/ 2 3\n", tri);
    expect_failure_at("an empty texture index", "slash.obj", text, strlen(text), "\"1/\"", 4);
    snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv 0 1 0x\nf 1 2 3\n");
    expect_failure_at("junk after a coordinate", "vjunk.obj", text, strlen(text), "coordinate \"0x\" is not a number", 3);
    snprintf(text, sizeof text, "v 0 0 0\n\nv 1 0 0\nv 0 1 1e400\nf 1 2 3\n");
    expect_failure_at("1e400, as written", "e400.obj", text, strlen(text), "coordinate 1e400 is not finite", 4);
    snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv 0 1.25e31 0\nf 1 2 3\n");
    expect_failure_at("1.25e31, as written", "e31.obj", text, strlen(text), "coordinate 1.25e31 is not finite or beyond", 3);
    snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv 0 1 # z missing\nf 1 2 3\n");
    expect_failure_at("two numbers and a comment", "vcomment.obj", text, strlen(text), "this one has 2", 3);
    snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv\nf 1 2 3\n");
    expect_failure_at("v alone", "valone.obj", text, strlen(text), "this one has 0", 3);
    { /* a long token is cut, a byte that is not printable shown as '?' */
        char longtoken[200];
        snprintf(longtoken, sizeof longtoken, "%sf 1 2 3\nf 1 2 3\xff%s\n", tri,
                 "abcdefghijabcdefghijabcdefghijabcdefghijabcdefghij");
        expect_failure_at("a long bad token", "token.obj", longtoken, strlen(longtoken),
                          "bad face vertex \"3?abcdefghijabcdefghijabcdefghijabcdefgh...\"", 5);
    }
    /* the bound of 1e30 applies to the float stored: the float of 1e30
       (1.00000002e30 when printed with 9 digits) loads again, in OBJ and
       in ASCII PLY; the next float up does not */
    {
        scene_mesh m;
        float e30 = (float)1e30, above = nextafterf(e30, INFINITY);
        char printed[64];
        snprintf(printed, sizeof printed, "%.9g", e30);
        snprintf(text, sizeof text, "v %s -%s 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", printed, printed);
        CHECK(parse_text("e30.obj", text, &m), "the float of 1e30 written as %s loads: %s", printed, message);
        CHECK(m.vertex_count == 3 && m.positions[0] == e30 && m.positions[1] == -e30, "as the float of 1e30");
        scene_free(&m);
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                 "%s 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", printed);
        CHECK(parse_text("e30.ply", text, &m), "in ASCII PLY too: %s", message);
        scene_free(&m);
        snprintf(printed, sizeof printed, "%.9g", above);
        snprintf(text, sizeof text, "v 0 %s 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", printed);
        expect_failure_at("the float after that of 1e30", "above.obj", text, strlen(text), "beyond 1e30", 1);
    }
    /* still accepted: w after z, a comment after a face, tabs */
    {
        scene_mesh m;
        CHECK(parse_text("w.obj", "v 0 0 0 1\nv 1 0 0 1#w\nv 0 1 0\t0.5\nf 1/1/1\t2//2 -1/1 # c\n", &m),
              "w coordinates, comments, tabs: %s", message);
        CHECK(m.index_count == 3 && m.vertex_count == 3 && m.indices[2] == 2, "and the triangle is 0 1 2");
        scene_free(&m);
    }
}

/* PLY header messages: each names its line. */
static void test_ply_header_messages(void)
{
    static const char *xyz = "property float x\nproperty float y\nproperty float z\n";
    char text[1024];
    snprintf(text, sizeof text, "ply\nformat ascii 2.0\nelement vertex 3\n%send_header\n0 0 0\n", xyz);
    expect_failure_at("format ascii 2.0", "v2.ply", text, strlen(text), "unsupported PLY version \"2.0\"", 2);
    expect_text_failure_at("format binary_little_endian 1.1", "v11.ply",
                           "ply\ncomment hi\nformat binary_little_endian 1.1\nend_header\n", "version \"1.1\"",
                           "format");
    expect_text_failure_at("format without a version", "nov.ply", "ply\nformat ascii\nend_header\n",
                           "\"format TYPE VERSION\" expected", "format");
    expect_text_failure_at("two format lines", "twoformats.ply",
                           "ply\nformat ascii 1.0\nformat binary_big_endian 1.0\nend_header\n", "a second format line",
                           "format binary");
    expect_text_failure_at("no format line", "noformat.ply", "ply\nelement vertex 0\nend_header\n",
                           "no format line", "end_header");
    expect_text_failure_at("\"ply junk\" as the first line", "plyjunk.ply", "ply junk\nformat ascii 1.0\nend_header\n",
                           "not a PLY file", "ply");
    expect_text_failure_at("a second \"ply\" line", "plyply.ply", "ply\nformat ascii 1.0\nply\nend_header\n",
                           "unexpected header line \"ply\"", "ply\nend");
    expect_text_failure_at("no end_header (last line without a newline)", "noend.ply",
                           "ply\nformat ascii 1.0\nelement vertex 3", "end_header", "element");
    expect_text_failure_at("no end_header (last line with a newline)", "noend2.ply",
                           "ply\nformat ascii 1.0\nelement vertex 3\n", "end_header", "element");
    expect_failure("an empty PLY", "empty.ply", "", 0, "empty file");
    expect_failure_at("a NUL byte in the header", "nul.ply", "ply\nformat ascii 1.0\ncomment a\0b\nend_header\n", 36,
                      "NUL byte in the header", 3);
    expect_text_failure_at("a byte that is not ASCII in a name", "utf.ply",
                           "ply\nformat ascii 1.0\nelement v\xc3\xa9rtex 3\nend_header\n", "not printable ASCII (0xc3)",
                           "element");
    expect_text_failure_at("an element name of 40 characters", "longname.ply",
                           "ply\nformat ascii 1.0\nelement abcdefghijabcdefghijabcdefghijabcdefghij 3\nend_header\n",
                           "element name \"abcdefghijabcdefghijabcdefghijabcdefghij\" longer than 31", "element");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\n%sproperty float "
             "abcdefghijabcdefghijabcdefghijab\nend_header\n", xyz);
    expect_text_failure_at("a property name of 32 characters", "longprop.ply", text, "longer than 31", "property float a");
    expect_text_failure_at("an element count of -1", "minus.ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
                           "bad element count \"-1\"", "element");
    expect_text_failure_at("an element count of +3", "plus.ply", "ply\nformat ascii 1.0\nelement vertex +3\nend_header\n",
                           "bad element count \"+3\"", "element");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\n%selement vertex 3\n%send_header\n", xyz, xyz);
    expect_text_failure_at("two vertex elements", "twovertex.ply", text, "a second element vertex", "element vertex 3\np"
                           "roperty float x\nproperty float y\nproperty float z\nend");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\n%sproperty float x\nend_header\n", xyz);
    expect_text_failure_at("two properties x", "twox.ply", text, "a second property x in element vertex",
                           "property float x\nend");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int vertex_indices\n"
             "element vertex 3\n%send_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n", xyz);
    expect_text_failure_at("faces before vertices", "facefirst.ply", text, "element face before element vertex",
                           "element face");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\n%selement face 1\n"
             "property list uchar int vertex_indices\nproperty list uchar int vertex_index\nend_header\n", xyz);
    expect_text_failure_at("both index lists", "bothlists.ply", text, "both vertex_indices and vertex_index",
                           "element face");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\n%selement face 1\n"
             "property list uchar int vertex_indices extra\nend_header\n", xyz);
    expect_text_failure_at("a list property of 6 words", "sixwords.ply", text, "\"property list COUNT_TYPE TYPE NAME\"",
                           "property list");
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property list uchar float z\nend_header\n");
    expect_text_failure_at("a list z", "listz.ply", text, "lacks one of the scalar properties x, y, z", "element");
}

/* Binary PLY body messages name the byte offset of the value. */
static void test_binary_messages(void)
{
    uint8_t data[1024], copy[1024];
    size_t size = make_binary_ply(data, 0), body = size - (4 * 20 + 1 + 16);
    char expect[128];
    float nan_value;
    uint32_t nan_bits = 0x7fc00000u;
    uint8_t *p = copy + body + 20 + 8 + 4; /* vertex 1's y */
    memcpy(copy, data, size);
    memcpy(&nan_value, &nan_bits, 4);
    put(&p, &nan_value, 4, 0);
    snprintf(expect, sizeof expect, "bnan.ply: byte %lu: coordinate nan of vertex 1 is not finite",
             (unsigned long)(body + 20 + 8 + 4));
    expect_failure("binary NaN", "bnan.ply", copy, size, expect);
    memcpy(copy, data, size);
    copy[size - 4] = 7; /* the last index */
    snprintf(expect, sizeof expect, "brange.ply: byte %lu: vertex index 7 of face 0 out of range (4 vertices)",
             (unsigned long)(size - 4));
    expect_failure("a binary index past the end", "brange.ply", copy, size, expect);
    memcpy(copy, data, size);
    copy[size - 17] = 255;
    snprintf(expect, sizeof expect, "b255.ply: byte %lu: truncated: the file ends inside face 0 of 1", (unsigned long)size);
    expect_failure("a binary list of 255 in 16 bytes", "b255.ply", copy, size, expect);
    snprintf(expect, sizeof expect, "bcut.ply: byte %lu: truncated: the file ends inside vertex 2 of 4",
             (unsigned long)(body + 40));
    expect_failure("a binary body cut after 2 vertices", "bcut.ply", data, body + 40, expect);
}

/* Every allocation failing in turn: a message, an empty mesh, no leak
   (the sanitizer build checks the last). */
static void test_allocation_failures(void)
{
    char obj[16384], *p = obj;
    uint8_t binary[1024];
    size_t binary_size = make_binary_ply(binary, 1);
    const char *path;
    unsigned long k, needed = 0, failed_right = 0, total = 0;
    int input, i;
    for (i = 0; i < 300; i++) p += sprintf(p, "v %d 0 0\n", i);
    for (i = 0; i < 100; i++) p += sprintf(p, "f 1 %d %d 3 4\n", i + 1, i + 2);
    path = write_temp("alloc.obj", obj, strlen(obj));
    for (input = 0; input < 4; input++) {
        const char *name = input == 0 ? "alloc.obj" : input == 1 ? "alloc.ply" : input == 2 ? "alloc-binary.ply" : path;
        scene_mesh m;
        for (k = 0;; k++) {
            int ok;
            alloc_count = 0;
            alloc_fail_at = k;
            message[0] = '\0';
            if (input == 0) ok = parse_text(name, obj, &m);
            else if (input == 1) ok = parse_text(name, ply_ascii, &m);
            else if (input == 2) ok = parse(name, binary, binary_size, &m);
            else ok = meshio_load(path, &m, message, sizeof message);
            if (k == 0) {
                CHECK(ok, "%s without a failing allocation: %s", name, message);
                needed = alloc_count;
                if (ok) scene_free(&m);
                continue;
            }
            total++;
            if (ok) scene_free(&m);
            failed_right += !ok && strncmp(message, name, strlen(name)) == 0 && strstr(message, "out of memory") &&
                            mesh_is_empty(&m);
            if (k >= needed) break;
        }
        CHECK(needed >= (input == 0 ? 6u : 4u), "%s: %lu allocations (the test reaches the buffers' growth)", name,
              needed);
    }
    CHECK(failed_right == total, "every failing allocation gives an \"out of memory\" message naming the file and an "
          "empty mesh (%lu of %lu)", failed_right, total);
    alloc_fail_at = 0;
    remove(path);
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

    /* ASCII body errors: each names the line of the value (the header has 9
       lines, the vertices are lines 10-12, the face line 13), the end of
       the file being its last line */
    snprintf(text, sizeof text, "%s%s3 0 1 3\n", head3, verts);
    expect_failure_at("an index past the end", "range.ply", text, strlen(text),
                      "vertex index 3 of face 0 out of range (3 vertices)", line_of(text, strlen(head3) + strlen(verts)));
    CHECK(line_of(text, strlen(head3) + strlen(verts)) == 13, "the face line of the test is line 13");
    snprintf(text, sizeof text, "%s%s3 0 -1 2\n", head3, verts);
    expect_failure_at("a negative index", "negative.ply", text, strlen(text), "index -1 of face 0 out of range", 13);
    snprintf(text, sizeof text, "%s%s3 0 1.5 2\n", head3, verts);
    expect_failure_at("a fractional index", "fraction.ply", text, strlen(text), "index 1.5 of face 0 is not a whole", 13);
    snprintf(text, sizeof text, "%s%s2 0 1\n", head3, verts);
    expect_failure_at("a face of two vertices", "two.ply", text, strlen(text), "at least 3", 13);
    snprintf(text, sizeof text, "%s%s3.5 0 1 2\n", head3, verts);
    expect_failure_at("a fractional list count", "count.ply", text, strlen(text), "count 3.5 of face 0 is not a whole", 13);
    snprintf(text, sizeof text, "%s%s-3 0 1 2\n", head3, verts);
    expect_failure_at("a negative list count", "negcount.ply", text, strlen(text), "count -3 ", 13);
    snprintf(text, sizeof text, "%s%s1e300 0 1 2\n", head3, verts);
    expect_failure_at("a list count of 1e300", "hugecount.ply", text, strlen(text), "count 1e300 ", 13);
    snprintf(text, sizeof text, "%s%s300 0 1 2\n", head3, verts);
    expect_failure_at("a list count of 300 for a uchar", "uchar.ply", text, strlen(text), "fits its type uchar", 13);
    snprintf(text, sizeof text, "%s%s3\n0\n1\n\n2.25\n", head3, verts);
    expect_failure_at("a face spread over lines", "spread.ply", text, strlen(text), "index 2.25 ", 17);
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n%s"
             "4000000000 0 1 2\n", verts);
    expect_failure_at("a list count of 4 billion with three values", "longlist.ply", text, strlen(text), "truncated",
                      line_count(text, strlen(text)));
    snprintf(text, sizeof text, "%s0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", head3);
    expect_failure_at("NaN in ASCII", "nan.ply", text, strlen(text), "coordinate nan of vertex 1 is not finite", 11);
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1e400 0\n3 0 1 2\n", head3);
    expect_failure_at("1e400 in ASCII, as written", "e400.ply", text, strlen(text), "coordinate 1e400 of vertex 2", 12);
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1\n", head3);
    expect_failure_at("a cut ASCII body", "cut.ply", text, strlen(text), "truncated", 12);
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0\n0 1 0\n3 0 1", head3);
    expect_failure_at("a cut ASCII body without a last newline", "cutnl.ply", text, strlen(text), "truncated", 13);
    expect_failure_at("an empty body", "nobody.ply", head3, strlen(head3), "truncated: the file ends inside vertex 0 of 3",
                      9);
    snprintf(text, sizeof text, "%s\n  \n", head3);
    expect_failure_at("a body of blank lines", "blank.ply", text, strlen(text), "truncated", 11);
    snprintf(text, sizeof text, "%s0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n", head3);
    expect_failure_at("a word in an ASCII body", "word.ply", text, strlen(text), "malformed: \"zero\" is not a number", 11);
    snprintf(text, sizeof text, "%s0 0 0\n1 0 0x\n0 1 0\n3 0 1 2\n", head3);
    expect_failure_at("junk after a number", "junk.ply", text, strlen(text), "\"0x\" is not a number", 11);
    snprintf(text, sizeof text, "%s%s3 0 1 2\n\n4 0 1 2 3\n", head3, verts);
    expect_failure_at("text after the last element", "extra.ply", text, strlen(text), "after the last element", 15);
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 3\nproperty uchar x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0\n1 0 0\n0.5 1 0\n3 0 1 2\n");
    expect_failure_at("a uchar coordinate of 0.5", "ucharx.ply", text, strlen(text), "0.5 of vertex 2 does not fit", 12);
    { /* 4 billion vertices claimed, 3 given */
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n%s3 0 1 2\n", verts);
        expect_failure_at("4 billion vertices claimed", "claims.ply", text, strlen(text), "truncated", 13);
        snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999999\n"
                                    "property float x\nproperty float y\nproperty float z\nend_header\n%s", verts);
        expect_failure_at("a vertex count beyond long", "overflow.ply", text, strlen(text),
                          "count 99999999999999999999999999 is too large", 3);
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

/* Whether message is placed as meshio.h says: "name:LINE: " with LINE a
   line of the input, "name: byte N: " with N at most its size (binary
   PLY only), or one of the messages about the whole file. */
static int message_placed(const char *name, const uint8_t *data, size_t size, int binary)
{
    static const char *whole[] = {": no vertices", ": no faces with 3 or more vertices", ": out of memory",
                                  ": empty file", ": 2^32 or more"};
    size_t n = strlen(name), i;
    const char *rest = message + n;
    char *end;
    if (strncmp(message, name, n) != 0) return 0;
    if (rest[0] == ':' && rest[1] >= '1' && rest[1] <= '9') {
        unsigned long line = strtoul(rest + 1, &end, 10);
        return end[0] == ':' && end[1] == ' ' && line <= line_count((const char *)data, size);
    }
    if (binary && strncmp(rest, ": byte ", 7) == 0 && rest[7] >= '0' && rest[7] <= '9') {
        unsigned long offset = strtoul(rest + 7, &end, 10);
        return end[0] == ':' && offset <= size;
    }
    for (i = 0; i < sizeof whole / sizeof *whole; i++)
        if (strncmp(rest, whole[i], strlen(whole[i])) == 0) return 1;
    return 0;
}

/* Every single-byte change of a valid file: a message placed as
   documented, or a sound mesh. */
static void mutate_all(const char *name, const uint8_t *data, size_t size, int binary)
{
    static const int deltas[] = {1, 0x20, 0x80, 0xff};
    uint8_t *copy = (uint8_t *)malloc(size);
    unsigned long unsound = 0, silent = 0, tried = 0, misplaced = 0;
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
                if (!message_placed(name, copy, size, binary)) {
                    if (!misplaced) fprintf(stderr, "  a misplaced message: %s\n", message);
                    misplaced++;
                }
            }
        }
    CHECK(unsound == 0 && silent == 0 && misplaced == 0,
          "%s: %lu single-byte changes: %lu unsound meshes, %lu failures without a message, %lu messages without the "
          "documented place (line, byte or whole file)", name, tried, unsound, silent, misplaced);
    free(copy);
}

static void test_mutations(void)
{
    uint8_t binary[1024];
    size_t size = make_binary_ply(binary, 1);
    const char *obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2 3/3 4/4\nf -1 -2 -3\n";
    mutate_all("mutated.obj", (const uint8_t *)obj, strlen(obj), 0);
    mutate_all("mutated-ascii.ply", (const uint8_t *)ply_ascii, strlen(ply_ascii), 0);
    mutate_all("mutated-binary.ply", binary, size, 1);
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
    test_obj_messages();
    test_ply_header_messages();
    test_binary_messages();
    test_allocation_failures();
    test_hostile_binary();
    test_truncated_ascii();
    test_mutations();
    rmdir(temp_dir);
    return test_finish();
}
