/* examples/meshio.h - a small OBJ and PLY loader for the examples and the
   benchmark of manylods (the library itself reads no files).  C99,
   header-only, no dependency beyond the C standard library and
   examples/scenes.h.

     int meshio_load(const char *path, scene_mesh *out, char *error, size_t error_size);
     int meshio_parse(const char *name, const void *data, size_t size, scene_mesh *out,
                      char *error, size_t error_size);

   meshio_load reads a file; meshio_parse the same bytes from memory (name
   only labels the messages).  They read positions and faces only (polygons
   are split into triangle fans; texture coordinates, normals, colours,
   lines and points are skipped), so out has positions and indices and no
   normals or colours; free it with scene_free.
   OBJ: "v x y z" and "f" lines with 1-based or negative (relative) indices
   in any of the forms i, i/t, i//n, i/t/n.  PLY: format ascii 1.0,
   binary_little_endian 1.0 or binary_big_endian 1.0; an element "vertex"
   with scalar properties x, y, z (any scalar type) and an element "face"
   with a list property vertex_indices (or vertex_index); other elements and
   properties are skipped.  The format comes from the extension (.obj,
   .ply, any case), else from the first bytes ("ply").
   Returns 1 on success; 0 with a message naming the file and, for OBJ and
   ASCII PLY, the line ("bunny.obj:12: ...") on a malformed, truncated or
   empty file, binary bytes in a text file, an index out of range, a
   coordinate that is not finite or beyond 1e30, a count that is not a
   whole number, or when memory runs out; *out is then left empty.  Memory
   and time grow with the file's size, never with the counts its header
   claims. */
#ifndef MANYLODS_EXAMPLES_MESHIO_H
#define MANYLODS_EXAMPLES_MESHIO_H

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../examples/scenes.h"

typedef struct meshio_buf {
    void *data;
    size_t count, capacity, size; /* elements, element size in bytes */
} meshio_buf;

static inline int meshio_push(meshio_buf *b, const void *element)
{
    if (b->count == b->capacity) {
        size_t cap = b->capacity ? 2 * b->capacity : 1024;
        void *p = realloc(b->data, cap * b->size);
        if (!p) return 0;
        b->data = p;
        b->capacity = cap;
    }
    memcpy((char *)b->data + b->count * b->size, element, b->size);
    b->count++;
    return 1;
}

static inline int meshio_fail(char *error, size_t size, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(error, size, format, args);
    va_end(args);
    return 0;
}

