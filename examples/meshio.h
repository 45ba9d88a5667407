/* examples/meshio.h - a small OBJ and PLY loader for the examples and the
   benchmark of manylods (the library itself reads no files, and this
   loader is no part of it).  C99, header-only, no dependency beyond the C
   standard library and examples/scenes.h.

     int meshio_load(const char *path, scene_mesh *out, char *error, size_t error_size);
     int meshio_parse(const char *name, const void *data, size_t size, scene_mesh *out,
                      char *error, size_t error_size);

   meshio_load reads a file; meshio_parse the same bytes from memory (name
   only labels the messages).  Both return 1 with positions and indices in
   *out (no normals or colours; free it with scene_free), or 0 with *out
   empty and a message in error (error_size bytes, cut to fit, NUL-ended;
   error may be NULL when error_size is 0).  Polygons become triangle fans;
   texture coordinates, normals, colours, lines and points are skipped.
   Memory and time grow with the input's size, never with the counts its
   header claims.  Define MESHIO_MALLOC(size) and MESHIO_REALLOC(p, size)
   before the include to count or fail allocations (blocks are freed with
   free(), as scene_free does).

   Accepted.  The format comes from the first bytes ("ply": PLY), else from
   the extension (.ply, any case: PLY; anything else: OBJ).
   - OBJ (text, no NUL byte): "v x y z" lines (numbers after z are
     ignored) and "f" lines of 3 or more vertices, each i, i/t, i//n or
     i/t/n: i is 1-based, or negative to count back from the last vertex so
     far (-1 is the last); t and n must be integers and are not used.
     Other lines are skipped.
   - PLY 1.0: a first line "ply"; one line "format ascii 1.0",
     "format binary_little_endian 1.0" or "format binary_big_endian 1.0";
     comment, obj_info and empty lines; an element "vertex" with scalar
     properties x, y, z (any scalar type) and, after it, an element "face"
     with one list property vertex_indices (or vertex_index); other
     elements and properties are read and skipped.  At most 16 elements of
     at most 16 properties; names of at most 31 printable ASCII characters;
     element counts of digits only.  An ASCII value used (a coordinate, a
     list count, an index) must fit its declared type; text after the last
     element is an error in ASCII, bytes after it are ignored in binary.
   - Coordinates finite and within +-1e30 as floats (1.00000002e30, the
     float of 1e30, is accepted); indices in range; at least one vertex and
     one triangle, fewer than 2^32 vertices and indices.

   Messages.  Every message starts with the file's name (the path for
   meshio_load).  An error found at a place in a text (an OBJ line, a PLY
   header line, a value of an ASCII PLY body) names that line:
   "bunny.obj:12: ..." (lines count from 1; an error at the end of the file
   names its last line).  An error in a binary PLY body names the byte
   offset, from the start of the file, of the value: "bunny.ply: byte 4096:
   ...".  Values are quoted as written in a text (an OBJ index of
   99999999999999999999 as such; a relative OBJ index out of range with the
   vertex count so far); binary values as their type holds them; PLY
   entries count from 0 like PLY's own indices.  Only errors about the
   whole file name no place: cannot open or read it (with the system's
   reason, such as "Is a directory"), an empty PLY, out of memory (except
   in OBJ, which names the line it was reading), no vertices, no triangles,
   2^32 or more vertices or indices. */
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

#ifndef MESHIO_MALLOC
#define MESHIO_MALLOC(size) malloc(size)
#endif
#ifndef MESHIO_REALLOC
#define MESHIO_REALLOC(p, size) realloc(p, size)
#endif

typedef struct meshio_buf {
    void *data;
    size_t count, capacity, size; /* elements, element size in bytes */
} meshio_buf;

