/* fuzz/fuzz_loader.c - libFuzzer harness for the examples' OBJ and PLY
   loader (examples/meshio.h): arbitrary bytes are parsed as an OBJ or PLY
   file (ASCII or binary PLY, whatever the bytes say) from memory, and now
   and then from a file on disk, and every outcome is checked against what
   meshio.h promises.  A violation prints "manylods fuzz: ..." and aborts,
   so libFuzzer keeps the input as a crash.

     clang -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined \
           -fno-sanitize-recover=all -I. fuzz/fuzz_loader.c -o fuzz_loader -lm
     ./fuzz_loader -max_len=4096 CORPUS_DIR      (seeds: fuzz/corpus/loader/)
     MANYLODS_FUZZ_VERBOSE=1 ./fuzz_loader FILE...   what each input gave

   Input: a flags byte, then the file's bytes.
     bits 0-1  the name: "in.obj", "in.ply", "in" (no extension), "IN.PLY"
     bit 2     a small error buffer: the next byte gives its size (0 .. 63)
     bit 3     fail one allocation: the next byte says which (1 .. 256)
     bit 4     also read the bytes from a file (meshio_load) and compare
   (the optional bytes come in that order, before the file's bytes).

   Checked:
   - success: at least one vertex and one triangle, index_count a multiple
     of 3, every index below vertex_count, every coordinate finite and
     within +-1e30, no normals or colours; and the mesh equals the one an
     independent, naive reader of the same bytes finds (it trusts the
     input, since the loader accepted it): each coordinate is the float of
     the number written, each face its fan, for OBJ, ASCII and binary PLY;
     the mesh written back as OBJ (%.9g) loads as the same mesh;
   - failure: the mesh left empty; a message that starts with the name and
     says where: "name:LINE: " with LINE from 1 to the input's number of
     lines, "name: byte N: " with N at most the input's size (PLY only), or
     one of the messages about the whole file (no vertices, no faces, out
     of memory, empty file, 2^32 or more); a small buffer holds the same
     message cut to fit, NUL-terminated, and nothing is written past it;
   - a failing allocation gives the same result as none, or a failure
     saying "out of memory"; meshio_load of the bytes in a file gives the
     same result and message as meshio_parse;
   - no leak (LeakSanitizer), no undefined behaviour, no crash. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static unsigned long fuzz_allocations, fuzz_fail_at; /* fail the fuzz_fail_at-th allocation; 0: none */

static void *fuzz_malloc(size_t size)
{
    return ++fuzz_allocations == fuzz_fail_at ? NULL : malloc(size);
}

static void *fuzz_realloc(void *p, size_t size)
{
    return ++fuzz_allocations == fuzz_fail_at ? NULL : realloc(p, size);
}

#define MESHIO_MALLOC(size) fuzz_malloc(size)
#define MESHIO_REALLOC(p, size) fuzz_realloc(p, size)
#include "../examples/meshio.h"
#include "fuzz.h"

/* ------------------------------------------------------- naive readers */

/* A mesh the naive readers build: growable arrays. */
typedef struct ref_mesh {
    float *positions;
    uint32_t *indices;
    size_t vertex_count, index_count, vertex_capacity, index_capacity;
} ref_mesh;

static void ref_vertex(ref_mesh *m, const double xyz[3])
{
    int k;
    if (m->vertex_count == m->vertex_capacity) {
        m->vertex_capacity = m->vertex_capacity ? 2 * m->vertex_capacity : 64;
        m->positions = (float *)realloc(m->positions, sizeof(float) * 3 * m->vertex_capacity);
        FZ_REQUIRE(m->positions != NULL, "the harness ran out of memory");
    }
    for (k = 0; k < 3; k++) m->positions[3 * m->vertex_count + (size_t)k] = (float)xyz[k];
    m->vertex_count++;
}