/* The whole file, NUL-terminated; *length excludes the NUL. */
static inline char *meshio_read_file(const char *path, size_t *length, char *error, size_t error_size)
{
    FILE *f = fopen(path, "rb");
    char *data = NULL;
    long size;
    if (!f) {
        meshio_fail(error, error_size, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        meshio_fail(error, error_size, "%s: cannot determine the file size", path);
        fclose(f);
        return NULL;
    }
    data = (char *)malloc((size_t)size + 1);
    if (!data) {
        meshio_fail(error, error_size, "%s: out of memory reading %ld bytes", path, size);
    } else if (fread(data, 1, (size_t)size, f) != (size_t)size) {
        meshio_fail(error, error_size, "%s: read error", path);
        free(data);
        data = NULL;
    } else {
        data[size] = '\0';
        *length = (size_t)size;
    }
    fclose(f);
    return data;
}

/* Move the triangles and vertices into a scene_mesh (no normals, colours). */
static inline int meshio_finish(const char *path, meshio_buf *vertices, meshio_buf *indices, scene_mesh *out,
                                char *error, size_t error_size)
{
    if (vertices->count == 0) return meshio_fail(error, error_size, "%s: no vertices", path);
    if (indices->count == 0) return meshio_fail(error, error_size, "%s: no faces with 3 or more vertices", path);
    if (vertices->count / 3 > 0xffffffffu || indices->count > 0xffffffffu)
        return meshio_fail(error, error_size, "%s: more than 2^32 vertices or indices", path);
    memset(out, 0, sizeof *out);
    out->positions = (float *)vertices->data;
    out->indices = (uint32_t *)indices->data;
    out->vertex_count = (uint32_t)(vertices->count / 3);
    out->index_count = (uint32_t)indices->count;
    vertices->data = indices->data = NULL;
    return 1;
}

/* Add the fan of a polygon of n >= 3 vertex indices. */
static inline int meshio_fan(meshio_buf *indices, const uint32_t *poly, size_t n)
{
    size_t i;
    for (i = 1; i + 1 < n; i++)
        if (!meshio_push(indices, &poly[0]) || !meshio_push(indices, &poly[i]) || !meshio_push(indices, &poly[i + 1]))
            return 0;
    return 1;
}

/* ------------------------------------------------------------------ OBJ */

static inline int meshio_load_obj(const char *path, char *text, scene_mesh *out, char *error, size_t error_size)
{
    meshio_buf vertices = {NULL, 0, 0, sizeof(float)}, indices = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_buf poly = {NULL, 0, 0, sizeof(uint32_t)};
    char *line = text;
    unsigned long line_number = 0;
    int ok = 0;
    while (*line) {
        char *end = strchr(line, '\n'), *p = line;
        if (end) *end = '\0';
        line_number++;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && (p[1] == ' ' || p[1] == '\t')) {
            float xyz[3];
            int k;
            p += 2;
            for (k = 0; k < 3; k++) {
                char *next;
                double x = strtod(p, &next);
                if (next == p) {
                    meshio_fail(error, error_size, "%s:%lu: a vertex needs 3 numbers (\"v x y z\")", path, line_number);
                    goto done;
                }
                if (!isfinite(x) || fabs(x) > 1e30) {
                    meshio_fail(error, error_size, "%s:%lu: vertex coordinate %g is not finite or beyond 1e30", path,
                                line_number, x);
                    goto done;
                }
                xyz[k] = (float)x;
                p = next;
            }
            for (k = 0; k < 3; k++)
                if (!meshio_push(&vertices, &xyz[k])) goto oom;
        } else if (p[0] == 'f' && (p[1] == ' ' || p[1] == '\t')) {
            size_t have = vertices.count / 3;
            p += 2;
            poly.count = 0;
            for (;;) {
                char *next;
                long i;
                uint32_t index;
                while (*p == ' ' || *p == '\t' || *p == '\r') p++;
                if (!*p || *p == '#') break;
                i = strtol(p, &next, 10);
                if (next == p || i == 0) {
                    meshio_fail(error, error_size, "%s:%lu: bad face vertex \"%.20s\" (expected a non-zero index)",
                                path, line_number, p);
                    goto done;
                }
                if (*next && *next != '/' && *next != ' ' && *next != '\t' && *next != '\r' && *next != '#') {
                    meshio_fail(error, error_size, "%s:%lu: bad face vertex \"%.20s\" (expected i, i/t, i//n or i/t/n)",
                                path, line_number, p);
                    goto done;
                }
                if (i < 0) i += (long)have + 1; /* relative to the last vertex */
                if (i < 1 || (size_t)i > have) {
                    meshio_fail(error, error_size, "%s:%lu: face index %ld out of range (%lu vertices so far)", path,
                                line_number, i, (unsigned long)have);
                    goto done;
                }
                index = (uint32_t)(i - 1);
                if (!meshio_push(&poly, &index)) goto oom;
                p = next;
                while (*p && *p != ' ' && *p != '\t' && *p != '\r') p++; /* skip /t/n */
            }
            if (poly.count < 3) {
                meshio_fail(error, error_size, "%s:%lu: a face needs at least 3 vertices, it has %lu", path,
                            line_number, (unsigned long)poly.count);
                goto done;
            }
            if (!meshio_fan(&indices, (const uint32_t *)poly.data, poly.count)) goto oom;
        }
        if (!end) break;
        line = end + 1;
    }
    ok = meshio_finish(path, &vertices, &indices, out, error, error_size);
    goto done;
oom:
    meshio_fail(error, error_size, "%s:%lu: out of memory", path, line_number);
done:
    free(vertices.data);
    free(indices.data);
    free(poly.data);
    return ok;
}

/* ------------------------------------------------------------------ PLY */

enum { MESHIO_ASCII, MESHIO_LITTLE, MESHIO_BIG };

typedef struct meshio_property {
    char name[32];
    int type;       /* bytes of the value: 1, 2, 4, 8; negative for signed ints, 0x40 | 4/8 for floats */
    int count_type; /* list count type as above, or 0 for a scalar */
} meshio_property;

typedef struct meshio_element {
    char name[32];
    unsigned long count;
    meshio_property properties[16];
    int property_count;
} meshio_element;