static inline int meshio_push(meshio_buf *b, const void *element)
{
    if (b->count == b->capacity) {
        size_t cap = b->capacity ? 2 * b->capacity : 256;
        void *p;
        if (cap / 2 < b->capacity || cap > (size_t)-1 / b->size) return 0;
        p = MESHIO_REALLOC(b->data, cap * b->size);
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
    if (!error || !size) return 0;
    va_start(args, format);
    vsnprintf(error, size, format, args);
    va_end(args);
    return 0;
}

/* The token at s (up to whitespace, a NUL or end; end NULL: up to
   whitespace or a NUL) for a message: at most 40 bytes, '?' for a byte
   that is not printable ASCII, "..." when cut. */
static inline const char *meshio_token(char out[48], const char *s, const char *end)
{
    size_t n = 0;
    while ((!end || s < end) && *s && !isspace((unsigned char)*s) && n < 40) {
        unsigned char c = (unsigned char)*s++;
        out[n++] = (char)(c > 0x20 && c < 0x7f ? c : '?');
    }
    if ((!end || s < end) && *s && !isspace((unsigned char)*s)) {
        memcpy(out + n, "...", 3);
        n += 3;
    }
    out[n] = '\0';
    return out;
}

/* The 1-based line of text[offset]. */
static inline unsigned long meshio_line_of(const char *text, size_t offset)
{
    unsigned long line = 1;
    size_t i;
    for (i = 0; i < offset; i++) line += text[i] == '\n';
    return line;
}

/* The whole file, NUL-terminated; *length excludes the NUL.  Read in
   growing blocks until the end, so that what a file claims to hold (a
   directory's or a device's size) does not matter. */
static inline char *meshio_read_file(const char *path, size_t *length, char *error, size_t error_size)
{
    FILE *f;
    char *data = NULL;
    size_t size = 0, capacity = 0;
    errno = 0;
    f = fopen(path, "rb");
    if (!f) {
        meshio_fail(error, error_size, "%s: cannot open: %s", path, errno ? strerror(errno) : "unknown reason");
        return NULL;
    }
    for (;;) {
        size_t want, got;
        if (capacity - size < 2) {
            size_t cap = capacity ? 2 * capacity : 65536;
            char *p = cap > capacity ? (char *)MESHIO_REALLOC(data, cap) : NULL;
            if (!p) {
                meshio_fail(error, error_size, "%s: out of memory after reading %lu bytes", path, (unsigned long)size);
                goto fail;
            }
            data = p;
            capacity = cap;
        }
        want = capacity - size - 1;
        errno = 0;
        got = fread(data + size, 1, want, f);
        size += got;
        if (got < want) {
            if (ferror(f)) {
                if (errno)
                    meshio_fail(error, error_size, "%s: cannot read: %s", path, strerror(errno));
                else
                    meshio_fail(error, error_size, "%s: cannot read (a directory, or not a regular file?)", path);
                goto fail;
            }
            break;
        }
    }
    fclose(f);
    data[size] = '\0';
    *length = size;
    return data;
fail:
    fclose(f);
    free(data);
    return NULL;
}

/* Whether x, stored as a float, is finite and within +-1e30: the bound
   is the float nearest 1e30, so that the float of an accepted coordinate,
   written out and read back, is accepted again. */
static inline int meshio_coordinate_ok(double x)
{
    return fabs(x) <= 1.0000001e30 && fabsf((float)x) <= (float)1e30;
}

/* Move the triangles and vertices into a scene_mesh (no normals, colours). */
static inline int meshio_finish(const char *path, meshio_buf *vertices, meshio_buf *indices, scene_mesh *out,
                                char *error, size_t error_size)
{
    if (vertices->count == 0) return meshio_fail(error, error_size, "%s: no vertices", path);
    if (indices->count == 0) return meshio_fail(error, error_size, "%s: no faces with 3 or more vertices", path);
    if (vertices->count / 3 > 0xffffffffu || indices->count > 0xffffffffu)
        return meshio_fail(error, error_size, "%s: 2^32 or more vertices or indices (at most 2^32 - 1 of each)", path);
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

/* An optional sign and at least one digit at *p, moved past them.  Returns
   0 without digits; else 1 with the magnitude in *value (saturated at
   2^40, far beyond any index that fits) and *negative. */
static inline int meshio_obj_integer(const char **p, unsigned long long *value, int *negative)
{
    const char *s = *p;
    unsigned long long v = 0;
    *negative = *s == '-';
    if (*s == '-' || *s == '+') s++;
    if (!isdigit((unsigned char)*s)) return 0;
    while (isdigit((unsigned char)*s)) {
        if (v < (1ull << 40)) v = 10 * v + (unsigned long long)(*s - '0');
        s++;
    }
    *p = s;
    *value = v;
    return 1;
}

static inline int meshio_obj_ends(char c) { return c == '\0' || c == ' ' || c == '\t' || c == '\r' || c == '#'; }

static inline int meshio_load_obj(const char *path, char *text, size_t length, scene_mesh *out, char *error,
                                  size_t error_size)
{
    meshio_buf vertices = {NULL, 0, 0, sizeof(float)}, indices = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_buf poly = {NULL, 0, 0, sizeof(uint32_t)};
    char *line = text, token[48];
    const char *nul = (const char *)memchr(text, '\0', length);
    unsigned long line_number = 0;
    int ok = 0;
    if (nul)
        return meshio_fail(error, error_size, "%s:%lu: a NUL byte: binary data in a text file (only PLY may be binary)",
                           path, meshio_line_of(text, (size_t)(nul - text)));
    while (*line) {
        char *end = strchr(line, '\n'), *p = line;
        if (end) *end = '\0';
        line_number++;
        while (*p == ' ' || *p == '\t') p++;
        if (p[0] == 'v' && meshio_obj_ends(p[1]) && p[1] != '#') {
            float xyz[3];
            int k;
            p++;
            for (k = 0; k < 3; k++) {
                char *next;
                double x;
                while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\v' || *p == '\f') p++;
                if (!*p || *p == '#') {
                    meshio_fail(error, error_size, "%s:%lu: a vertex needs 3 numbers (\"v x y z\"), this one has %d",
                                path, line_number, k);
                    goto done;
                }
                x = strtod(p, &next);
                if (next == p || !meshio_obj_ends(*next)) {
                    meshio_fail(error, error_size, "%s:%lu: vertex coordinate \"%s\" is not a number", path,
                                line_number, meshio_token(token, p, NULL));
                    goto done;
                }
                if (!meshio_coordinate_ok(x)) {
                    meshio_fail(error, error_size, "%s:%lu: vertex coordinate %s is not finite or beyond 1e30", path,
                                line_number, meshio_token(token, p, NULL));
                    goto done;
                }
                xyz[k] = (float)x;
                p = next;
            }
            for (k = 0; k < 3; k++)
                if (!meshio_push(&vertices, &xyz[k])) goto oom;
        } else if (p[0] == 'f' && meshio_obj_ends(p[1]) && p[1] != '#') {
            unsigned long have = (unsigned long)(vertices.count / 3);
            p++;
            poly.count = 0;
            for (;;) {
                const char *q, *start;
                unsigned long long i, unused;
                int negative, unused_sign, form_ok;
                uint32_t index;
                while (*p == ' ' || *p == '\t' || *p == '\r') p++;
                if (!*p || *p == '#') break;
                q = start = p;
                form_ok = meshio_obj_integer(&q, &i, &negative);
                if (form_ok && *q == '/') { /* i/t, i//n, i/t/n */
                    q++;
                    if (*q == '/') {
                        q++;
                        form_ok = meshio_obj_integer(&q, &unused, &unused_sign);
                    } else {
                        form_ok = meshio_obj_integer(&q, &unused, &unused_sign);
                        if (form_ok && *q == '/') {
                            q++;
                            form_ok = meshio_obj_integer(&q, &unused, &unused_sign);
                        }
                    }
                }
                if (!form_ok || !meshio_obj_ends(*q)) {
                    meshio_fail(error, error_size, "%s:%lu: bad face vertex \"%s\" (expected i, i/t, i//n or i/t/n with "
                                "integers i, t, n)", path, line_number, meshio_token(token, start, NULL));
                    goto done;
                }
                /* the index as written: from its first character to its last digit */
                {
                    const char *digits = start + (*start == '-' || *start == '+');
                    size_t n = 0;
                    while (isdigit((unsigned char)digits[n])) n++;
                    n += (size_t)(digits - start);
                    memcpy(token, start, n > 40 ? 40 : n);
                    strcpy(token + (n > 40 ? 40 : n), n > 40 ? "..." : "");
                }
                if (i == 0) {
                    meshio_fail(error, error_size, "%s:%lu: face index %s: expected a non-zero index (1 is the first "
                                "vertex, -1 the last so far)", path, line_number, token);
                    goto done;
                }
                if (i > have) {
                    if (negative && have == 0)
                        meshio_fail(error, error_size, "%s:%lu: relative face index %s out of range (no vertex so far)",
                                    path, line_number, token);
                    else if (negative)
                        meshio_fail(error, error_size, "%s:%lu: relative face index %s out of range (%lu vertices so far, "
                                    "so -1 .. -%lu)", path, line_number, token, have, have);
                    else
                        meshio_fail(error, error_size, "%s:%lu: face index %s out of range (%lu vertices so far)", path,
                                    line_number, token, have);
                    goto done;
                }
                index = (uint32_t)(negative ? have - i : i - 1);
                if (!meshio_push(&poly, &index)) goto oom;
                p = (char *)q;
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
    int role;       /* 0, 1, 2: x, y, z of a vertex; 3: a face's indices; -1: skipped */
} meshio_property;

typedef struct meshio_element {
    char name[32];
    unsigned long count, line; /* entries; the header line declaring it */
    meshio_property properties[16];
    int property_count;
} meshio_element;

static const char *const meshio_type_names[] = {"char", "int8",  "uchar", "uint8",   "short",  "int16",
                                                "ushort", "uint16", "int", "int32", "uint", "uint32",
                                                "float", "float32", "double", "float64"};
static const int meshio_types[] = {-1, -1, 1, 1, -2, -2, 2, 2, -4, -4, 4, 4, 0x44, 0x44, 0x48, 0x48};

static inline int meshio_ply_type(const char *name)
{
    int i;
    for (i = 0; i < 16; i++)
        if (strcmp(name, meshio_type_names[i]) == 0) return meshio_types[i];
    return 0;
}

static inline const char *meshio_type_name(int type)
{
    int i;
    for (i = 0; i < 16; i += 2)
        if (meshio_types[i] == type) return meshio_type_names[i];
    return "?";
}

static inline size_t meshio_type_bytes(int type) { return (size_t)((type < 0 ? -type : type) & 0xf); }

/* Whether value is one of type's values (an integer type's range, whole;
   any number for a float type). */
static inline int meshio_fits(int type, double value)
{
    double lo, hi;
    if (type & 0x40) return 1;
    if (value != floor(value)) return 0;
    hi = type < 0 ? ldexp(1.0, 8 * (int)meshio_type_bytes(type) - 1) - 1 : ldexp(1.0, 8 * (int)meshio_type_bytes(type)) - 1;
    lo = type < 0 ? -hi - 1 : 0.0;
    return value >= lo && value <= hi;
}

/* A reader over the body: ASCII tokens or binary values. */
typedef struct meshio_reader {
    const char *path;
    const unsigned char *start, *p, *end; /* the file, the next byte, the end */
    int format;
    unsigned long line;         /* ASCII: the line of p */
    const unsigned char *value; /* the last value read or tried: its first byte */
    unsigned long value_line;   /* ASCII: its line */
    int newline_at_end;         /* whether the file's last byte is a newline */
} meshio_reader;

/* 1 with *value; 0 at the end of the data (r->value_line: the last line);
   -1 on an ASCII token that is not a number. */
static inline int meshio_read_value(meshio_reader *r, int type, double *value)
{
    if (r->format == MESHIO_ASCII) {
        char *next;
        while (r->p < r->end && isspace(*r->p)) {
            if (*r->p == '\n') r->line++;
            r->p++;
        }
        r->value = r->p;
        r->value_line = r->line;
        if (r->p >= r->end) {
            r->value_line -= r->newline_at_end; /* no line after the last newline */
            return 0;
        }
        *value = strtod((const char *)r->p, &next);
        if ((const unsigned char *)next == r->p || ((const unsigned char *)next < r->end && !isspace((unsigned char)*next)))
            return -1;
        r->p = (const unsigned char *)next;
        return 1;
    } else {
        size_t n = meshio_type_bytes(type), i;
        uint64_t u = 0; /* the value's bits, whatever the host's byte order */
        r->value = r->p;
        if ((size_t)(r->end - r->p) < n) {
            r->value = r->end;
            return 0;
        }
        for (i = 0; i < n; i++) u |= (uint64_t)r->p[r->format == MESHIO_LITTLE ? i : n - 1 - i] << (8 * i);
        r->p += n;
        if (type == 0x44) {
            uint32_t bits = (uint32_t)u;
            float v;
            memcpy(&v, &bits, 4);
            *value = v;
        } else if (type == 0x48) {
            double v;
            memcpy(&v, &u, 8);
            *value = v;
        } else if (type < 0 && (u >> (8 * n - 1))) {
            *value = (double)u - ldexp(1.0, 8 * (int)n); /* two's complement */
        } else {
            *value = (double)u;
        }
        return 1;
    }
}

/* The last value as written: its ASCII token, or the binary value. */
static inline const char *meshio_value_text(char out[48], const meshio_reader *r, int type, double value)
{
    if (r->format == MESHIO_ASCII) return meshio_token(out, (const char *)r->value, (const char *)r->end);
    snprintf(out, 48, type == 0x44 ? "%.9g" : type == 0x48 ? "%.17g" : "%.0f", value);
    return out;
}

/* A message placed at the last value: "path:line: ..." (ASCII) or
   "path: byte N: ..." (binary). */
static inline int meshio_body_fail(const meshio_reader *r, char *error, size_t error_size, const char *format, ...)
{
    char detail[320];
    va_list args;
    va_start(args, format);
    vsnprintf(detail, sizeof detail, format, args);
    va_end(args);
    if (r->format == MESHIO_ASCII) return meshio_fail(error, error_size, "%s:%lu: %s", r->path, r->value_line, detail);
    return meshio_fail(error, error_size, "%s: byte %lu: %s", r->path, (unsigned long)(r->value - r->start), detail);
}

/* A whole number of decimal digits only: 1 with *count, 0 if not such a
   number, -1 if beyond unsigned long. */
static inline int meshio_ply_count(const char *s, unsigned long *count)
{
    unsigned long v = 0;
    if (!*s) return 0;
    for (; *s; s++) {
        unsigned d;
        if (!isdigit((unsigned char)*s)) return 0;
        d = (unsigned)(*s - '0');
        if (v > ((unsigned long)-1 - d) / 10) return -1;
        v = 10 * v + d;
    }
    *count = v;
    return 1;
}

static inline int meshio_load_ply(const char *path, char *text, size_t length, scene_mesh *out, char *error,
                                  size_t error_size)
{
    meshio_element elements[16];
    int element_count = 0, format = -1, vertex_element = -1, e, ok = 0, newline_at_end;
    unsigned long line_number = 1, vertex_total = 0;
    char *p = text, *text_end = text + length, *body, token[48], token2[48];
    meshio_buf vertices = {NULL, 0, 0, sizeof(float)}, indices = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_buf poly = {NULL, 0, 0, sizeof(uint32_t)};
    meshio_reader r;
    if (length == 0) return meshio_fail(error, error_size, "%s: empty file (not even a \"ply\" line)", path);
    newline_at_end = text[length - 1] == '\n'; /* before the header's newlines become NULs */
    /* the header, line by line, up to end_header */
    for (;; line_number++) {
        char *end = (char *)memchr(p, '\n', (size_t)(text_end - p)), *word[6], *s;
        int words = 0, k;
        if (!end)
            return meshio_fail(error, error_size, "%s:%lu: the file ends before an end_header line", path,
                               p < text_end ? line_number : line_number - 1);
        if (memchr(p, '\0', (size_t)(end - p)))
            return meshio_fail(error, error_size, "%s:%lu: a NUL byte in the header", path, line_number);
        *end = '\0';
        for (s = p; words < 6;) { /* split into words on whitespace */
            while (*s && isspace((unsigned char)*s)) s++;
            if (!*s) break;
            word[words++] = s;
            while (*s && !isspace((unsigned char)*s)) s++;
            if (*s) *s++ = '\0';
        }
        if (words && strcmp(word[0], "comment") != 0 && strcmp(word[0], "obj_info") != 0)
            for (s = p; s < end; s++)
                if (*s && !isspace((unsigned char)*s) && !(*s > 0x20 && *s < 0x7f))
                    return meshio_fail(error, error_size, "%s:%lu: a byte that is not printable ASCII (0x%02x) in the "
                                       "header", path, line_number, (unsigned)(unsigned char)*s);
        if (line_number == 1) {
            if (words != 1 || strcmp(word[0], "ply") != 0)
                return meshio_fail(error, error_size, "%s:1: not a PLY file (the first line is not \"ply\")", path);
        } else if (words == 0 || strcmp(word[0], "comment") == 0 || strcmp(word[0], "obj_info") == 0) {
            /* nothing to read */
        } else if (strcmp(word[0], "end_header") == 0 && words == 1) {
            body = end + 1;
            break;
        } else if (strcmp(word[0], "format") == 0) {
            if (format >= 0) return meshio_fail(error, error_size, "%s:%lu: a second format line", path, line_number);
            if (words != 3)
                return meshio_fail(error, error_size, "%s:%lu: \"format TYPE VERSION\" expected", path, line_number);
            if (strcmp(word[1], "ascii") == 0) format = MESHIO_ASCII;
            else if (strcmp(word[1], "binary_little_endian") == 0) format = MESHIO_LITTLE;
            else if (strcmp(word[1], "binary_big_endian") == 0) format = MESHIO_BIG;
            else
                return meshio_fail(error, error_size, "%s:%lu: unknown format \"%s\"", path, line_number,
                                   meshio_token(token, word[1], NULL));
            if (strcmp(word[2], "1.0") != 0)
                return meshio_fail(error, error_size, "%s:%lu: unsupported PLY version \"%s\" (only 1.0 is known)", path,
                                   line_number, meshio_token(token, word[2], NULL));
        } else if (strcmp(word[0], "element") == 0) {
            meshio_element *el = &elements[element_count];
            int counted;
            if (element_count == 16) return meshio_fail(error, error_size, "%s:%lu: more than 16 elements", path, line_number);
            if (words != 3) return meshio_fail(error, error_size, "%s:%lu: \"element NAME COUNT\" expected", path, line_number);
            if (strlen(word[1]) > 31)
                return meshio_fail(error, error_size, "%s:%lu: element name \"%s\" longer than 31 characters", path,
                                   line_number, meshio_token(token, word[1], NULL));
            for (k = 0; k < element_count; k++)
                if (strcmp(elements[k].name, word[1]) == 0)
                    return meshio_fail(error, error_size, "%s:%lu: a second element %s", path, line_number, word[1]);
            memset(el, 0, sizeof *el);
            strcpy(el->name, word[1]);
            el->line = line_number;
            counted = meshio_ply_count(word[2], &el->count);
            if (counted == 0)
                return meshio_fail(error, error_size, "%s:%lu: bad element count \"%s\" (expected digits only)", path,
                                   line_number, meshio_token(token, word[2], NULL));
            if (counted < 0)
                return meshio_fail(error, error_size, "%s:%lu: element count %s is too large", path, line_number,
                                   meshio_token(token, word[2], NULL));
            if (strcmp(el->name, "vertex") == 0) vertex_element = element_count;
            element_count++;
        } else if (strcmp(word[0], "property") == 0) {
            meshio_element *el = element_count ? &elements[element_count - 1] : NULL;
            meshio_property *prop;
            const char *name;
            if (!el) return meshio_fail(error, error_size, "%s:%lu: a property before any element", path, line_number);
            if (el->property_count == 16)
                return meshio_fail(error, error_size, "%s:%lu: more than 16 properties", path, line_number);
            prop = &el->properties[el->property_count];
            memset(prop, 0, sizeof *prop);
            if (words >= 2 && strcmp(word[1], "list") == 0) {
                if (words != 5)
                    return meshio_fail(error, error_size, "%s:%lu: \"property list COUNT_TYPE TYPE NAME\" expected",
                                       path, line_number);
                prop->count_type = meshio_ply_type(word[2]);
                prop->type = meshio_ply_type(word[3]);
                if (!prop->count_type || !prop->type || (prop->count_type > 0 && (prop->count_type & 0x40)))
                    return meshio_fail(error, error_size, "%s:%lu: bad list types \"%s\" \"%s\" (an integer count type, "
                                       "any value type)", path, line_number, meshio_token(token, word[2], NULL),
                                       meshio_token(token2, word[3], NULL));
                name = word[4];
            } else {
                if (words != 3)
                    return meshio_fail(error, error_size, "%s:%lu: \"property TYPE NAME\" expected", path, line_number);
                prop->type = meshio_ply_type(word[1]);
                if (!prop->type)
                    return meshio_fail(error, error_size, "%s:%lu: unknown property type \"%s\"", path, line_number,
                                       meshio_token(token, word[1], NULL));
                name = word[2];
            }
            if (strlen(name) > 31)
                return meshio_fail(error, error_size, "%s:%lu: property name \"%s\" longer than 31 characters", path,
                                   line_number, meshio_token(token, name, NULL));
            for (k = 0; k < el->property_count; k++)
                if (strcmp(el->properties[k].name, name) == 0)
                    return meshio_fail(error, error_size, "%s:%lu: a second property %s in element %s", path,
                                       line_number, name, el->name);
            strcpy(prop->name, name);
            el->property_count++;
        } else {
            return meshio_fail(error, error_size, "%s:%lu: unexpected header line \"%s\"", path, line_number,
                               meshio_token(token, word[0], NULL));
        }
        p = end + 1;
    }
    if (format < 0) return meshio_fail(error, error_size, "%s:%lu: no format line before end_header", path, line_number);
    /* what each property is for */
    for (e = 0; e < element_count; e++) {
        meshio_element *el = &elements[e];
        int is_vertex = strcmp(el->name, "vertex") == 0, is_face = strcmp(el->name, "face") == 0, seen = 0, k;
        for (k = 0; k < el->property_count; k++) {
            meshio_property *prop = &el->properties[k];
            const char *n = prop->name;
            prop->role = -1;
            if (is_vertex && !prop->count_type && n[1] == '\0' && n[0] >= 'x' && n[0] <= 'z') prop->role = n[0] - 'x';
            if (is_face && prop->count_type && (strcmp(n, "vertex_indices") == 0 || strcmp(n, "vertex_index") == 0)) {
                if (seen & 8)
                    return meshio_fail(error, error_size, "%s:%lu: element face has both vertex_indices and vertex_index",
                                       path, el->line);
                prop->role = 3;
            }
            if (prop->role >= 0) seen |= 1 << prop->role;
        }
        if (is_vertex && seen != 7)
            return meshio_fail(error, error_size, "%s:%lu: element vertex lacks one of the scalar properties x, y, z",
                               path, el->line);
        if (is_face && vertex_element > e)
            return meshio_fail(error, error_size, "%s:%lu: element face before element vertex (not supported)", path,
                               el->line);
        if (is_face && !seen)
            return meshio_fail(error, error_size, "%s:%lu: element face has no list property vertex_indices", path,
                               el->line);
    }
    r.path = path;
    r.start = (const unsigned char *)text; /* offsets count from the file's first byte */
    r.p = r.value = (const unsigned char *)body;
    r.end = (const unsigned char *)text_end;
    r.format = format;
    r.line = r.value_line = line_number + 1;
    r.newline_at_end = newline_at_end;
    for (e = 0; e < element_count; e++) {
        meshio_element *el = &elements[e];
        int k, got;
        unsigned long i;
        if (e == vertex_element) vertex_total = el->count;
        if (el->property_count == 0) continue; /* holds no bytes, however many it claims */
        for (i = 0; i < el->count; i++) {
            float xyz[3] = {0, 0, 0};
            for (k = 0; k < el->property_count; k++) {
                const meshio_property *prop = &el->properties[k];
                double value;
                if (prop->count_type) {
                    double n;
                    unsigned long j;
                    if ((got = meshio_read_value(&r, prop->count_type, &n)) <= 0) goto unread;
                    if (!(n >= 0 && n <= 4294967295.0 && n == floor(n)) ||
                        (format == MESHIO_ASCII && !meshio_fits(prop->count_type, n))) {
                        meshio_body_fail(&r, error, error_size, "list count %s of %s %lu is not a whole number that "
                                         "fits its type %s", meshio_value_text(token, &r, prop->count_type, n),
                                         el->name, i, meshio_type_name(prop->count_type));
                        goto done;
                    }
                    poly.count = 0;
                    for (j = 0; j < (unsigned long)n; j++) {
                        uint32_t index;
                        if ((got = meshio_read_value(&r, prop->type, &value)) <= 0) goto unread;
                        if (prop->role != 3) continue;
                        if (value != floor(value) || (format == MESHIO_ASCII && !meshio_fits(prop->type, value))) {
                            meshio_body_fail(&r, error, error_size, "vertex index %s of face %lu is not a whole number "
                                             "that fits its type %s", meshio_value_text(token, &r, prop->type, value),
                                             i, meshio_type_name(prop->type));
                            goto done;
                        }
                        if (!(value >= 0 && value < (double)vertex_total && value <= 4294967295.0)) {
                            meshio_body_fail(&r, error, error_size, "vertex index %s of face %lu out of range "
                                             "(%lu vertices)", meshio_value_text(token, &r, prop->type, value), i,
                                             vertex_total);
                            goto done;
                        }
                        index = (uint32_t)value;
                        if (!meshio_push(&poly, &index)) goto oom;
                    }
                    if (prop->role == 3) {
                        if (poly.count < 3) {
                            meshio_body_fail(&r, error, error_size, "face %lu has %lu vertices, at least 3 needed", i,
                                             (unsigned long)poly.count);
                            goto done;
                        }
                        if (!meshio_fan(&indices, (const uint32_t *)poly.data, poly.count)) goto oom;
                    }
                } else {
                    if ((got = meshio_read_value(&r, prop->type, &value)) <= 0) goto unread;
                    if (prop->role >= 0 && prop->role < 3) {
                        if (format == MESHIO_ASCII && !meshio_fits(prop->type, value)) {
                            meshio_body_fail(&r, error, error_size, "coordinate %s of vertex %lu does not fit its type %s",
                                             meshio_value_text(token, &r, prop->type, value), i,
                                             meshio_type_name(prop->type));
                            goto done;
                        }
                        if (!meshio_coordinate_ok(value)) {
                            meshio_body_fail(&r, error, error_size, "coordinate %s of vertex %lu is not finite or "
                                             "beyond 1e30", meshio_value_text(token, &r, prop->type, value), i);
                            goto done;
                        }
                        xyz[prop->role] = (float)value;
                    }
                }
            }
            if (e == vertex_element)
                for (k = 0; k < 3; k++)
                    if (!meshio_push(&vertices, &xyz[k])) goto oom;
            continue;
        unread:
            if (got == 0)
                meshio_body_fail(&r, error, error_size, "truncated: the file ends inside %s %lu of %lu (property %s)",
                                 el->name, i, el->count, el->properties[k].name);
            else
                meshio_body_fail(&r, error, error_size, "malformed: \"%s\" is not a number (%s %lu of %lu, property %s)",
                                 meshio_token(token, (const char *)r.value, text_end), el->name, i, el->count,
                                 el->properties[k].name);
            goto done;
        }
    }
    if (format == MESHIO_ASCII) {
        while (r.p < r.end && isspace(*r.p)) {
            if (*r.p == '\n') r.line++;
            r.p++;
        }
        if (r.p < r.end) {
            r.value = r.p;
            r.value_line = r.line;
            meshio_body_fail(&r, error, error_size, "unexpected \"%s\" after the last element",
                             meshio_token(token, (const char *)r.p, text_end));
            goto done;
        }
    }
    ok = meshio_finish(path, &vertices, &indices, out, error, error_size);
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
    memset(out, 0, sizeof *out);
    if ((length >= 3 && memcmp(text, "ply", 3) == 0) || meshio_has_extension(name, ".ply"))
        return meshio_load_ply(name, text, length, out, error, error_size);
    return meshio_load_obj(name, text, length, out, error, error_size);
}

static inline int meshio_parse(const char *name, const void *data, size_t size, scene_mesh *out, char *error,
                               size_t error_size)
{
    char *text = size < (size_t)-1 ? (char *)MESHIO_MALLOC(size + 1) : NULL;
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