static void ref_index(ref_mesh *m, uint32_t index)
{
    if (m->index_count == m->index_capacity) {
        m->index_capacity = m->index_capacity ? 2 * m->index_capacity : 64;
        m->indices = (uint32_t *)realloc(m->indices, sizeof(uint32_t) * m->index_capacity);
        FZ_REQUIRE(m->indices != NULL, "the harness ran out of memory");
    }
    m->indices[m->index_count++] = index;
}

/* A polygon's fan: (first, i, i + 1). */
static void ref_fan(ref_mesh *m, const uint32_t *poly, size_t n)
{
    size_t i;
    for (i = 1; i + 1 < n; i++) {
        ref_index(m, poly[0]);
        ref_index(m, poly[i]);
        ref_index(m, poly[i + 1]);
    }
}

/* OBJ as its definition reads: "v" lines give 3 numbers, "f" lines
   whitespace-separated vertices whose first integer is the index. */
static void ref_obj(const char *text, ref_mesh *m)
{
    const char *line = text;
    uint32_t *poly = NULL;
    size_t poly_capacity = 0;
    while (*line) {
        const char *end = strchr(line, '\n'), *p = line;
        size_t length = end ? (size_t)(end - line) : strlen(line);
        char *copy = (char *)malloc(length + 1);
        FZ_REQUIRE(copy != NULL, "the harness ran out of memory");
        memcpy(copy, line, length);
        copy[length] = '\0';
        p = copy;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t' || p[1] == '\r')) {
            double xyz[3];
            char *next;
            int k;
            p++;
            for (k = 0; k < 3; k++) {
                xyz[k] = strtod(p, &next);
                p = next;
            }
            ref_vertex(m, xyz);
        } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t' || p[1] == '\r')) {
            size_t n = 0;
            p++;
            for (;;) {
                long long i;
                while (*p == ' ' || *p == '\t' || *p == '\r') p++;
                if (!*p || *p == '#') break;
                i = strtoll(p, NULL, 10);
                if (n == poly_capacity) {
                    poly_capacity = poly_capacity ? 2 * poly_capacity : 16;
                    poly = (uint32_t *)realloc(poly, sizeof *poly * poly_capacity);
                    FZ_REQUIRE(poly != NULL, "the harness ran out of memory");
                }
                poly[n++] = (uint32_t)(i < 0 ? (long long)m->vertex_count + i : i - 1);
                while (*p && *p != ' ' && *p != '\t' && *p != '\r' && *p != '#') p++;
            }
            ref_fan(m, poly, n);
        }
        free(copy);
        if (!end) break;
        line = end + 1;
    }
    free(poly);
}

/* PLY: the header's elements and properties in order, then each value
   of each entry read as text (strtod) or as bytes of its type. */
typedef struct ref_property {
    char name[64];
    int list, count_bytes, count_kind, bytes, kind; /* kind: 'i' signed, 'u' unsigned, 'f' float */
} ref_property;