static inline int meshio_ply_type(const char *name)
{
    static const char *names[] = {"char", "int8", "uchar", "uint8", "short", "int16", "ushort", "uint16",
                                  "int",  "int32", "uint", "uint32", "float", "float32", "double", "float64"};
    static const int types[] = {-1, -1, 1, 1, -2, -2, 2, 2, -4, -4, 4, 4, 0x44, 0x44, 0x48, 0x48};
    int i;
    for (i = 0; i < 16; i++)
        if (strcmp(name, names[i]) == 0) return types[i];
    return 0;
}

static inline size_t meshio_type_bytes(int type) { return (size_t)((type < 0 ? -type : type) & 0xf); }

/* A reader over the body: ASCII tokens or binary values. */
typedef struct meshio_reader {
    const char *path;
    const unsigned char *p, *end;
    int format;
    unsigned long line; /* ASCII only */
} meshio_reader;

static inline int meshio_read_value(meshio_reader *r, int type, double *value)
{
    if (r->format == MESHIO_ASCII) {
        char *next;
        while (r->p < r->end && isspace(*r->p)) {
            if (*r->p == '\n') r->line++;
            r->p++;
        }
        if (r->p >= r->end) return 0;
        *value = strtod((const char *)r->p, &next);
        if ((const unsigned char *)next == r->p) return 0;
        r->p = (const unsigned char *)next;
        return 1;
    } else {
        unsigned char b[8];
        size_t n = meshio_type_bytes(type), i;
        if ((size_t)(r->end - r->p) < n) return 0;
        for (i = 0; i < n; i++) b[i] = r->p[r->format == MESHIO_LITTLE ? i : n - 1 - i];
        r->p += n;
        switch (type) {
        case -1: *value = (int8_t)b[0]; break;
        case 1: *value = b[0]; break;
        case -2: { int16_t v; memcpy(&v, b, 2); *value = v; } break;
        case 2: { uint16_t v; memcpy(&v, b, 2); *value = v; } break;
        case -4: { int32_t v; memcpy(&v, b, 4); *value = v; } break;
        case 4: { uint32_t v; memcpy(&v, b, 4); *value = v; } break;
        case 0x44: { float v; memcpy(&v, b, 4); *value = v; } break;
        default: { double v; memcpy(&v, b, 8); *value = v; } break;
        }
        return 1;
    }
}

