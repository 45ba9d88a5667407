/* examples/scenes.h - small deterministic procedural scenes for the examples
   and the tests of manylods.  Header-only, C99, no dependency on manylods.h.

   Every scene is a scene_mesh: indexed triangles with per-vertex positions,
   and (where the scene has them) normals and linear RGB colours, 3 floats
   each.  Triangles are counter-clockwise seen from the side their normal
   points to.  Free a scene with scene_free().  Functions return 0 when
   malloc fails (the mesh is then empty), 1 otherwise.

       scene_mesh s;
       scene_uv_sphere(&s, 1.0f, 16, 32);
       ... s.positions, s.vertex_count, s.indices, s.index_count ...
       scene_free(&s);
*/
#ifndef MANYLODS_SCENES_H
#define MANYLODS_SCENES_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct scene_mesh {
    float *positions;      /* 3 per vertex */
    float *normals;        /* 3 per vertex, or NULL */
    float *colors;         /* 3 per vertex, or NULL */
    uint32_t *indices;     /* 3 per triangle */
    uint32_t vertex_count;
    uint32_t index_count;
} scene_mesh;

#define SCENE_PI 3.14159265358979323846

/* ------------------------------------------------------ random numbers */

/* splitmix64: a tiny deterministic generator; *state is any seed. */
static inline uint64_t scene_rng_next(uint64_t *state)
{
    uint64_t z = (*state += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double scene_rng_double(uint64_t *state)
{
    return (double)(scene_rng_next(state) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [lo, hi). */
static inline float scene_rng_range(uint64_t *state, float lo, float hi)
{
    return lo + (hi - lo) * (float)scene_rng_double(state);
}

/* ------------------------------------------------------------ storage */

static inline void scene_free(scene_mesh *s)
{
    free(s->positions);
    free(s->normals);
    free(s->colors);
    free(s->indices);
    memset(s, 0, sizeof *s);
}

static inline int scene_alloc(scene_mesh *s, uint32_t vertices, uint32_t indices, int normals, int colors)
{
    memset(s, 0, sizeof *s);
    s->positions = (float *)malloc(sizeof(float) * 3 * (vertices ? vertices : 1));
    s->normals = normals ? (float *)malloc(sizeof(float) * 3 * (vertices ? vertices : 1)) : NULL;
    s->colors = colors ? (float *)malloc(sizeof(float) * 3 * (vertices ? vertices : 1)) : NULL;
    s->indices = (uint32_t *)malloc(sizeof(uint32_t) * (indices ? indices : 1));
    if (!s->positions || !s->indices || (normals && !s->normals) || (colors && !s->colors)) {
        scene_free(s);
        return 0;
    }
    s->vertex_count = vertices;
    s->index_count = indices;
    return 1;
}

static inline void scene_set3(float *a, uint32_t i, double x, double y, double z)
{
    a[3 * i + 0] = (float)x;
    a[3 * i + 1] = (float)y;
    a[3 * i + 2] = (float)z;
}

/* A colour that varies smoothly with the position. */
static inline void scene_color_from_position(scene_mesh *s)
{
    uint32_t i;
    for (i = 0; i < s->vertex_count && s->colors; i++) {
        const float *p = s->positions + 3 * i;
        scene_set3(s->colors, i, 0.5 + 0.5 * sin(p[0] * 2.0), 0.5 + 0.5 * sin(p[1] * 2.0 + 1.0),
                   0.5 + 0.5 * sin(p[2] * 2.0 + 2.0));
    }
}

/* Add triangle (a, b, c), flipped if needed so that its geometric normal
   agrees with the vertex normal of a. */
static inline void scene_emit_oriented(scene_mesh *s, uint32_t *k, uint32_t a, uint32_t b, uint32_t c)
{
    const float *p = s->positions, *n = s->normals + 3 * a;
    double e1[3], e2[3], cr[3];
    int i;
    for (i = 0; i < 3; i++) {
        e1[i] = (double)p[3 * b + i] - p[3 * a + i];
        e2[i] = (double)p[3 * c + i] - p[3 * a + i];
    }
    cr[0] = e1[1] * e2[2] - e1[2] * e2[1];
    cr[1] = e1[2] * e2[0] - e1[0] * e2[2];
    cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
    s->indices[(*k)++] = a;
    if (cr[0] * n[0] + cr[1] * n[1] + cr[2] * n[2] >= 0.0) {
        s->indices[(*k)++] = b;
        s->indices[(*k)++] = c;
    } else {
        s->indices[(*k)++] = c;
        s->indices[(*k)++] = b;
    }
}

/* -------------------------------------------------------------- scenes */

/* UV sphere around the origin: stacks >= 2 rings from +y to -y, slices >= 3
   around y; 2 * slices * (stacks - 1) triangles, none degenerate.  Normals
   point outwards; colours vary with the position. */
static inline int scene_uv_sphere(scene_mesh *s, float radius, uint32_t stacks, uint32_t slices)
{
    uint32_t i, j, k = 0, row = slices + 1;
    if (!scene_alloc(s, (stacks + 1) * row, 6 * slices * (stacks - 1), 1, 1)) return 0;
    for (i = 0; i <= stacks; i++) {
        double theta = SCENE_PI * i / stacks;
        double st = (i == 0 || i == stacks) ? 0.0 : sin(theta);
        double ct = i == 0 ? 1.0 : i == stacks ? -1.0 : cos(theta);
        for (j = 0; j <= slices; j++) {
            double phi = j == slices ? 0.0 : 2.0 * SCENE_PI * j / slices;
            double n[3];
            n[0] = st * cos(phi);
            n[1] = ct;
            n[2] = st * sin(phi);
            scene_set3(s->normals, i * row + j, n[0], n[1], n[2]);
            scene_set3(s->positions, i * row + j, radius * n[0], radius * n[1], radius * n[2]);
        }
    }
    for (i = 0; i < stacks; i++) {
        for (j = 0; j < slices; j++) {
            uint32_t a = i * row + j, b = a + row;
            if (i != 0) scene_emit_oriented(s, &k, a, a + 1, b);          /* not at the north pole */
            if (i != stacks - 1) scene_emit_oriented(s, &k, a + 1, b + 1, b); /* nor the south pole */
        }
    }
    s->index_count = k;
    scene_color_from_position(s);
    return 1;
}

/* Torus around the y axis: ring radius R, tube radius r, nu x nv quads. */
static inline int scene_torus(scene_mesh *s, float R, float r, uint32_t nu, uint32_t nv)
{
    uint32_t i, j, k = 0, row = nv + 1;
    if (!scene_alloc(s, (nu + 1) * row, 6 * nu * nv, 1, 1)) return 0;
    for (i = 0; i <= nu; i++) {
        double u = i == nu ? 0.0 : 2.0 * SCENE_PI * i / nu;
        for (j = 0; j <= nv; j++) {
            double v = j == nv ? 0.0 : 2.0 * SCENE_PI * j / nv;
            double n[3];
            n[0] = cos(v) * cos(u);
            n[1] = sin(v);
            n[2] = cos(v) * sin(u);
            scene_set3(s->normals, i * row + j, n[0], n[1], n[2]);
            scene_set3(s->positions, i * row + j, (R + r * cos(v)) * cos(u), r * sin(v),
                       (R + r * cos(v)) * sin(u));
        }
    }
    for (i = 0; i < nu; i++) {
        for (j = 0; j < nv; j++) {
            uint32_t a = i * row + j, b = a + row;
            scene_emit_oriented(s, &k, a, a + 1, b);
            scene_emit_oriented(s, &k, a + 1, b + 1, b);
        }
    }
    scene_color_from_position(s);
    return 1;
}

/* The unit square [0,1]^2 in the plane z = 0, two triangles, normal +z. */
static inline int scene_unit_square(scene_mesh *s)
{
    static const uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    uint32_t i;
    if (!scene_alloc(s, 4, 6, 1, 1)) return 0;
    scene_set3(s->positions, 0, 0, 0, 0);
    scene_set3(s->positions, 1, 1, 0, 0);
    scene_set3(s->positions, 2, 1, 1, 0);
    scene_set3(s->positions, 3, 0, 1, 0);
    for (i = 0; i < 4; i++) {
        scene_set3(s->normals, i, 0, 0, 1);
        scene_set3(s->colors, i, s->positions[3 * i], s->positions[3 * i + 1], 0.5);
    }
    memcpy(s->indices, idx, sizeof idx);
    return 1;
}

/* Append an axis-aligned box (4 vertices and 2 triangles per face, flat
   normals) facing outwards, or inwards when inward != 0. */
static inline void scene_add_box(scene_mesh *s, const float lo[3], const float hi[3], int inward, const float color[3])
{
    uint32_t face, c;
    for (face = 0; face < 6; face++) {
        uint32_t axis = face / 2, a1 = (axis + 1) % 3, a2 = (axis + 2) % 3, base = s->vertex_count;
        double sign = (face & 1) ? 1.0 : -1.0, n[3] = {0, 0, 0};
        n[axis] = inward ? -sign : sign;
        for (c = 0; c < 4; c++) {
            float p[3];
            p[axis] = (face & 1) ? hi[axis] : lo[axis];
            p[a1] = (c == 1 || c == 2) ? hi[a1] : lo[a1];
            p[a2] = (c >= 2) ? hi[a2] : lo[a2];
            scene_set3(s->positions, base + c, p[0], p[1], p[2]);
            scene_set3(s->normals, base + c, n[0], n[1], n[2]);
            scene_set3(s->colors, base + c, color[0], color[1], color[2]);
        }
        s->vertex_count += 4;
        scene_emit_oriented(s, &s->index_count, base, base + 1, base + 2);
        scene_emit_oriented(s, &s->index_count, base, base + 2, base + 3);
    }
}

/* A closed room [-2,2] x [0,3] x [-2,2] with inward faces, holding three
   boxes with outward faces (one of them floating). */
static inline int scene_room(scene_mesh *s)
{
    static const float box[4][2][3] = {{{-2, 0, -2}, {2, 3, 2}},
                                       {{-1.5f, 0, -1.5f}, {-0.5f, 1, -0.5f}},
                                       {{0.5f, 0, 0.25f}, {1.25f, 1.75f, 1.0f}},
                                       {{-0.25f, 1.5f, -1.0f}, {0.25f, 2.0f, -0.5f}}};
    static const float color[4][3] = {{0.8f, 0.8f, 0.8f}, {0.9f, 0.2f, 0.1f}, {0.1f, 0.3f, 0.9f}, {0.2f, 0.8f, 0.3f}};
    int b;
    if (!scene_alloc(s, 4 * 24, 4 * 36, 1, 1)) return 0;
    s->vertex_count = 0;
    s->index_count = 0;
    for (b = 0; b < 4; b++) scene_add_box(s, box[b][0], box[b][1], b == 0, color[b]);
    return 1;
}

/* count unconnected triangles with vertices in [-1,1]^3 and random colours,
   no normals.  Every 10th triangle has zero area exactly (a repeated
   vertex, or three points on a line parallel to the x axis), every 7th is a
   sliver (height 1e-4 times its length). */
static inline int scene_soup(scene_mesh *s, uint32_t count, uint64_t seed)
{
    uint32_t t, i;
    if (!scene_alloc(s, 3 * count, 3 * count, 0, 1)) return 0;
    for (t = 0; t < count; t++) {
        float *p = s->positions + 9 * t;
        for (i = 0; i < 9; i++) p[i] = scene_rng_range(&seed, -1.0f, 1.0f);
        if (t % 10 == 3) {
            memcpy(p + 6, p, 3 * sizeof(float));
        } else if (t % 10 == 8) {
            p[4] = p[1];
            p[5] = p[2];
            p[7] = p[1];
            p[8] = p[2];
        } else if (t % 7 == 5) {
            for (i = 0; i < 3; i++) p[6 + i] = 0.5f * (p[i] + p[3 + i]);
            p[7] += 1e-4f * (float)fabs(p[3] - p[0]) + 1e-6f;
        }
        for (i = 0; i < 3; i++) {
            s->indices[3 * t + i] = 3 * t + i;
            scene_set3(s->colors, 3 * t + i, scene_rng_double(&seed), scene_rng_double(&seed),
                       scene_rng_double(&seed));
        }
    }
    return 1;
}

/* A smooth deformation at time t of the same topology: a twist around the y
   axis (angle 0.6 t y) and a sideways bend, with normals (when both pointers
   are non-NULL) rotated by the twist.  t = 0 gives the rest positions. */
static inline void scene_deform(const scene_mesh *rest, float t, float *out_positions, float *out_normals)
{
    uint32_t i;
    for (i = 0; i < rest->vertex_count; i++) {
        const float *p = rest->positions + 3 * i;
        double a = 0.6 * t * p[1], c = cos(a), sn = sin(a);
        double bend = 0.15 * sin(t) * p[1] * p[1];
        scene_set3(out_positions, i, c * p[0] - sn * p[2] + bend, p[1] + 0.05 * sin(0.7 * t) * p[0],
                   sn * p[0] + c * p[2]);
        if (out_normals && rest->normals) {
            const float *n = rest->normals + 3 * i;
            scene_set3(out_normals, i, c * n[0] - sn * n[2], n[1], sn * n[0] + c * n[2]);
        }
    }
}

/* Total area of the mesh's triangles (double precision). */
static inline double scene_area(const scene_mesh *s)
{
    double sum = 0.0;
    uint32_t t, i;
    for (t = 0; t + 2 < s->index_count; t += 3) {
        const float *a = s->positions + 3 * s->indices[t], *b = s->positions + 3 * s->indices[t + 1],
                    *c = s->positions + 3 * s->indices[t + 2];
        double e1[3], e2[3], cr[3];
        for (i = 0; i < 3; i++) {
            e1[i] = (double)b[i] - a[i];
            e2[i] = (double)c[i] - a[i];
        }
        cr[0] = e1[1] * e2[2] - e1[2] * e2[1];
        cr[1] = e1[2] * e2[0] - e1[0] * e2[2];
        cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
        sum += 0.5 * sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    }
    return sum;
}

#endif /* MANYLODS_SCENES_H */