static int ref_type(const char *name, int *bytes, int *kind)
{
    static const char *names[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double",
                                  "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
    static const int size[] = {1, 1, 2, 2, 4, 4, 4, 8};
    static const char kinds[] = "iuiuiuff";
    int i;
    for (i = 0; i < 16; i++)
        if (strcmp(name, names[i]) == 0) {
            *bytes = size[i % 8];
            *kind = kinds[i % 8];
            return 1;
        }
    return 0;
}

typedef struct ref_reader {
    const uint8_t *p, *end;
    int binary, big;
} ref_reader;

static double ref_value(ref_reader *r, int bytes, int kind)
{
    uint8_t b[8];
    int i;
    if (!r->binary) {
        char *next;
        double v = strtod((const char *)r->p, &next);
        r->p = (const uint8_t *)next;
        return v;
    }
    FZ_REQUIRE((size_t)(r->end - r->p) >= (size_t)bytes, "the loader accepted a binary PLY that ends early");
    for (i = 0; i < bytes; i++) b[i] = r->p[r->big ? bytes - 1 - i : i];
    r->p += bytes;
    {
        uint64_t u = 0;
        for (i = bytes - 1; i >= 0; i--) u = u << 8 | b[i]; /* b holds the value least significant byte first */
        if (kind == 'u') return (double)u;
        if (kind == 'i') return (double)(int64_t)(u << (64 - 8 * bytes)) / ldexp(1.0, 64 - 8 * bytes);
        if (bytes == 4) {
            uint32_t u32 = (uint32_t)u;
            float f;
            memcpy(&f, &u32, 4);
            return f;
        } else {
            double d;
            memcpy(&d, &u, 8);
            return d;
        }
    }
}

static void ref_ply(const uint8_t *data, size_t size, ref_mesh *m)
{
    char names[16][64];
    unsigned long counts[16];
    ref_property props[16][16];
    int nprops[16] = {0}, nelements = 0, e, k;
    const uint8_t *p = data, *end = data + size;
    ref_reader r;
    uint32_t *poly = NULL;
    size_t poly_capacity = 0;
    r.binary = r.big = 0;
    for (;;) { /* the header */
        const uint8_t *nl = (const uint8_t *)memchr(p, '\n', (size_t)(end - p));
        char line[512], w[5][64];
        size_t length;
        int words;
        FZ_REQUIRE(nl != NULL, "the loader accepted a PLY without an end_header line");
        length = (size_t)(nl - p) < sizeof line - 1 ? (size_t)(nl - p) : sizeof line - 1;
        memcpy(line, p, length);
        line[length] = '\0';
        p = nl + 1;
        words = sscanf(line, "%63s %63s %63s %63s %63s", w[0], w[1], w[2], w[3], w[4]);
        if (words <= 0) continue;
        if (strcmp(w[0], "end_header") == 0) break;
        if (strcmp(w[0], "format") == 0) {
            r.binary = strcmp(w[1], "ascii") != 0;
            r.big = strcmp(w[1], "binary_big_endian") == 0;
        } else if (strcmp(w[0], "element") == 0) {
            FZ_REQUIRE(nelements < 16, "the loader accepted more than 16 elements");
            strcpy(names[nelements], w[1]);
            counts[nelements] = strtoul(w[2], NULL, 10);
            nelements++;
        } else if (strcmp(w[0], "property") == 0) {
            ref_property *q = &props[nelements - 1][nprops[nelements - 1]++];
            memset(q, 0, sizeof *q);
            q->list = strcmp(w[1], "list") == 0;
            if (q->list) {
                ref_type(w[2], &q->count_bytes, &q->count_kind);
                ref_type(w[3], &q->bytes, &q->kind);
                strcpy(q->name, w[4]);
            } else {
                ref_type(w[1], &q->bytes, &q->kind);
                strcpy(q->name, w[2]);
            }
        }
    }
    r.p = p;
    r.end = end;
    for (e = 0; e < nelements; e++) {
        unsigned long i;
        int is_vertex = strcmp(names[e], "vertex") == 0, is_face = strcmp(names[e], "face") == 0;
        if (nprops[e] == 0) continue;
        for (i = 0; i < counts[e]; i++) {
            double xyz[3] = {0, 0, 0};
            for (k = 0; k < nprops[e]; k++) {
                const ref_property *q = &props[e][k];
                if (q->list) {
                    unsigned long n = (unsigned long)ref_value(&r, q->count_bytes, q->count_kind), j;
                    int used = is_face && (strcmp(q->name, "vertex_indices") == 0 || strcmp(q->name, "vertex_index") == 0);
                    if (used && n > poly_capacity) {
                        poly_capacity = n;
                        poly = (uint32_t *)realloc(poly, sizeof *poly * n);
                        FZ_REQUIRE(poly != NULL, "the harness ran out of memory");
                    }
                    for (j = 0; j < n; j++) {
                        double v = ref_value(&r, q->bytes, q->kind);
                        if (used) poly[j] = (uint32_t)v;
                    }
                    if (used) ref_fan(m, poly, n);
                } else {
                    double v = ref_value(&r, q->bytes, q->kind);
                    if (is_vertex && q->name[0] >= 'x' && q->name[0] <= 'z' && q->name[1] == '\0') xyz[q->name[0] - 'x'] = v;
                }
            }
            if (is_vertex) ref_vertex(m, xyz);
        }
    }
    free(poly);
}

/* -------------------------------------------------------------- checks */

static size_t line_count(const uint8_t *data, size_t size)
{
    size_t lines = 0, i;
    for (i = 0; i < size; i++) lines += data[i] == '\n';
    return lines + (size > 0 && data[size - 1] != '\n');
}

static int mesh_empty(const scene_mesh *m)
{
    return !m->positions && !m->indices && !m->normals && !m->colors && !m->vertex_count && !m->index_count;
}

/* A successful load: sound, and what the naive reader finds. */
static void check_mesh(const scene_mesh *m, const uint8_t *data, size_t size, int is_ply)
{
    ref_mesh ref = {NULL, NULL, 0, 0, 0, 0};
    uint32_t i;
    FZ_REQUIRE(m->vertex_count >= 1 && m->index_count >= 3 && m->index_count % 3 == 0, "a mesh of %u vertices, %u indices",
            m->vertex_count, m->index_count);
    FZ_REQUIRE(m->positions && m->indices && !m->normals && !m->colors, "the mesh's arrays");
    for (i = 0; i < m->index_count; i++)
        FZ_REQUIRE(m->indices[i] < m->vertex_count, "index %u of %u vertices", m->indices[i], m->vertex_count);
    for (i = 0; i < 3 * m->vertex_count; i++)
        FZ_REQUIRE(isfinite(m->positions[i]) && fabsf(m->positions[i]) <= (float)1e30, "coordinate %g", m->positions[i]);
    {
        char *text = (char *)malloc(size + 1);
        FZ_REQUIRE(text != NULL, "the harness ran out of memory");
        memcpy(text, data, size);
        text[size] = '\0';
        if (is_ply) ref_ply(data, size, &ref);
        else ref_obj(text, &ref);
        free(text);
    }
    FZ_REQUIRE(ref.vertex_count == m->vertex_count && ref.index_count == m->index_count,
            "the naive reader finds %lu vertices and %lu indices, the loader %u and %u", (unsigned long)ref.vertex_count,
            (unsigned long)ref.index_count, m->vertex_count, m->index_count);
    FZ_REQUIRE(memcmp(ref.positions, m->positions, sizeof(float) * 3 * m->vertex_count) == 0,
            "the coordinates differ from the naive reader's");
    FZ_REQUIRE(memcmp(ref.indices, m->indices, sizeof(uint32_t) * m->index_count) == 0,
            "the indices differ from the naive reader's");
    free(ref.positions);
    free(ref.indices);
}

/* The mesh written as OBJ loads as the same mesh. */
static void check_round_trip(const scene_mesh *m)
{
    size_t capacity = 64 + 60 * (size_t)m->vertex_count + 40 * (size_t)m->index_count, n = 0;
    char *text = (char *)malloc(capacity), error[256];
    scene_mesh again;
    uint32_t i;
    FZ_REQUIRE(text != NULL, "the harness ran out of memory");
    for (i = 0; i < m->vertex_count; i++)
        n += (size_t)snprintf(text + n, capacity - n, "v %.9g %.9g %.9g\n", m->positions[3 * i], m->positions[3 * i + 1],
                              m->positions[3 * i + 2]);
    for (i = 0; i < m->index_count; i += 3)
        n += (size_t)snprintf(text + n, capacity - n, "f %u %u %u\n", m->indices[i] + 1, m->indices[i + 1] + 1,
                              m->indices[i + 2] + 1);
    fuzz_fail_at = 0;
    FZ_REQUIRE(meshio_parse("again.obj", text, n, &again, error, sizeof error), "the mesh written as OBJ: %s", error);
    FZ_REQUIRE(again.vertex_count == m->vertex_count && again.index_count == m->index_count &&
                memcmp(again.positions, m->positions, sizeof(float) * 3 * m->vertex_count) == 0 &&
                memcmp(again.indices, m->indices, sizeof(uint32_t) * m->index_count) == 0,
            "the mesh written as OBJ loads as another mesh");
    scene_free(&again);
    free(text);
}

/* A failure's message: starts with the name, then a place or a message
   about the whole file. */
static void check_message(const char *message, const char *name, const uint8_t *data, size_t size, int is_ply)
{
    static const char *whole[] = {": no vertices", ": no faces with 3 or more vertices", ": out of memory",
                                  ": empty file", ": 2^32 or more", ": cannot read"};
    size_t n = strlen(name), i;
    const char *rest = message + n;
    char *end;
    FZ_REQUIRE(message[0] != '\0', "a failure without a message");
    FZ_REQUIRE(strncmp(message, name, n) == 0, "the message does not start with the name \"%s\": %s", name, message);
    if (rest[0] == ':' && rest[1] >= '1' && rest[1] <= '9') {
        unsigned long line = strtoul(rest + 1, &end, 10);
        size_t lines = line_count(data, size);
        FZ_REQUIRE(end[0] == ':' && end[1] == ' ' && end[2] != '\0', "a line number without a message: %s", message);
        FZ_REQUIRE(line <= lines, "line %lu of an input of %lu lines: %s", line, (unsigned long)lines, message);
        return;
    }
    if (is_ply && strncmp(rest, ": byte ", 7) == 0 && rest[7] >= '0' && rest[7] <= '9') {
        unsigned long offset = strtoul(rest + 7, &end, 10);
        FZ_REQUIRE(end[0] == ':' && end[1] == ' ' && end[2] != '\0', "a byte offset without a message: %s", message);
        FZ_REQUIRE(offset <= size, "byte %lu of an input of %lu bytes: %s", offset, (unsigned long)size, message);
        return;
    }
    for (i = 0; i < sizeof whole / sizeof *whole; i++)
        if (strncmp(rest, whole[i], strlen(whole[i])) == 0) return;
    fz_fail(__FILE__, __LINE__, "a message with no place (line, byte offset) that is not about the whole file: %s", message);
}

static char fuzz_dir[256];

static void fuzz_remove_dir(void)
{
    if (fuzz_dir[0]) rmdir(fuzz_dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *input, size_t input_size);
int LLVMFuzzerTestOneInput(const uint8_t *input, size_t input_size)
{
    static const char *names[4] = {"in.obj", "in.ply", "in", "IN.PLY"};
    char message[512], small[80];
    const uint8_t *data;
    size_t size, small_size = 0;
    unsigned fail_at = 0;
    int flags, ok, is_ply;
    const char *name;
    scene_mesh m;
    if (input_size < 1) return 0;
    flags = input[0];
    data = input + 1;
    size = input_size - 1;
    if ((flags & 4) && size) {
        small_size = data[0] % 64;
        data++;
        size--;
    }
    if ((flags & 8) && size) {
        fail_at = 1u + data[0];
        data++;
        size--;
    }
    name = names[flags & 3];
    is_ply = (size >= 3 && memcmp(data, "ply", 3) == 0) || (flags & 3) == 1 || (flags & 3) == 3;

    /* the plain parse */
    fuzz_allocations = fuzz_fail_at = 0;
    memset(message, 0, sizeof message);
    ok = meshio_parse(name, data, size, &m, message, sizeof message);
    if (fz_verbose()) fprintf(stderr, "%s, %lu bytes: %s\n", name, (unsigned long)size, ok ? "loaded" : message);
    if (ok) {
        check_mesh(&m, data, size, is_ply);
        check_round_trip(&m);
    } else {
        FZ_REQUIRE(mesh_empty(&m), "a failure left a mesh");
        FZ_REQUIRE(memchr(message, '\0', sizeof message) != NULL, "the message is not NUL-terminated");
        check_message(message, name, data, size, is_ply);
    }

    /* a small buffer: the same message, cut, and nothing past it */
    if (flags & 4) {
        scene_mesh s;
        int ok2;
        memset(small, 0x5a, sizeof small);
        ok2 = meshio_parse(name, data, size, &s, small_size ? small : NULL, small_size);
        FZ_REQUIRE(ok2 == ok, "a small error buffer changed the result");
        if (ok2) scene_free(&s);
        else if (small_size) {
            FZ_REQUIRE(memchr(small, '\0', small_size) != NULL, "a message of a %lu-byte buffer is not NUL-terminated",
                    (unsigned long)small_size);
            FZ_REQUIRE(strncmp(small, message, small_size - 1) == 0 &&
                        strlen(small) == (strlen(message) < small_size - 1 ? strlen(message) : small_size - 1),
                    "the message cut to %lu bytes is \"%s\", not a prefix of \"%s\"", (unsigned long)small_size, small,
                    message);
        }
        for (size_t i = small_size; i < sizeof small; i++)
            FZ_REQUIRE((uint8_t)small[i] == 0x5a, "a %lu-byte error buffer was written past its end",
                    (unsigned long)small_size);
    }

    /* one failing allocation: the same result, or "out of memory" */
    if (fail_at) {
        scene_mesh f;
        char failed[512];
        int ok3;
        fuzz_allocations = 0;
        fuzz_fail_at = fail_at;
        ok3 = meshio_parse(name, data, size, &f, failed, sizeof failed);
        fuzz_fail_at = 0;
        if (ok3) {
            FZ_REQUIRE(ok && f.vertex_count == m.vertex_count && f.index_count == m.index_count &&
                        memcmp(f.positions, m.positions, sizeof(float) * 3 * m.vertex_count) == 0 &&
                        memcmp(f.indices, m.indices, sizeof(uint32_t) * m.index_count) == 0,
                    "with allocation %u failing, another mesh", fail_at);
            scene_free(&f);
        } else {
            FZ_REQUIRE(mesh_empty(&f), "a failure left a mesh");
            FZ_REQUIRE(strstr(failed, "out of memory") || (!ok && strcmp(failed, message) == 0),
                    "with allocation %u failing: \"%s\" (without: \"%s\")", fail_at, failed, ok ? "loaded" : message);
            check_message(failed, name, data, size, is_ply);
        }
    }

    /* from a file: what meshio_parse gave */
    if (flags & 16) {
        char path[512], loaded[1024];
        scene_mesh l;
        FILE *file;
        int ok4;
        if (!fuzz_dir[0]) {
            const char *tmp = getenv("TMPDIR");
            /* mkdtemp's template ends in six X, written apart */
            snprintf(fuzz_dir, sizeof fuzz_dir, "%s/manylods-fuzz-loader-%s", tmp && *tmp ? tmp : "/tmp", "XX" "XX" "XX");
            FZ_REQUIRE(mkdtemp(fuzz_dir) != NULL, "cannot create a directory for the harness's files");
            atexit(fuzz_remove_dir);
        }
        snprintf(path, sizeof path, "%s/%s", fuzz_dir, name);
        file = fopen(path, "wb");
        FZ_REQUIRE(file != NULL, "cannot write %s", path);
        FZ_REQUIRE(fwrite(data, 1, size, file) == size && fclose(file) == 0, "cannot write %s", path);
        ok4 = meshio_load(path, &l, loaded, sizeof loaded);
        remove(path);
        FZ_REQUIRE(ok4 == ok, "meshio_load and meshio_parse disagree: %s", ok4 ? "loaded" : loaded);
        if (ok4) {
            FZ_REQUIRE(l.vertex_count == m.vertex_count && l.index_count == m.index_count &&
                        memcmp(l.positions, m.positions, sizeof(float) * 3 * m.vertex_count) == 0 &&
                        memcmp(l.indices, m.indices, sizeof(uint32_t) * m.index_count) == 0,
                    "meshio_load gives another mesh");
            scene_free(&l);
        } else {
            /* the same message, with the path for the name */
            FZ_REQUIRE(strncmp(loaded, path, strlen(path)) == 0 && strcmp(loaded + strlen(path), message + strlen(name)) == 0,
                    "meshio_load says \"%s\", meshio_parse \"%s\"", loaded, message);
        }
    }
    if (ok) scene_free(&m);
    return 0;
}