static inline int meshio_load_ply(const char *path, char *text, size_t length, scene_mesh *out, char *error,
                                  size_t error_size)
{
    meshio_element elements[16];
    int element_count = 0, format = -1, e, ok = 0;
    unsigned long line_number = 1, vertex_total = 0;
    char *p = text, *body;
    meshio_buf vertices = {NULL, 0, 0, sizeof(float)}, indices = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_buf poly = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_reader r;
    /* the header, line by line, up to end_header */
    for (;;) {
        char *end = strchr(p, '\n'), word[4][32];
        int words;
        if (!end) return meshio_fail(error, error_size, "%s: the header has no end_header line", path);
        *end = '\0';
        if (end > p && end[-1] == '\r') end[-1] = '\0';
        words = sscanf(p, "%31s %31s %31s %31s", word[0], word[1], word[2], word[3]);
        if (line_number == 1 && (words < 1 || strcmp(word[0], "ply") != 0))
            return meshio_fail(error, error_size, "%s:1: not a PLY file (no \"ply\" line)", path);
        if (words >= 1 && strcmp(word[0], "end_header") == 0) {
            body = end + 1;
            break;
        }
        if (words >= 2 && strcmp(word[0], "format") == 0) {
            if (strcmp(word[1], "ascii") == 0) format = MESHIO_ASCII;
            else if (strcmp(word[1], "binary_little_endian") == 0) format = MESHIO_LITTLE;
            else if (strcmp(word[1], "binary_big_endian") == 0) format = MESHIO_BIG;
            else return meshio_fail(error, error_size, "%s:%lu: unknown format \"%s\"", path, line_number, word[1]);
        } else if (words >= 1 && strcmp(word[0], "element") == 0) {
            meshio_element *el = &elements[element_count];
            char *tail;
            if (element_count == 16) return meshio_fail(error, error_size, "%s:%lu: more than 16 elements", path, line_number);
            if (words < 3) return meshio_fail(error, error_size, "%s:%lu: \"element NAME COUNT\" expected", path, line_number);
            memset(el, 0, sizeof *el);
            strcpy(el->name, word[1]);
            el->count = strtoul(word[2], &tail, 10);
            if (*tail) return meshio_fail(error, error_size, "%s:%lu: bad element count \"%s\"", path, line_number, word[2]);
            element_count++;
        } else if (words >= 1 && strcmp(word[0], "property") == 0) {
            meshio_element *el = element_count ? &elements[element_count - 1] : NULL;
            meshio_property *prop;
            if (!el) return meshio_fail(error, error_size, "%s:%lu: a property before any element", path, line_number);
            if (el->property_count == 16)
                return meshio_fail(error, error_size, "%s:%lu: more than 16 properties", path, line_number);
            prop = &el->properties[el->property_count++];
            memset(prop, 0, sizeof *prop);
            if (words >= 2 && strcmp(word[1], "list") == 0) {
                if (words < 4) {
                    /* sscanf stops at 4 words: "property list T1 T2 NAME" names sit further */
                    return meshio_fail(error, error_size, "%s:%lu: \"property list COUNT_TYPE TYPE NAME\" expected",
                                       path, line_number);
                }
                prop->count_type = meshio_ply_type(word[2]);
                prop->type = meshio_ply_type(word[3]);
                if (sscanf(p, "%*s %*s %*s %*s %31s", prop->name) != 1)
                    return meshio_fail(error, error_size, "%s:%lu: the list property has no name", path, line_number);
                if (!prop->count_type || !prop->type || (prop->count_type & 0x40))
                    return meshio_fail(error, error_size, "%s:%lu: bad list types \"%s %s\"", path, line_number,
                                       word[2], word[3]);
            } else {
                if (words < 3) return meshio_fail(error, error_size, "%s:%lu: \"property TYPE NAME\" expected", path, line_number);
                prop->type = meshio_ply_type(word[1]);
                strcpy(prop->name, word[2]);
                if (!prop->type)
                    return meshio_fail(error, error_size, "%s:%lu: unknown property type \"%s\"", path, line_number, word[1]);
            }
        } else if (words >= 1 && strcmp(word[0], "comment") != 0 && strcmp(word[0], "obj_info") != 0 &&
                   strcmp(word[0], "ply") != 0) {
            return meshio_fail(error, error_size, "%s:%lu: unexpected header line \"%s\"", path, line_number, word[0]);
        }
        p = end + 1;
        line_number++;
    }
    if (format < 0) return meshio_fail(error, error_size, "%s: the header has no format line", path);
    r.path = path;
    r.p = (const unsigned char *)body;
    r.end = (const unsigned char *)text + length;
    r.format = format;
    r.line = line_number + 1;
    for (e = 0; e < element_count; e++) {
        meshio_element *el = &elements[e];
        int is_vertex = strcmp(el->name, "vertex") == 0, is_face = strcmp(el->name, "face") == 0;
        int axis[16], k;
        unsigned long i;
        for (k = 0; k < el->property_count; k++) {
            const char *n = el->properties[k].name;
            axis[k] = -1;
            if (is_vertex && !el->properties[k].count_type && n[1] == '\0' && n[0] >= 'x' && n[0] <= 'z')
                axis[k] = n[0] - 'x';
            if (is_face && el->properties[k].count_type &&
                (strcmp(n, "vertex_indices") == 0 || strcmp(n, "vertex_index") == 0))
                axis[k] = 3;
        }
        if (is_vertex) {
            int seen = 0;
            for (k = 0; k < el->property_count; k++)
                if (axis[k] >= 0) seen |= 1 << axis[k];
            if (seen != 7) {
                meshio_fail(error, error_size, "%s: element vertex lacks one of the properties x, y, z", path);
                goto done;
            }
            vertex_total = el->count;
        }
        if (is_face) {
            int seen = 0;
            for (k = 0; k < el->property_count; k++) seen |= axis[k] == 3;
            if (!seen) {
                meshio_fail(error, error_size, "%s: element face has no list property vertex_indices", path);
                goto done;
            }
        }
        if (el->property_count == 0) continue; /* holds no bytes, however many it claims */
        for (i = 0; i < el->count; i++) {
            float xyz[3] = {0, 0, 0};
            for (k = 0; k < el->property_count; k++) {
                const meshio_property *prop = &el->properties[k];
                double value;
                if (prop->count_type) {
                    double n;
                    unsigned long j;
                    if (!meshio_read_value(&r, prop->count_type, &n)) goto truncated;
                    if (!(n >= 0 && n <= 4294967295.0 && n == floor(n))) {
                        meshio_fail(error, error_size, "%s: element %s %lu: list count %g is not a whole number in [0, 2^32)",
                                    path, el->name, i, n);
                        goto done;
                    }
                    poly.count = 0;
                    for (j = 0; j < (unsigned long)n; j++) {
                        uint32_t index;
                        if (!meshio_read_value(&r, prop->type, &value)) goto truncated;
                        if (axis[k] != 3) continue;
                        if (!(value >= 0 && value < (double)vertex_total && value == floor(value))) {
                            meshio_fail(error, error_size, "%s: face %lu: vertex index %g out of range (%lu vertices)",
                                        path, i, value, vertex_total);
                            goto done;
                        }
                        index = (uint32_t)value;
                        if (!meshio_push(&poly, &index)) goto oom;
                    }
                    if (axis[k] == 3) {
                        if (poly.count < 3) {
                            meshio_fail(error, error_size, "%s: face %lu has %lu vertices, at least 3 needed", path, i,
                                        (unsigned long)poly.count);
                            goto done;
                        }
                        if (!meshio_fan(&indices, (const uint32_t *)poly.data, poly.count)) goto oom;
                    }
                } else {
                    if (!meshio_read_value(&r, prop->type, &value)) goto truncated;
                    if (axis[k] >= 0 && axis[k] < 3) {
                        if (!isfinite(value) || fabs(value) > 1e30) {
                            meshio_fail(error, error_size, "%s: vertex %lu: coordinate %g is not finite or beyond 1e30", path, i,
                                    value);
                            goto done;
                        }
                        xyz[axis[k]] = (float)value;
                    }
                }
            }
            if (is_vertex)
                for (k = 0; k < 3; k++)
                    if (!meshio_push(&vertices, &xyz[k])) goto oom;
        }
    }
    ok = meshio_finish(path, &vertices, &indices, out, error, error_size);
    goto done;
truncated:
    if (format == MESHIO_ASCII)
        meshio_fail(error, error_size, "%s:%lu: truncated or malformed body (a number was expected)", path, r.line);
    else
        meshio_fail(error, error_size, "%s: truncated body (the file ends inside the data the header declares)", path);
    goto done;
oom:
    meshio_fail(error, error_size, "%s: out of memory", path);
done:
    free(vertices.data);
    free(indices.data);
    free(poly.data);
    return ok;
}

/* Whether path ends with ext (".ply"), ignoring ASCII case. */
static inline int meshio_has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext), i;
    if (n < m) return 0;
    for (i = 0; i < m; i++)
        if (tolower((unsigned char)path[n - m + i]) != ext[i]) return 0;
    return 1;
}

/* Parse text (length bytes, NUL-terminated, modified in place) as the file
   `name`. */
static inline int meshio_parse_text(const char *name, char *text, size_t length, scene_mesh *out, char *error,
                                    size_t error_size)
{
    int is_ply = length >= 3 && memcmp(text, "ply", 3) == 0;
    memset(out, 0, sizeof *out);
    if (!is_ply && strlen(text) != length)
        return meshio_fail(error, error_size, "%s: binary data in a text file (only PLY may be binary)", name);
    if (is_ply || meshio_has_extension(name, ".ply")) return meshio_load_ply(name, text, length, out, error, error_size);
    return meshio_load_obj(name, text, out, error, error_size);
}

static inline int meshio_parse(const char *name, const void *data, size_t size, scene_mesh *out, char *error,
                               size_t error_size)
{
    char *text = (char *)malloc(size + 1);
    int ok;
    memset(out, 0, sizeof *out);
    if (!text) return meshio_fail(error, error_size, "%s: out of memory for %lu bytes", name, (unsigned long)size);
    if (size) memcpy(text, data, size);
    text[size] = '\0';
    ok = meshio_parse_text(name, text, size, out, error, error_size);
    free(text);
    return ok;
}

static inline int meshio_load(const char *path, scene_mesh *out, char *error, size_t error_size)
{
    size_t length = 0;
    char *text;
    int ok;
    memset(out, 0, sizeof *out);
    text = meshio_read_file(path, &length, error, error_size);
    if (!text) return 0;
    ok = meshio_parse_text(path, text, length, out, error, error_size);
    free(text);
    return ok;
}

#endif /* MANYLODS_EXAMPLES_MESHIO_H */
